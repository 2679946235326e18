"""The one door from Python into the kernel: pack a `KernelRun`, run it, build the result."""

from __future__ import annotations

import time

import numpy as np

from frictiondisk.kernel import driver
from frictiondisk.kernel import energy as ken
from frictiondisk.kernel import model as km
from frictiondisk.kernel.record import KernelRun
from frictiondisk.model.limits import MAX_RECORD_ROWS, record_rows_limit
from frictiondisk.outcome.classify import revolution
from frictiondisk.outcome.horizon import horizon_of
from frictiondisk.outcome.result import SimulationResult, Trajectory
from frictiondisk.outcome.shakedown_verdict import applies as bound_applies
from frictiondisk.simulation.common import build_result, initial_state

METHOD_CODES = {"rodas4": 0, "rodas4-fixed": 1}
STICK_RULE_CODES = {"contacts": driver.RULE_CONTACTS, "corotation": driver.RULE_COROTATION}


def record_capacity(t_span: float, dt_out: float, limit: int = MAX_RECORD_ROWS) -> int:
    """Rows to reserve for a recorded trajectory over t_span [s]: every dt_out sample plus
    room for the rows written at switches (or 200 000 step ends when dt_out = 0), at most
    `limit` (limits.record_rows_limit: wide rows get fewer)."""
    if dt_out <= 0.0:
        return min(200_000, limit)
    return int(min(limit, t_span / dt_out + 50_000))


def pack_parameters(config) -> tuple[np.ndarray, np.ndarray]:
    """Parameter vector p (kernel/model.py indices) and contacts pts (N, 3): body-frame
    point [m] and relative weight N w_i of each contact (kernel/model.py)."""
    par = config.params
    con = config.contact
    n = config.n_contacts
    p = np.zeros(km.N_PARAMS)
    p[km.P_MU] = par.mu
    p[km.P_OMEGA] = par.omega_m
    p[km.P_CS] = par.c_s
    p[km.P_BETAS] = par.beta_s
    p[km.P_MS] = par.m_s
    p[km.P_JS] = par.J_s
    p[km.P_BETAB] = par.beta_b
    p[km.P_XMS] = par.x_ms
    # Distributed contact: stiffness, damping and normal force spread over the points by
    # their weights (docs/model.md section 3); pts[:, 2] scales these means.
    p[km.P_CI] = con.stiffness / n
    p[km.P_BETAI] = config.contact_damping / n
    p[km.P_FNI] = par.F_n / n
    p[km.P_EPS] = con.eps
    p[km.P_STR_R] = con.stribeck.r
    p[km.P_STR_VS] = con.stribeck.v_s
    p[km.P_STR_DELTA] = con.stribeck.delta
    p[km.P_ROT] = 1.0 if config.scene == "disk" else 0.0
    pts = np.column_stack((config.contact_positions(), config.contact_weights()))
    return p, np.ascontiguousarray(pts, dtype=np.float64)


def initial_modes(p: np.ndarray, pts: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Stick iff |k_i(0)| < F_St,i (docs/model.md section 3)."""
    modes = np.empty(pts.shape[0], dtype=np.int8)
    stick = np.int8(km.STICK)  # a mode as the kernel holds it: one compiled switch_value
    for i in range(pts.shape[0]):
        modes[i] = km.STICK if km.switch_value(p, pts, y, i, stick) < 0.0 else km.SLIDE
    return modes


def simulate(
    config, record: bool = False, dt_out: float = 0.0, *, dense_lu: bool = False
) -> SimulationResult:
    """Run one scene and classify its long-term motion.

    record: keep the trajectory (dense-output samples every dt_out seconds plus every
    switching instant; dt_out = 0 records every step). dense_lu: factor the Rosenbrock
    stage matrix densely, O(N^3) per step, instead of by its arrow structure, O(N)
    (kernel/linalg.py); for comparisons (benchmarks/bench_layouts.py) only.
    """
    if config.numerics.method == "coulomb":
        from frictiondisk.simulation.coulomb import simulate_coulomb

        return simulate_coulomb(config, record=record, dt_out=dt_out)
    if config.numerics.method == "scipy-radau":
        from frictiondisk.simulation.radau import simulate_radau

        return simulate_radau(config, record=record, dt_out=dt_out)
    return _simulate_numba(config, record, dt_out, dense_lu)


def _simulate_numba(config, record: bool, dt_out: float, dense_lu: bool) -> SimulationResult:
    num = config.numerics
    p, pts = pack_parameters(config)
    y0 = initial_state(config)
    modes = initial_modes(p, pts, y0)
    rev = revolution(config.params.omega_m)

    limit = record_rows_limit(y0.shape[0], pts.shape[0])
    cap = record_capacity(horizon_of(config) + rev, dt_out, limit) if record else 1
    run = KernelRun.allocate(y0, modes, cap, p, pts)

    iopt = run.iopt
    iopt[driver.O_METHOD] = METHOD_CODES[num.method]
    iopt[driver.O_MAX_STEPS] = num.max_steps
    iopt[driver.O_MAX_EVENTS] = num.max_events
    iopt[driver.O_CYCLE_COUNT] = num.cycle_count
    iopt[driver.O_CONVERGE] = 1 if num.mode == "converge" else 0
    iopt[driver.O_STOP_ON_STICK] = 1 if num.stop_on_stick else 0
    iopt[driver.O_RECORD] = 1 if record else 0
    iopt[driver.O_STICK_RULE] = STICK_RULE_CODES[num.stick_rule]
    iopt[driver.O_DENSE_LU] = 1 if dense_lu else 0
    iopt[driver.O_OBSERVE] = 1 if num.evidence == "observe" else 0
    iopt[driver.O_BOUND] = 1 if bound_applies(config) else 0
    fopt = run.fopt
    fopt[driver.O_RTOL] = num.rtol
    fopt[driver.O_ATOL] = num.atol
    fopt[driver.O_DT] = num.dt
    fopt[driver.O_HMAX] = num.h_max
    fopt[driver.O_HORIZON] = horizon_of(config)
    fopt[driver.O_CYCLE_TOL] = num.cycle_tol
    fopt[driver.O_HOLD] = rev
    fopt[driver.O_DT_OUT] = dt_out
    fopt[driver.O_BUDGET] = horizon_of(config) * num.horizon_budget

    energy_0 = float(ken.stored_energy(p, pts, y0))
    wall0 = time.perf_counter()
    run.run()  # the kernel integrates run.y in place: it holds the final state afterwards
    wall = time.perf_counter() - wall0
    energy = energy_balance(
        energy_0,
        float(ken.stored_energy(p, pts, run.y)),
        run.work_in,
        run.work_dissipated,
    )

    trajectory = None
    if record:
        nq = 3 if config.scene == "disk" else 2
        trajectory = Trajectory.from_states(*run.recorded_rows(), nq, run.truncated)
    return build_result(config, run, wall, trajectory, energy)


def energy_balance(
    energy_0: float, energy_end: float, work_in: float, work_diss: float
) -> dict[str, float]:
    """Energy diagnostic of a run (kernel/energy.py): `energy_in`, `energy_dissipated` [J]
    and the relative residual of  E(t_end) - E(0) = W_in - W_diss.

    The residual is divided by the largest of |W_in|, W_diss and |E(t_end) - E(0)|: the
    size of the terms being balanced. Starting from rest the stored energy can be 0, and
    on a limit cycle W_in and W_diss grow with the run while E stays bounded, so dividing
    by E would say nothing; the largest term makes it an error per joule put through the
    system, comparable across run lengths. It is 0 when no energy moves at all.
    """
    delta = energy_end - energy_0
    scale = max(abs(work_in), abs(work_diss), abs(delta))
    residual = (delta - work_in + work_diss) / scale if scale > 0.0 else 0.0
    return {
        "energy_in": work_in,
        "energy_dissipated": work_diss,
        "energy_residual": residual,
    }
