"""The friction reserve of a run: a signed, continuous companion of its verdict. Pure numpy.

A slave that sticks for good co-rotates with the master on the circle where it first
stuck as a whole, of radius R1. It keeps sticking if its static friction mu F_n covers
the demand of that circle (frictiondisk.verdict.admissibility: c_s |x_ms| + g R1 for a pin or a
disk without brake torque, Melan's shakedown demand with one). The reserve

    reserve = mu - demand(R1) / F_n   [1, units of mu]

is > 0 where the first sticking circle holds and < 0 where it breaks. R1 moves smoothly
with mu, so the reserve crosses zero at the jump of a point whose first sticking circle
decides it (docs/model.md section 7), nearly linearly. The search interpolates on it
(frictiondisk.tasks.jump_search.bisection); verdicts stay the ground truth, so a reserve that misleads (a
disk from rest, a jump decided by a later circle) costs runs, never a wrong mu*.
NaN where the slave never stuck as a whole.
"""

from __future__ import annotations

import math

from frictiondisk.verdict import admissibility as ad


def demand(config, radius: float) -> float:
    """Static friction force [N] that rigid co-rotation on a circle of `radius` [m] needs
    (the Melan shakedown demand; c_s |x_ms| + g R without brake torque)."""
    par = config.params
    case = ad.LoadCase.of(par, radius, par.beta_b if config.scene == "disk" else 0.0)
    if case.torque == 0.0:
        # a pure force: every layout shares it in proportion to its capacity
        return case.preload + case.g * radius
    return ad.shakedown_demand(case, config.contact_positions())


def friction_reserve(config, radius: float) -> float:
    """mu - demand(radius) / F_n [1]; NaN for a NaN radius (the slave never stuck)."""
    if not math.isfinite(radius):
        return math.nan
    return config.params.mu - demand(config, radius) / config.params.F_n
