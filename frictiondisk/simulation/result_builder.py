"""A finished run's `RunBuffers` -> its `SimulationResult` (shared by every integrator with
the loop's records: rodas4 in simulation/rodas_method.py, scipy-radau in radau.py).

It gathers the facts (verdict/facts.py) from the records and lets the label
(verdict/label.py) say what the run is; it decides nothing itself.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from frictiondisk.kernel import monitor
from frictiondisk.kernel.records import OWN_RING, REV_RING
from frictiondisk.simulation.buffers import RunBuffers
from frictiondisk.simulation.result import SimulationResult, Trajectory
from frictiondisk.verdict.facts import Evidence, Revolutions, RunFacts
from frictiondisk.verdict.horizon import revolution
from frictiondisk.verdict.label import BOUND_RECONSIDERS, label
from frictiondisk.verdict.motion_evidence import MotionEvidence, OwnScene
from frictiondisk.verdict.params import VerdictParams
from frictiondisk.verdict.reserve import friction_reserve
from frictiondisk.verdict.shakedown_bound import floor_reserve


def build_result(
    config,
    run: RunBuffers,
    wall: float,
    trajectory: Trajectory | None,
    energy: dict[str, float] | None = None,
    *,
    verdict: VerdictParams,
) -> SimulationResult:
    """Label a finished run from its `RunBuffers` (shared by every integrator): status,
    t_end [s], final state, the motion and verdict records, counters and, when
    run.revolutions is not None, the revolution ring and total plastic slip. An integrator
    without the ring supports stick_rule contacts only. wall: run time [s]. energy: the
    fields of `energy_balance`; None (an integrator without the diagnostic) leaves them
    NaN. verdict: the thresholds the run was judged by.
    """
    values = run.values()
    facts = run_facts(config, run, verdict, values)
    named = label(facts, config, verdict)
    motion, counters = values["motion"], values["counters"]
    R1 = float(motion["r1"])
    return SimulationResult(
        outcome=named.outcome,
        reason=named.reason,
        R1=R1,
        t_R1=float(motion["t_r1"]),
        size=named.size,
        a=named.a,
        n_transitions=int(motion["switches"]),
        stick_fraction=float(facts.frac_all),
        t_end=run.t_end,
        n_steps=counters["steps"],
        n_rejected=counters["rejected"],
        n_refused=counters["refused"],
        cycle_converged=named.converged,
        wall_s=wall,
        method=config.numerics.method,
        trajectory=trajectory,
        revolutions=facts.revolution_log,
        sections=section_log(run.phases, motion),
        own_section=facts.own_rows,
        slip_total=run.slip_total,
        reserve=friction_reserve(config, R1),
        decided_by=named.rule,
        **_revolution_measures(facts.revs),
        **_motion_measures(named.motion),
        **(energy or {}),
    )


def run_facts(
    config, run: RunBuffers, verdict: VerdictParams, values: Mapping | None = None
) -> RunFacts:
    """What the label reads of a finished run (verdict/facts.py); values: run.values(),
    if already read."""
    values = run.values() if values is None else values
    num = config.numerics
    rev = revolution(config.params.omega_m)
    window = num.window_revs * rev
    t_end = run.t_end
    motion, vs = values["motion"], values["verdict"]
    frac_all, frac_any = monitor.window_fractions(
        run.motion, run.phases, run.intervals, t_end, window
    )
    ring = run.revolutions is not None
    own = run.own_steps is not None
    floor = math.nan
    if run.status in BOUND_RECONSIDERS:
        floor = float(floor_reserve(run.p, run.pts)) if run.p is not None else math.nan
    return RunFacts(
        status=run.status,
        t_end=t_end,
        stuck_for=float(monitor.stuck_for(run.motion, t_end)),
        hold=rev,
        window=(max(0.0, t_end - window), t_end),
        frac_all=float(frac_all),
        frac_any=float(frac_any),
        converge_mode=num.mode == "converge",
        max_steps=num.max_steps,
        max_events=num.max_events,
        stick_rule=num.stick_rule,
        revs=_revolutions(config, run, values) if ring else None,
        evidence=evidence_of(vs) if ring else None,
        steps=values["counters"]["steps"],
        revolution_log=revolution_log(run.revolutions, motion) if ring else None,
        floor=floor,
        radius_end=math.hypot(run.y[0], run.y[1]),
        cycle_converged=bool(vs["agree"] >= num.cycle_count),
        cycle_size=float(motion["size"]),
        cycle_excess=float(motion["a"]),
        own_rows=own_log(run.own_steps, values["own"]) if own else None,
        own_scene=own_scene(config, run, motion) if own else None,
    )


def own_scene(config, run: RunBuffers, motion: Mapping | np.void) -> OwnScene:
    """What the own section's evidence needs of the scene (verdict/motion_evidence.py);
    motion: the MOTION record or its values."""
    p = config.params
    rules = run.rules
    omega0 = math.sqrt(p.c_s / p.m_s) if p.c_s > 0.0 else abs(p.omega_m)
    return OwnScene(
        omega0=omega0 if omega0 > 0.0 else 1.0,
        arm=float(motion["arm"]),
        eps=config.contact.eps,
        n_contacts=int(run.modes.shape[0]),
        cycle_tol=float(rules["cycle_tol"]),
        atol=float(rules["atol"]),
        rtol=float(rules["rtol"]),
        observe=bool(rules["observe"]),
        tangential_rate=p.beta_s / (2.0 * p.m_s),
    )


MOTION_MEASURES = (
    "own_period",
    "mean_radius",
    "amplitude",
    "spin_rate",
    "floquet_ratio",
    "decay_rate",
    "r_eq_x",
    "r_eq_y",
    "r_eq",
    "r_eq_angle",
    "envelope_period",
    "envelope_depth",
)


def _motion_measures(motion: MotionEvidence | None) -> dict[str, float]:
    """The pure-sliding motion's measures (NaN where none was read)."""
    return {name: getattr(motion, name) if motion else math.nan for name in MOTION_MEASURES}


def _revolutions(config, run: RunBuffers, values: Mapping) -> Revolutions:
    """The label's view of the revolution ring (NaN measures before one revolution);
    values: run.values()."""
    motion, vs = values["motion"], values["verdict"]
    n = int(motion["n_rev"])
    last = run.revolutions[(n - 1) % REV_RING] if n > 0 else None
    nan = math.nan
    return Revolutions(
        count=n,
        slip=float(last["slip"]) if n > 0 else nan,
        drift=float(last["drift_r"]) if n > 0 else nan,
        spin_drift=float(last["drift_phi"]) if n > 0 and config.scene == "disk" else nan,
        decay=float(vs["decay"]),
        decay_se=float(vs["decay_se"]),
        remaining=float(vs["remaining"]),
        limit=float(vs["limit"]),
        limit_spread=float(vs["limit_spread"]),
        on_orbit=bool(n > 0 and last["any_stuck"]),
        settling=bool(vs["budget_spent"]),
        tol=float(vs["slip_tol"]),
    )


def evidence_of(vs: Mapping | np.void) -> Evidence:
    """The section evidence of the run's last check (verdict/section_evidence.py); vs: the
    VERDICT record or its values."""
    return Evidence(
        kind=int(vs["evidence"]),
        source=int(vs["ev_source"]),
        distance=float(vs["ev_distance"]),
        ratio=float(vs["ev_ratio"]),
        ratio_bound=float(vs["ev_ratio_bound"]),
        limit=float(vs["ev_limit"]),
        lag=int(vs["ev_lag"]),
        points=int(vs["ev_points"]),
        sliding_revs=int(vs["sliding_revs"]),
        envelope_revs=int(vs["envelope_revs"]),
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


def ring_rows(ring: np.ndarray, written: int, keep: int) -> np.ndarray:
    """A copy of the last `keep` of the `written` rows a ring buffer took (row k went to
    k mod len(ring)), oldest first: at most two slices, no index list."""
    size = ring.shape[0]
    keep = min(written, keep, size)
    start = (written - keep) % size
    if start + keep <= size:
        return copy_rows(ring[start : start + keep])
    return np.concatenate((ring[start:], ring[: start + keep - size]))


def copy_rows(rows: np.ndarray) -> np.ndarray:
    """A copy of contiguous record rows, made as one copy of their bytes (numpy copies a
    record array field by field: 3 us for a few rows, against under 2 us)."""
    out = np.empty(rows.shape[0], dtype=rows.dtype)
    out.view(np.uint8)[:] = rows.view(np.uint8)
    return out


def revolution_log(revs: np.ndarray, motion: Mapping | np.void) -> np.ndarray:
    """The kept rows of the revolution ring (kernel/records.py REVOLUTION), oldest first."""
    return ring_rows(revs, int(motion["n_rev"]), REV_RING)


def own_log(steps: np.ndarray, own: Mapping | np.void) -> np.ndarray:
    """The kept rows of the own section (kernel/records.py OWN_STEP), oldest first."""
    return ring_rows(steps, int(own["n"]), OWN_RING)


def section_log(phases: np.ndarray, motion: Mapping | np.void, keep: int = 256) -> np.ndarray:
    """The last `keep` completed whole-body sticking phases (kernel/records.py PHASE),
    oldest first."""
    return ring_rows(phases, int(motion["n_phases"]), keep)
