"""How long a certification check watches a bracket end before it may name a not-stick
motion (certify.py). Pure Python.

A verdict that an extrapolation decided (verdict/deciding_rule.py EXTRAPOLATED) is tested
on later motion, not repeated: its check decides only on what it sees until
`certify.watch` times the decision time of the run that decided the end. The end of a
motion boundary (`between` other than not_stick | stick) is watched at least
`MOTION_WATCH` times that decision time whatever decided it: a motion named at one horizon
(a slow spiral, a ring's ripple) is checked on a longer one, not only at a stricter rtol.
"""

from __future__ import annotations

from frictiondisk.model.search_settings import Certify
from frictiondisk.tasks.jump_search.bisection import UNDETERMINED, Bisection
from frictiondisk.tasks.jump_search.sides import Between
from frictiondisk.verdict.deciding_rule import EXTRAPOLATED

# a check of a motion boundary's end watches at least this many times the decision time of
# the run that decided it (a longer horizon, not only a stricter rtol)
MOTION_WATCH = 2.0


def check_watch(search: Bisection, mu: float, certify: Certify, between: Between) -> float:
    """How long [s] the check of `search`'s bracket end `mu` watches (module docstring): at
    least as long as the search it checks watched."""
    watched = search.settings.watch
    if not certify.enabled:
        return watched
    decided = [r for r in search.runs if r.request.mu == mu and r.outcome != UNDETERMINED]
    if not decided:
        return watched
    t_end = float(decided[-1].result.get("t_end", 0.0))
    if not between.is_default:
        watched = max(watched, max(MOTION_WATCH, certify.watch) * t_end)
    if certify.watch and not certify.observe:
        if decided[-1].result.get("decided_by") in EXTRAPOLATED:
            watched = max(watched, certify.watch * t_end)
    return watched
