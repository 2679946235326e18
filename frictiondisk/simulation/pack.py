"""From a validated scene to the step loop's inputs: the parameter record, the contacts,
the initial state and modes, the integrator's options and the verdict's rules."""

from __future__ import annotations

import numpy as np

from frictiondisk.kernel import model as km
from frictiondisk.kernel.records import OPTIONS, filled
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
    # Distributed contact: stiffness, damping and normal force spread over the points by
    # their weights (docs/model.md section 3); pts[:, 2] scales these means.
    p = filled(
        km.PARAMETERS,
        mu=par.mu,
        omega_m=par.omega_m,
        c_s=par.c_s,
        beta_s=par.beta_s,
        m_s=par.m_s,
        J_s=par.J_s,
        beta_b=par.beta_b,
        x_ms=par.x_ms,
        c_i=con.stiffness / n,
        beta_i=config.contact_damping / n,
        F_n_i=par.F_n / n,
        eps=con.eps,
        stribeck_r=con.stribeck.r,
        stribeck_v_s=con.stribeck.v_s,
        stribeck_delta=con.stribeck.delta,
        disk=config.scene == "disk",
    )
    positions, weights = config.contact_layout()
    pts = np.empty((n, 3))
    pts[:, :2] = positions
    pts[:, 2] = weights
    return p, pts


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


def new_options(num, record: bool, dt_out: float, dense_lu: bool) -> np.void:
    """The integrator's options (kernel/records.py OPTIONS) from the scene's numerics."""
    return filled(
        OPTIONS,
        fixed_step=num.method == "rodas4-fixed",
        stepper=RODAS5 if num.method == "rodas5" else RODAS4,
        dense_lu=dense_lu,
        record=record,
        rtol=num.rtol,
        atol=num.atol,
        dt=num.dt,
        h_max=num.h_max,
        dt_out=dt_out,
        max_steps=num.max_steps,
        max_events=num.max_events,
    )


def new_rules(config) -> np.void:
    """What the scene asks of the verdict (frictiondisk/verdict/records.py RULES)."""
    num = config.numerics
    horizon = horizon_of(config)
    return filled(
        RULES,
        corotation=num.stick_rule == "corotation",
        converge=num.mode == "converge",
        stop_on_stick=num.stop_on_stick,
        observe=num.evidence == "observe" or num.observe_until > 0.0,
        watch=num.observe_until if num.evidence == "extrapolate" else 0.0,
        follow_until=num.follow_departures_until,
        bound=bound_applies(config),
        hold=revolution(config.params.omega_m),
        horizon=horizon,
        budget=horizon * num.horizon_budget,
        cycle_tol=num.cycle_tol,
        cycle_count=num.cycle_count,
        rtol=num.rtol,
        atol=num.atol,
    )
