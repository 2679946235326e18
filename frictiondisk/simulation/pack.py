"""From a validated scene to the step loop's inputs: the parameter record, the contacts,
the initial state and modes, the integrator's options and the verdict's rules."""

from __future__ import annotations

import numpy as np

from frictiondisk.kernel import model as km
from frictiondisk.kernel.records import one
from frictiondisk.kernel.steppers import RODAS4, RODAS5
from frictiondisk.model.limits import MAX_RECORD_ROWS
from frictiondisk.verdict.horizon import horizon_of, revolution
from frictiondisk.verdict.records import RULES
from frictiondisk.verdict.shakedown_verdict import applies as bound_applies


def record_capacity(t_span: float, dt_out: float, limit: int = MAX_RECORD_ROWS) -> int:
    """Rows to reserve for a recorded trajectory over t_span [s]: every dt_out sample plus
    room for the rows written at switches (or 200 000 step ends when dt_out = 0), at most
    `limit` (limits.record_rows_limit: wide rows get fewer)."""
    if dt_out <= 0.0:
        return min(200_000, limit)
    return int(min(limit, t_span / dt_out + 50_000))


def pack_parameters(config) -> tuple[np.void, np.ndarray]:
    """The parameter record p (kernel/model.py PARAMETERS) and contacts pts (N, 3): body-frame
    point [m] and relative weight N w_i of each contact (kernel/model.py)."""
    par = config.params
    con = config.contact
    n = config.n_contacts
    p = one(km.PARAMETERS)
    p["mu"] = par.mu
    p["omega_m"] = par.omega_m
    p["c_s"] = par.c_s
    p["beta_s"] = par.beta_s
    p["m_s"] = par.m_s
    p["J_s"] = par.J_s
    p["beta_b"] = par.beta_b
    p["x_ms"] = par.x_ms
    # Distributed contact: stiffness, damping and normal force spread over the points by
    # their weights (docs/model.md section 3); pts[:, 2] scales these means.
    p["c_i"] = con.stiffness / n
    p["beta_i"] = config.contact_damping / n
    p["F_n_i"] = par.F_n / n
    p["eps"] = con.eps
    p["stribeck_r"] = con.stribeck.r
    p["stribeck_v_s"] = con.stribeck.v_s
    p["stribeck_delta"] = con.stribeck.delta
    p["disk"] = config.scene == "disk"
    pts = np.column_stack((config.contact_positions(), config.contact_weights()))
    return p, np.ascontiguousarray(pts, dtype=np.float64)


def initial_state(config) -> np.ndarray:
    """r = (x_ms + x0, y0), r' = (vx0, vy0), phi = 0, phi' = phidot0, Z = 0 (docs/model.md section 5)."""
    par = config.params
    nq = 3 if config.scene == "disk" else 2
    y = np.zeros(2 * nq + 2 * config.n_contacts)
    y[0] = par.x_ms + par.x0
    y[1] = par.y0
    y[nq] = par.vx0
    y[nq + 1] = par.vy0
    if nq == 3:
        y[nq + 2] = par.phidot0
    return y


def initial_modes(p: np.void, pts: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Stick iff |k_i(0)| < F_St,i (docs/model.md section 3)."""
    modes = np.empty(pts.shape[0], dtype=np.int8)
    stick = np.int8(km.STICK)  # a mode as the kernel holds it: one compiled switch_value
    for i in range(pts.shape[0]):
        modes[i] = km.STICK if km.switch_value(p, pts, y, i, stick) < 0.0 else km.SLIDE
    return modes


def fill_options(options: np.void, num, record: bool, dt_out: float, dense_lu: bool) -> None:
    """The integrator's options (kernel/records.py OPTIONS) from the scene's numerics."""
    options["fixed_step"] = num.method == "rodas4-fixed"
    options["stepper"] = RODAS5 if num.method == "rodas5" else RODAS4
    options["dense_lu"] = dense_lu
    options["record"] = record
    options["rtol"] = num.rtol
    options["atol"] = num.atol
    options["dt"] = num.dt
    options["h_max"] = num.h_max
    options["dt_out"] = dt_out
    options["max_steps"] = num.max_steps
    options["max_events"] = num.max_events


def fill_rules(rules: np.void, config) -> None:
    """What the scene asks of the verdict (frictiondisk/verdict/records.py RULES)."""
    num = config.numerics
    horizon = horizon_of(config)
    rules["corotation"] = num.stick_rule == "corotation"
    rules["converge"] = num.mode == "converge"
    rules["stop_on_stick"] = num.stop_on_stick
    rules["observe"] = num.evidence == "observe" or num.observe_until > 0.0
    rules["watch"] = num.observe_until if num.evidence == "extrapolate" else 0.0
    rules["follow_until"] = num.follow_departures_until
    rules["bound"] = bound_applies(config)
    rules["hold"] = revolution(config.params.omega_m)
    rules["horizon"] = horizon
    rules["budget"] = horizon * num.horizon_budget
    rules["cycle_tol"] = num.cycle_tol
    rules["cycle_count"] = num.cycle_count
    rules["rtol"] = num.rtol
    rules["atol"] = num.atol


def new_rules(config) -> np.void:
    """A RULES record filled for `config` (fill_rules)."""
    rules = one(RULES)
    fill_rules(rules, config)
    return rules
