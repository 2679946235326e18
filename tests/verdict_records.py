"""Records for tests of the verdict's numba rules on synthetic data: a revolution ring, a
section sequence, and the motion, rules and verdict records around them (kernel/records.py,
frictiondisk/verdict/records.py), filled as a run would leave them."""

from __future__ import annotations

import numpy as np

from frictiondisk.kernel.records import MOTION, REV_RING, REVOLUTION, one
from frictiondisk.verdict.params import VerdictParams
from frictiondisk.verdict.records import RULES, VERDICT
from frictiondisk.verdict.section_sequence import SEQ_MAX

DEFAULT = VerdictParams().record()


def records(
    slip_tol=np.nan,
    *,
    arm=0.0,
    rtol=1e-6,
    atol=1e-9,
    cycle_tol=1e-6,
    stribeck=False,
    stick_radius=-np.inf,
):
    """(rules, motion, vs): a run's RULES, MOTION and VERDICT records, the verdict's
    measures NaN (as a run begins them); stick_radius: R* [m] (-inf: no sticking disc)."""
    rules = one(RULES)
    rules["corotation"] = True
    rules["rtol"], rules["atol"], rules["cycle_tol"] = rtol, atol, cycle_tol
    rules["hold"] = 1.0
    motion = one(MOTION)
    motion["arm"] = arm
    vs = one(VERDICT)
    for name in VERDICT.names:
        if VERDICT[name] == np.float64:
            vs[name] = np.nan
    vs["slip_tol"] = slip_tol
    vs["stribeck"] = stribeck
    vs["stick_radius"] = stick_radius
    return rules, motion, vs


def ring(slips, *, any_stuck=True, ever_all=False, still=False, times=None, **kw):
    """(rules, motion, vs, revs): a revolution ring holding `slips` [m], oldest first, with
    the given flags; keywords as `records`."""
    rules, motion, vs = records(**kw)
    revs = np.zeros(REV_RING, dtype=REVOLUTION)
    n = len(slips)
    revs["slip"][:n] = slips
    revs["t"][:n] = np.arange(1, n + 1, dtype=float) if times is None else times
    revs["any_stuck"][:n] = any_stuck
    revs["ever_all"][:n] = ever_all
    revs["still"][:n] = still
    motion["n_rev"] = n
    return rules, motion, vs, revs


def sequence(points, slip, stick):
    """A section sequence (points, slip, stick) of SEQ_MAX rows holding these n steps:
    points (n, <= 5) [m], slip (n) [m], stick (n) [s]."""
    n = len(slip)
    pts = np.zeros((SEQ_MAX, 5))
    pts[:n, : np.shape(points)[1]] = points
    seq_slip, seq_stick = np.zeros(SEQ_MAX), np.zeros(SEQ_MAX)
    seq_slip[:n], seq_stick[:n] = slip, stick
    return pts, seq_slip, seq_stick
