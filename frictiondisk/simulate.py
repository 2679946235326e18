"""The one door from Python into the kernel: pack arrays, run, build the result."""

from __future__ import annotations

import math
import time

import numpy as np

from .classify import RunFacts, classify, revolution
from .kernel import driver
from .kernel import energy as ken
from .kernel import model as km
from .kernel import monitor as mon
from .result import SimulationResult, Trajectory

METHOD_CODES = {"rodas4": 0, "rodas4-fixed": 1}


def record_capacity(t_span: float, dt_out: float) -> int:
    """Rows to reserve for a recorded trajectory over t_span [s]: every dt_out sample plus
    room for the rows written at switches (or 200 000 step ends when dt_out = 0)."""
    if dt_out <= 0.0:
        return 200_000
    return int(min(2_000_000, t_span / dt_out + 50_000))


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
    # their weights (MODEL.md 3); pts[:, 2] scales these means.
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


def initial_state(config) -> np.ndarray:
    """r = (x_ms + x0, y0), r' = (vx0, vy0), phi = 0, phi' = phidot0, Z = 0 (MODEL.md 5)."""
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


def initial_modes(p: np.ndarray, pts: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Stick iff |k_i(0)| < F_St,i (MODEL.md section 3)."""
    modes = np.empty(pts.shape[0], dtype=np.int8)
    for i in range(pts.shape[0]):
        modes[i] = km.STICK if km.switch_value(p, pts, y, i, km.STICK) < 0.0 else km.SLIDE
    return modes


def horizon_of(config) -> float:
    num = config.numerics
    return num.t_max if num.mode == "converge" else num.t_decide


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
        from .coulomb import simulate_coulomb

        return simulate_coulomb(config, record=record, dt_out=dt_out)
    if config.numerics.method == "scipy-radau":
        from .crosscheck import simulate_radau

        return simulate_radau(config, record=record, dt_out=dt_out)
    return _simulate_numba(config, record, dt_out, dense_lu)


def _simulate_numba(config, record: bool, dt_out: float, dense_lu: bool) -> SimulationResult:
    num = config.numerics
    p, pts = pack_parameters(config)
    y0 = initial_state(config)
    modes = initial_modes(p, pts, y0)
    rev = revolution(config.params.omega_m)

    iopt = np.zeros(driver.N_IOPT, dtype=np.int64)
    iopt[driver.O_METHOD] = METHOD_CODES[num.method]
    iopt[driver.O_MAX_STEPS] = num.max_steps
    iopt[driver.O_MAX_EVENTS] = num.max_events
    iopt[driver.O_CYCLE_COUNT] = num.cycle_count
    iopt[driver.O_CONVERGE] = 1 if num.mode == "converge" else 0
    iopt[driver.O_STOP_ON_STICK] = 1 if num.stop_on_stick else 0
    iopt[driver.O_RECORD] = 1 if record else 0
    iopt[driver.O_DENSE_LU] = 1 if dense_lu else 0
    fopt = np.zeros(driver.N_FOPT)
    fopt[driver.O_RTOL] = num.rtol
    fopt[driver.O_ATOL] = num.atol
    fopt[driver.O_DT] = num.dt
    fopt[driver.O_HMAX] = num.h_max
    fopt[driver.O_HORIZON] = horizon_of(config)
    fopt[driver.O_CYCLE_TOL] = num.cycle_tol
    fopt[driver.O_HOLD] = rev
    fopt[driver.O_DT_OUT] = dt_out

    cap = record_capacity(horizon_of(config) + rev, dt_out) if record else 1
    rec_t = np.empty(cap)
    rec_y = np.empty((cap, y0.shape[0]))
    rec_m = np.empty((cap, pts.shape[0]), dtype=np.int8)
    mf = np.empty(mon.N_MF)
    mi = np.empty(mon.N_MI, dtype=np.int64)
    ring_all = np.empty((mon.RING, 2))
    ring_any = np.empty((mon.RING, 2))
    out_i = np.zeros(driver.N_OUT_I, dtype=np.int64)
    out_f = np.zeros(ken.N_OUT_F)
    energy_0 = float(ken.stored_energy(p, pts, y0))

    wall0 = time.perf_counter()
    state = y0  # the kernel integrates in place: this holds the final state afterwards
    status, t_end = driver.run(
        p,
        pts,
        state,
        modes,
        iopt,
        fopt,
        rec_t,
        rec_y,
        rec_m,
        mf,
        mi,
        ring_all,
        ring_any,
        out_i,
        out_f,
    )
    wall = time.perf_counter() - wall0
    energy = energy_balance(
        energy_0,
        float(ken.stored_energy(p, pts, state)),
        float(out_f[ken.E_W_IN]),
        float(out_f[ken.E_W_DISS]),
    )

    trajectory = None
    if record:
        k = int(out_i[driver.C_RECORDED])
        truncated = bool(out_i[driver.C_TRUNCATED])
        nq = 3 if config.scene == "disk" else 2
        trajectory = Trajectory.from_states(rec_t[:k], rec_y[:k], rec_m[:k], nq, truncated)
    counters = {
        "n_steps": int(out_i[driver.C_STEPS]),
        "n_rejected": int(out_i[driver.C_REJECTED]),
        "n_refused": int(out_i[driver.C_REFUSED]),
    }
    return build_result(
        config,
        int(status),
        float(t_end),
        state,
        mf,
        mi,
        ring_all,
        ring_any,
        counters,
        wall,
        trajectory,
        energy,
    )


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


def build_result(
    config,
    status,
    t_end,
    y_end,
    mf,
    mi,
    ring_all,
    ring_any,
    counters,
    wall,
    trajectory,
    energy: dict[str, float] | None = None,
) -> SimulationResult:
    """Classify a finished run from its monitor state (shared by every integrator).

    energy: the fields of `energy_balance`; None (an integrator without the diagnostic)
    leaves them NaN.
    """
    num = config.numerics
    rev = revolution(config.params.omega_m)
    window = num.window_revs * rev
    frac_all, frac_any = mon.window_fractions(mf, mi, ring_all, ring_any, t_end, window)
    facts = RunFacts(
        status=status,
        t_end=t_end,
        stuck_for=float(mon.stuck_for(mf, mi, t_end)),
        hold=rev,
        window=(max(0.0, t_end - window), t_end),
        frac_all=float(frac_all),
        frac_any=float(frac_any),
        converge_mode=num.mode == "converge",
        max_steps=num.max_steps,
        max_events=num.max_events,
    )
    outcome, reason = classify(facts)
    radius_end = math.hypot(y_end[0], y_end[1])
    size = math.nan
    a = math.nan
    if outcome == "stick":
        size = radius_end
    elif outcome == "stick_slip" and mon.cycle_converged(mi):
        # only a converged cycle has a size (MODEL.md 6); before that the sticking segments
        # still creep outwards, and their radius says nothing about the final cycle
        size = float(mf[mon.F_SIZE])
        a = float(mf[mon.F_A])
    return SimulationResult(
        outcome=outcome,
        reason=reason,
        R1=float(mf[mon.F_R1]),
        t_R1=float(mf[mon.F_T_R1]),
        size=size,
        a=a,
        n_transitions=int(mi[mon.I_NTRANS]),
        stick_fraction=float(frac_all),
        t_end=t_end,
        n_steps=counters["n_steps"],
        n_rejected=counters["n_rejected"],
        n_refused=counters["n_refused"],
        cycle_converged=bool(mon.cycle_converged(mi)),
        wall_s=wall,
        method=num.method,
        trajectory=trajectory,
        **(energy or {}),
    )
