"""The label after the run: the machine's final state and the run's facts -> outcome,
reason and measures (docs/model.md section 6). The one place that decides an outcome: the
rules' verdict (`_classify`), then Melan and Koiter for a braked disk
(verdict/shakedown_verdict.py), then the rule that a stick needs steps. Reasons keep their
wording: runs.nc stores them.
"""

from __future__ import annotations

import dataclasses
import math

from frictiondisk.kernel import status as st

from . import records as rc
from .deciding_rule import deciding_rule
from .facts import Revolutions, RunFacts
from .motion_evidence import MotionEvidence, judge
from .outcomes import CREEP, SLIDE, STICK, STICK_SLIP, UNDETERMINED
from .params import VerdictParams
from .shakedown_verdict import decide as bound_decides

ERROR_REASONS = {
    st.MAX_STEPS: "work budget exhausted: numerics.max_steps = {max_steps} steps at t = {t:.6g} s",
    st.MAX_EVENTS: "work budget exhausted: numerics.max_events = {max_events} switches at t = {t:.6g} s",
    st.STEP_TOO_SMALL: "integrator failed: step size underflow at t = {t:.6g} s",
    st.NONFINITE: "integrator failed: non-finite state at t = {t:.6g} s",
    st.ZENO: "integrator failed: endless switching at one instant (Zeno) at t = {t:.6g} s",
}
# where the run ended by a verdict that Melan and Koiter may reconsider (a braked disk)
BOUND_RECONSIDERS = (rc.AT_HORIZON, rc.COROTATING, rc.CREEPING, rc.SHAKEN_DOWN, rc.BOUND_DECIDED)


@dataclasses.dataclass(frozen=True)
class Label:
    """What a run is: its outcome (verdict/outcomes.py OUTCOMES), why, and its measures."""

    outcome: str
    reason: str
    size: float  # sticking-circle radius (stick) or a converged cycle's segment radius [m]
    a: float  # largest excess of a converged cycle's sliding over its segment [m]
    rule: str = ""  # the rule that decided it (verdict/deciding_rule.py DECIDING_RULES)
    converged: bool = False  # the motion settled (a cycle, a rest state, a modulation)
    motion: MotionEvidence | None = None  # the pure-sliding motion's evidence and measures


def label(facts: RunFacts, config, vp: VerdictParams) -> Label:
    """The outcome, reason and measures of a finished run (module docstring)."""
    outcome, reason = _classify(facts, vp)
    rule = deciding_rule(facts)
    if facts.status in BOUND_RECONSIDERS:
        stopped = facts.status == rc.BOUND_DECIDED
        ruled = (outcome, reason)
        outcome, reason = bound_decides(
            config, outcome, reason, facts.revolution_log, facts.floor, vp, stopped
        )
        rule = rule if (outcome, reason) == ruled else "bound"
    if outcome == STICK and facts.steps == 0:
        # sticking for a revolution takes time, hence steps: a stick at t = 0 contradicts
        # itself (a revolution shorter than round-off); never report it
        outcome, reason = UNDETERMINED, "stick decided after 0 steps: the inputs are degenerate"
        rule = "error"
    motion = None
    if _refinable(facts, outcome):
        motion = judge(facts.own_rows, facts.own_scene, vp)
        outcome, reason = _refine(outcome, reason, motion)
        rule = motion.rule or rule  # a trend read ahead named the motion
    size = math.nan
    a = math.nan
    if outcome == STICK:
        size = facts.radius_end
    elif outcome == STICK_SLIP and facts.cycle_converged:
        # only a converged cycle has a size (docs/model.md section 6); before that the
        # sticking segments still creep outwards, and their radius says nothing about the
        # final cycle
        size = facts.cycle_size
        a = facts.cycle_excess
    converged = facts.cycle_converged or (
        motion is not None and motion.motion == outcome and motion.converged
    )
    return Label(outcome, reason, size, a, rule, converged, motion)


def _refinable(facts: RunFacts, outcome: str) -> bool:
    """Whether the own section may name the motion: a run that never stuck as a whole in
    its final window (`slide`). Where sticking and sliding alternate there, that is what the
    run has shown: `stick_slip`, whatever its section evidence (docs/model.md section 6)."""
    return facts.own_scene is not None and outcome == SLIDE


def _refine(outcome: str, reason: str, motion: MotionEvidence) -> tuple[str, str]:
    """(outcome, reason): the pure-sliding motion the own section shows, else `slide` with
    what the section showed (not stick, its motion not yet shown)."""
    if motion.motion:
        return motion.motion, f"{motion.reason} ({reason})"
    return outcome, f"{reason}; {motion.reason}"


def _rates(r: Revolutions) -> str:
    spin = "" if math.isnan(r.spin_drift) else f", spin drift {r.spin_drift:.3g} rad"
    return f"slip {r.slip:.3g} m, centre drift {r.drift:.3g} m{spin} per revolution"


def _trend(r: Revolutions) -> str:
    if math.isnan(r.decay):
        return "no slip trend (a revolution without slip)"
    return (
        f"slip per revolution changes by a factor exp({r.decay:.3g} \u00b1 {r.decay_se:.2g}) "
        "per revolution"
    )


def _classify(facts: RunFacts, vp: VerdictParams) -> tuple[str, str]:
    """(outcome, reason) of the rules; never guesses: anything unclear is `undetermined`."""
    if facts.status in ERROR_REASONS:
        reason = ERROR_REASONS[facts.status].format(
            t=facts.t_end, max_steps=facts.max_steps, max_events=facts.max_events
        )
        return UNDETERMINED, reason
    return _by_corotation(facts) or _by_window(facts, vp)


def _by_corotation(facts: RunFacts) -> tuple[str, str] | None:
    """(outcome, reason) where the co-rotation rule or the bound stopped the run, else None."""
    t = facts.t_end
    revs = facts.revs
    if facts.status == rc.COROTATING:
        how = (
            "it repeated within the integrator's tolerance, with every contact stuck "
            f"throughout or no slip above eps T = {revs.tol:.3g} m in the last revolutions"
            if revs.remaining == 0.0
            else f"shakedown: {_trend(revs)} towards a limit of "
            f"{revs.limit:.3g} m (estimates spread {revs.limit_spread:.2g} m) <= "
            f"eps T = {revs.tol:.3g} m (slip still to come {revs.remaining:.3g} m)"
        )
        return STICK, (
            f"co-rotates with the master without net slip at t = {t:.6g} s: last revolution "
            f"{_rates(revs)}; {how}"
        )
    if facts.status == rc.SHAKEN_DOWN:
        ev = facts.evidence
        if ev.kind == rc.EV_RIM:
            return STICK, f"sticks in the limit, seen at t = {t:.6g} s: {ev.describe()}"
        return STICK, (
            f"shakes down to co-rotation at t = {t:.6g} s: {ev.describe()} <= "
            f"eps T = {revs.tol:.3g} m a revolution (last revolution {_rates(revs)})"
        )
    if facts.status == rc.CREEPING:
        limit = (
            ""
            if math.isnan(revs.limit)
            else f", extrapolated limit {revs.limit:.3g} m, its estimates spread "
            f"{revs.limit_spread:.2g} m"
        )
        return CREEP, (
            f"ratchets on its small orbit at t = {t:.6g} s: {_rates(revs)}, not decaying "
            f"to zero ({_trend(revs)}{limit})"
        )
    if facts.status == rc.BOUND_DECIDED:
        # worded by verdict/shakedown_verdict.py, which reads the same reserves
        return UNDETERMINED, (
            f"the run stopped at t = {t:.6g} s for the shakedown bound, which then did not "
            "decide (a kernel and outcome mismatch)"
        )
    return None


def _by_window(facts: RunFacts, vp: VerdictParams) -> tuple[str, str]:
    """(outcome, reason) of the contacts rule, the converge test, the horizon budget and the
    final window with the section evidence."""
    t = facts.t_end
    revs = facts.revs
    # integrators without revolution measures apply the contacts rule (the pin only)
    contacts_rule = facts.stick_rule == "contacts" or revs is None
    if facts.status == rc.STICK_HELD or (contacts_rule and facts.stuck_for >= facts.hold):
        return STICK, (
            f"every contact stuck without interruption for one master revolution "
            f"({facts.hold:.6g} s) from t = {t - facts.stuck_for:.6g} s"
        )
    lo, hi = facts.window
    if facts.status == rc.CYCLE_FOUND:
        return STICK_SLIP, f"limit cycle with sticking and sliding converged at t = {t:.6g} s"
    if revs is not None and revs.settling:
        if facts.stick_rule == "corotation" and revs.count < vp.verdict_revs:
            where = (
                f"after {revs.count} whole revolutions ({vp.verdict_revs} are needed to "
                "tell stick, creep and stick_slip apart)"
            )
        elif revs.on_orbit and facts.stick_rule == "corotation":
            where = "on its small orbit, co-rotation not yet decided"
        else:
            evidence = facts.evidence.describe() if facts.evidence else "no evidence"
            where = f"without evidence that it will not stick: {evidence}"
        # the co-rotation rule reads a slip trend on the small orbit only
        trend = f"; {_trend(revs)}" if revs.on_orbit else ""
        return UNDETERMINED, (
            f"horizon budget reached at t = {t:.6g} s {where}: last revolution {_rates(revs)}"
            f"{trend} (raise numerics.horizon_budget or t_decide)"
        )
    why = ""
    if facts.evidence is not None and facts.evidence.kind == rc.EV_SHAKEDOWN:
        why = (
            f"; {facts.evidence.describe()}: co-rotation with grazing contacts, which "
            "stick_rule contacts does not count as stick"
        )
    elif facts.evidence is not None and facts.evidence.kind != rc.EV_NONE:
        why = f"; {facts.evidence.describe()}"
    if facts.frac_all == 0.0:
        # outcome, stick_fraction and size all mean whole-body sticking (every contact)
        partial = (
            f"; single contacts stuck {facts.frac_any:.3g} of it" if facts.frac_any > 0 else ""
        )
        return SLIDE, (
            f"the slave never stuck as a whole in the final window [{lo:.6g}, {hi:.6g}] s"
            f"{partial}{why}"
        )
    if facts.status == rc.AT_T_MAX:
        return UNDETERMINED, (
            f"limit cycle not converged by numerics.t_max = {t:.6g} s "
            f"(stick fraction {facts.frac_all:.3g} in the final window)"
        )
    if facts.status == rc.AT_HORIZON:
        return STICK_SLIP, (
            f"sticking and sliding alternate in the final window [{lo:.6g}, {hi:.6g}] s "
            f"(stick fraction {facts.frac_all:.3g}){why}"
        )
    return UNDETERMINED, f"unknown kernel status {facts.status} at t = {t:.6g} s"
