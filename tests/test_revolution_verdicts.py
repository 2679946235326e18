"""The sliding evidence read from the revolution ring (frictiondisk/verdict/sliding.py) on
synthetic rings taken from the well-posedness study's seed 6 scene 32, a pin near its
grazing sticking circle: what a watching run showed, and what the old rule made of it."""

from __future__ import annotations

import numpy as np
from verdict_records import DEFAULT
from verdict_records import ring as _ring

from frictiondisk.verdict.corotation import slip_slope
from frictiondisk.verdict.sliding import steady_sliding

EPS_T = 1.01e-8  # the pin's eps T [m]: slip per revolution that counts as none

# mu = 0.07647, default numerics: slip per revolution [m] at revolutions 4 ... 11, sliding
# as a whole; it falls by half over the eight, alternating on the way, and the pin sticks
# for good at 292 s.
ALTERNATING_FALL = [3.681e-2, 2.443e-2, 2.497e-2, 1.769e-2, 1.785e-2, 1.394e-2, 1.333e-2, 1.125e-2]
# A sliding orbit whose slip wanders about a level, for the 16 revolutions that the lowest
# slip of the newest 8 needs to be compared with the lowest of the 8 before.
WANDERING = [1.20e-2, 1.31e-2, 1.18e-2, 1.27e-2, 1.22e-2, 1.33e-2, 1.19e-2, 1.26e-2] * 2


def ring(slips, *, any_stuck, ever_all, still):
    """(rules, motion, vs, revs) of a pin's revolution ring holding `slips` [m], oldest first,
    with the given flags."""
    times = 10.0 * np.arange(1, len(slips) + 1)
    rules, motion, vs, revs = _ring(
        slips,
        any_stuck=any_stuck,
        ever_all=ever_all,
        still=still,
        times=times,
        slip_tol=EPS_T,
        arm=0.0,  # a pin
        atol=1e-8,
        rtol=1e-5,
    )
    return rules, motion, vs, revs


def test_a_slip_that_falls_while_alternating_is_no_sliding_state():
    """The mean of successive log ratios (-0.12 ± 0.07 a revolution) did not establish the
    fall, so the old rule read a sliding orbit at 121 s. The slope over all eight
    revolutions does (-0.15 a revolution)."""
    rules, motion, vs, revs = ring(ALTERNATING_FALL, any_stuck=False, ever_all=False, still=False)
    assert not steady_sliding(DEFAULT, rules, motion, vs, revs)
    slope, se = slip_slope(motion, revs, DEFAULT["slide_revs"])
    assert slope + DEFAULT["verdict_z"] * se < 0.0 < -slope


def test_a_slip_that_wanders_about_a_level_is_a_sliding_state():
    rules, motion, vs, revs = ring(WANDERING, any_stuck=False, ever_all=False, still=False)
    assert steady_sliding(DEFAULT, rules, motion, vs, revs)
    assert (vs["sliding_revs"], vs["envelope_revs"]) == (16, 8)


def test_a_wandering_slip_is_no_sliding_state_before_two_windows_of_it():
    rules, motion, vs, revs = ring(WANDERING[:15], any_stuck=False, ever_all=False, still=False)
    assert not steady_sliding(DEFAULT, rules, motion, vs, revs)
