"""The friction reserve's offset at the jump, learned from a finished point.
Pure Python.

The reserve (frictiondisk/verdict/reserve.py) is mu minus a rigid-contact demand, so near
the jump it runs at slope 1 in mu, but its zero is not mu*: contact compliance makes the
demand a fixed fraction too low, and the reserve at mu* reads `offset` x mu* (the pin at
the default contact stiffness: offset -2.6e-6 at every x_ms, the zero 46 tol above mu* at
x_ms = 0.14, tol 1e-8; docs/model.md section 7). A point that aims its probes at the
reserve's zero then lands that far from the jump and walks back. Where a finished point
shows the offset, later points correct their reserves by it (`BisectionSettings.reserve_offset`)
and aim at the jump instead. Verdicts alone move a bracket: a wrong offset costs runs,
never a wrong answer.
"""

from __future__ import annotations

import math

from frictiondisk.tasks.jump_search.runs import BisectionResult
from frictiondisk.verdict.outcomes import STICK


def learned_offset(result: BisectionResult | None, tol: float) -> float:
    """The reserve's offset at the jump per unit mu, (mu* - zero) / mu*, from a converged
    rising jump whose sticking end carries a reserve: its zero lies at mu_hi - reserve
    (slope 1). 0.0 where the result shows none, or where the offset at mu* is under tol
    (the zero then lies within the bracket's resolution of the jump, as the search
    assumes without it)."""
    if result is None or result.status != "converged" or not result.rising:
        return 0.0
    stick_end = result.end_result("hi")
    if stick_end is None or stick_end.get("outcome") != STICK:
        return 0.0
    reserve = stick_end.get("reserve")
    mu_star = result.mu_star
    if reserve is None or not math.isfinite(reserve) or mu_star <= 0:
        return 0.0
    offset = mu_star - (result.mu_hi - reserve)
    return offset / mu_star if abs(offset) >= tol else 0.0
