"""What every integrator shares (rodas4 in simulate.py, scipy-radau in radau.py): the
initial state and the result builder, which classifies a finished run from its
`KernelRun` (kernel/record.py). Kept apart from the dispatcher
`frictiondisk.simulation.simulate.simulate`, which imports the integrators, so that no
integrator imports its own dispatcher.
"""

from __future__ import annotations

import math

import numpy as np

from frictiondisk.kernel import monitor as mon
from frictiondisk.kernel import status as st
from frictiondisk.kernel.record import KernelRun
from frictiondisk.kernel.shakedown_bound import floor_reserve
from frictiondisk.outcome.classify import Evidence, Revolutions, RunFacts, classify, revolution
from frictiondisk.outcome.reserve import friction_reserve
from frictiondisk.outcome.result import SimulationResult, Trajectory
from frictiondisk.outcome.shakedown_verdict import decide as bound_decides


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


def build_result(
    config,
    run: KernelRun,
    wall: float,
    trajectory: Trajectory | None,
    energy: dict[str, float] | None = None,
) -> SimulationResult:
    """Classify a finished run from its `KernelRun` (shared by every integrator): status,
    t_end [s], final state, monitor state, counters and, when run.rv is not None, the
    revolution ring and total plastic slip. An integrator without the ring supports
    stick_rule contacts only. wall: run time [s]. energy: the fields of `energy_balance`;
    None (an integrator without the diagnostic) leaves them NaN.
    """
    num = config.numerics
    rev = revolution(config.params.omega_m)
    window = num.window_revs * rev
    t_end = run.t_end
    mf, mi = run.mf, run.mi
    frac_all, frac_any = mon.window_fractions(*run.monitor(), t_end, window)
    ring = run.rv is not None
    facts = RunFacts(
        status=run.status,
        t_end=t_end,
        stuck_for=float(mon.stuck_for(mf, mi, t_end)),
        hold=rev,
        window=(max(0.0, t_end - window), t_end),
        frac_all=float(frac_all),
        frac_any=float(frac_any),
        converge_mode=num.mode == "converge",
        max_steps=num.max_steps,
        max_events=num.max_events,
        stick_rule=num.stick_rule,
        revs=_revolutions(config, run) if ring else None,
        evidence=_evidence(mf, mi) if ring else None,
    )
    outcome, reason = classify(facts)
    rows = revolution_log(run.rv, mi) if ring else None
    if run.status in (
        st.HORIZON_REACHED,
        st.COROTATING,
        st.CREEPING,
        st.SHAKEN_DOWN,
        st.BOUND_DECIDED,
    ):
        stopped = run.status == st.BOUND_DECIDED
        floor = float(floor_reserve(run.p, run.pts)) if run.p is not None else math.nan
        outcome, reason = bound_decides(config, outcome, reason, rows, floor, stopped)
    revs = facts.revs
    if outcome == "stick" and run.steps == 0:
        # sticking for a revolution takes time, hence steps: a stick at t = 0 contradicts
        # itself (a revolution shorter than round-off); never report it (issue 14)
        outcome, reason = "undetermined", "stick decided after 0 steps: the inputs are degenerate"
    radius_end = math.hypot(run.y[0], run.y[1])
    size = math.nan
    a = math.nan
    if outcome == "stick":
        size = radius_end
    elif outcome == "stick_slip" and mon.cycle_converged(mi):
        # only a converged cycle has a size (docs/model.md section 6); before that the sticking segments
        # still creep outwards, and their radius says nothing about the final cycle
        size = float(mf[mon.F_SIZE])
        a = float(mf[mon.F_A])
    R1 = float(mf[mon.F_R1])
    return SimulationResult(
        outcome=outcome,
        reason=reason,
        R1=R1,
        t_R1=float(mf[mon.F_T_R1]),
        size=size,
        a=a,
        n_transitions=int(mi[mon.I_NTRANS]),
        stick_fraction=float(frac_all),
        t_end=t_end,
        n_steps=run.steps,
        n_rejected=run.rejected,
        n_refused=run.refused,
        cycle_converged=bool(mon.cycle_converged(mi)),
        wall_s=wall,
        method=num.method,
        trajectory=trajectory,
        revolutions=rows,
        sections=section_log(run.ring_all, mi),
        slip_total=run.slip_total,
        reserve=friction_reserve(config, R1),
        **_revolution_measures(revs),
        **(energy or {}),
    )


def _revolutions(config, run: KernelRun) -> Revolutions:
    """The classifier's view of the revolution ring (NaN measures before one revolution)."""
    mf, mi, rv = run.mf, run.mi, run.rv
    n = int(mi[mon.I_NREV])
    last = rv[(n - 1) % mon.REV_RING] if n > 0 else np.full(mon.N_RV, np.nan)
    return Revolutions(
        count=n,
        slip=float(last[mon.RV_SLIP]),
        drift=float(last[mon.RV_DRIFT_R]),
        spin_drift=float(last[mon.RV_DRIFT_PHI]) if config.scene == "disk" else math.nan,
        decay=float(mf[mon.F_LAMBDA]),
        decay_se=float(mf[mon.F_LAMBDA_SE]),
        remaining=float(mf[mon.F_REMAIN]),
        limit=float(mf[mon.F_S_INF]),
        limit_spread=float(mf[mon.F_S_INF_SPREAD]),
        on_orbit=bool(n > 0 and last[mon.RV_ANY_STUCK] == 1.0),
        settling=run.budget_spent,
        tol=float(mf[mon.F_SLIP_TOL]),
    )


def _evidence(mf: np.ndarray, mi: np.ndarray) -> Evidence:
    """The section evidence of the run's last check (kernel/sections.py)."""
    return Evidence(
        kind=int(mi[mon.I_EVIDENCE]),
        source=int(mi[mon.I_EV_SOURCE]),
        distance=float(mf[mon.F_EV_D]),
        ratio=float(mf[mon.F_EV_Q]),
        ratio_bound=float(mf[mon.F_EV_QUP]),
        limit=float(mf[mon.F_EV_LIMIT]),
        lag=int(mi[mon.I_EV_LAG]),
        points=int(mi[mon.I_EV_STEPS]),
    )


def _revolution_measures(revs: Revolutions | None) -> dict[str, float | int]:
    if revs is None:
        return {}
    return {
        "n_revolutions": revs.count,
        "slip_per_rev": revs.slip,
        "drift_per_rev": revs.drift,
        "spin_drift_per_rev": revs.spin_drift,
        "slip_decay": revs.decay,
        "slip_limit": revs.limit,
    }


def revolution_log(rv: np.ndarray, mi: np.ndarray) -> np.ndarray:
    """The kept rows of the revolution ring (monitor.RV_* columns), oldest first."""
    n = int(mi[mon.I_NREV])
    keep = min(n, mon.REV_RING)
    order = [(n - keep + j) % mon.REV_RING for j in range(keep)]
    return rv[order].copy()


def section_log(ring_all: np.ndarray, mi: np.ndarray, keep: int = 256) -> np.ndarray:
    """The last `keep` completed whole-body sticking phases (monitor.RA_* columns), oldest
    first."""
    n = int(mi[mon.I_RS_N])
    keep = min(n, keep, ring_all.shape[0])
    order = [(n - keep + j) % ring_all.shape[0] for j in range(keep)]
    return ring_all[order].copy()
