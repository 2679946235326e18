"""Which rule decided a run (runs.nc `decided_by`), from the facts the label reads.

Certification asks it (tasks/jump_search/certify.py): a verdict that rests on an
extrapolation (`EXTRAPOLATED`: a trend or a section read ahead to its end) is tested by a
stricter run that watches before it may extrapolate; a verdict on what the run showed (a
stick seen, every contact held, a bound) is re-run as before.
"""

from __future__ import annotations

import math

from . import records as rc
from .facts import RunFacts
from .outcomes import CREEP

EVIDENCE_RULES = {
    rc.EV_REPEAT: "repeat",
    rc.EV_CONTRACT: "contract",
    rc.EV_DEPART: "depart",
    rc.EV_SHAKEDOWN: "shakedown",
    rc.EV_CANNOT: "cannot",
    rc.EV_SLIDING: "sliding",
    rc.EV_GRAZE: "graze",
}
# the rules that read a trend or a section ahead to where it ends (docs/model.md section 7)
EXTRAPOLATED = frozenset(
    {
        "repeat",
        "contract",
        "depart",
        "shakedown",
        "sliding",
        "graze",
        "rim",
        "corotation_limit",
        "creep_limit",
        "envelope_trend",
        "amplitude_trend",
    }
)
BUDGET_RAN_OUT = "budget"  # undetermined: the run looked as far as its horizon budget lets it
INTEGRATOR_FAILED = "error"  # undetermined: the integrator failed or ran out of work
DECIDING_RULES = (
    "corotation",  # co-rotates without net slip, seen (every contact stuck and still, or no slip)
    "corotation_limit",  # the slip per revolution extrapolated to a limit <= eps T
    CREEP,  # named after the outcome it decides: the slip per revolution shown not to fall
    "creep_limit",  # ... extrapolated to a limit that keeps most of it
    "contacts",  # every contact stuck for one revolution (stick_rule contacts)
    "cycle",  # mode converge: the cycle's section points agreed
    "bound",  # Melan's or Koiter's bound (a braked disk)
    "rim",  # a Coulomb pin's slips carry it inward, onto its sticking disc (verdict/grazing.py)
    *EVIDENCE_RULES.values(),  # the section evidence at the horizon (verdict/horizon_evidence.py)
    "window",  # the final window without section evidence (stick_rule contacts)
    "envelope_trend",  # a pure-sliding motion named by its envelope's trend read ahead
    "amplitude_trend",  # ... by its size's trend read ahead (a spiral dying out or growing)
    BUDGET_RAN_OUT,  # undetermined: the horizon budget ran out
    INTEGRATOR_FAILED,  # undetermined: the integrator failed or ran out of work
)


def deciding_rule(facts: RunFacts) -> str:
    """The rule of DECIDING_RULES behind the machine's final state (before the bound's
    reconsideration, which the label names itself)."""
    status, revs = facts.status, facts.revs
    if status == rc.COROTATING:
        return "corotation" if revs.remaining == 0.0 else "corotation_limit"
    if status == rc.SHAKEN_DOWN:
        on_rim = facts.evidence is not None and facts.evidence.kind == rc.EV_RIM
        return "rim" if on_rim else "shakedown"
    if status == rc.CREEPING:
        return CREEP if math.isnan(revs.limit) else "creep_limit"
    if status == rc.BOUND_DECIDED:
        return "bound"
    if status == rc.STICK_HELD or (
        (facts.stick_rule == "contacts" or revs is None) and facts.stuck_for >= facts.hold
    ):
        return "contacts"
    if status == rc.CYCLE_FOUND:
        return "cycle"
    if status not in (rc.AT_HORIZON, rc.AT_T_MAX):
        return INTEGRATOR_FAILED
    if revs is not None and revs.settling:
        return BUDGET_RAN_OUT
    kind = facts.evidence.kind if facts.evidence is not None else rc.EV_NONE
    return EVIDENCE_RULES.get(kind, "window")
