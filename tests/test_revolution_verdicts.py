"""The sliding evidence read from the revolution ring (frictiondisk/kernel/verdict.py) on
synthetic rings taken from the well-posedness study's seed 6 scene 32, a pin near its
grazing sticking circle: what a watching run showed, and what the old rule made of it."""

from __future__ import annotations

import numpy as np

from frictiondisk.kernel import monitor_slots as ms
from frictiondisk.kernel import verdict as vd

EPS_T = 1.01e-8  # the pin's eps T [m]: slip per revolution that counts as none

# mu = 0.07647, default numerics: slip per revolution [m] at revolutions 4 ... 11, sliding
# as a whole; it falls by half over the eight, alternating on the way, and the pin sticks
# for good at 292 s.
ALTERNATING_FALL = [3.681e-2, 2.443e-2, 2.497e-2, 1.769e-2, 1.785e-2, 1.394e-2, 1.333e-2, 1.125e-2]
# A sliding orbit whose slip wanders about a level.
WANDERING = [1.20e-2, 1.31e-2, 1.18e-2, 1.27e-2, 1.22e-2, 1.33e-2, 1.19e-2, 1.26e-2]


def ring(slips, *, any_stuck, ever_all, still):
    """A revolution ring holding `slips` [m], oldest first, with the given flags."""
    rv = np.zeros((ms.REV_RING, ms.N_RV))
    n = len(slips)
    rv[:n, ms.RV_SLIP] = slips
    rv[:n, ms.RV_T] = 10.0 * np.arange(1, n + 1)
    rv[:n, ms.RV_ANY_STUCK] = float(any_stuck)
    rv[:n, ms.RV_EVER_ALL] = float(ever_all)
    rv[:n, ms.RV_STILL] = float(still)
    mf = np.full(ms.N_MF, np.nan)
    mf[ms.F_SLIP_TOL] = EPS_T
    mf[ms.F_ARM] = 0.0  # a pin
    mf[ms.F_ATOL] = 1e-8
    mf[ms.F_RTOL] = 1e-5
    mi = np.zeros(ms.N_MI, dtype=np.int64)
    mi[ms.I_NREV] = n
    return mf, mi, rv


def test_a_slip_that_falls_while_alternating_is_no_sliding_state():
    """The mean of successive log ratios (-0.12 ± 0.07 a revolution) did not establish the
    fall, so the old rule read a sliding orbit at 121 s. The slope over all eight
    revolutions does (-0.15 a revolution)."""
    mf, mi, rv = ring(ALTERNATING_FALL, any_stuck=False, ever_all=False, still=False)
    assert not vd.steady_sliding(mf, mi, rv)
    slope, se = vd._slip_slope(mi, rv, vd.SLIDE_REVS)
    assert slope + vd.VERDICT_Z * se < 0.0 < -slope


def test_a_slip_that_wanders_about_a_level_is_a_sliding_state():
    mf, mi, rv = ring(WANDERING, any_stuck=False, ever_all=False, still=False)
    assert vd.steady_sliding(mf, mi, rv)
