"""Is a slave that slides as a whole in a sliding state, or on its way to sticking? (numba)
The EV_SLIDING evidence, read from the revolution ring; thresholds from VerdictParams."""

import math

from frictiondisk.kernel.jit import kernel_jit
from frictiondisk.kernel.monitor import newest_revolution as _row

from .corotation import sliding_revolutions, slip_slope, slip_trend


@kernel_jit
def _spinning_up(vp, rules, motion, revs):
    """Whether the slave's spin came closer to co-rotation, by more than the integrator's
    tolerance, at each of the last vp.slide_revs revolutions: an approach to sticking, not
    a sliding state (a Stribeck disk from rest spins up at every revolution while its slip
    per revolution rises now and then). A spin drifting away from co-rotation, as a braked
    disk's does while it slowly leaves sticking, is no approach. In metres: the spin rate
    times the longest arm over omega_m, which is the arm itself at co-rotation (0 for the
    pin)."""
    arm = motion.arm
    if arm <= 0.0:
        return False
    for back in range(vp.slide_revs - 1):
        new = abs(revs[_row(motion, back)].w - arm)
        old = abs(revs[_row(motion, back + 1)].w - arm)
        if not new < old - (rules.atol + rules.rtol * arm):
            return False
    return True


@kernel_jit
def steady_sliding(vp, rules, motion, revs):
    """Whether the run has slid as a whole (no whole-body stick) for vp.slide_revs
    revolutions at a slip per revolution that did not fall at every one of them (a slip
    falling revolution after revolution is an approach to sticking, however slowly it
    falls), whose decay is not established at vp.verdict_z standard errors, neither by the
    slope of ln(slip) over the vp.slide_revs revolutions nor over the last vp.verdict_revs
    (a slip that alternates on its way down is still a fall): a sliding orbit whose slip
    wanders about a level (its period not the master's) or grows."""
    if sliding_revolutions(motion, revs) < vp.slide_revs:
        return False
    if _spinning_up(vp, rules, motion, revs):
        return False
    falling = True
    for back in range(vp.slide_revs - 1):
        falling = falling and revs[_row(motion, back)].slip < revs[_row(motion, back + 1)].slip
    if falling:
        return False
    slope, slope_se = slip_slope(motion, revs, vp.slide_revs)
    if slope + vp.verdict_z * slope_se < 0.0:
        return False  # falls over the window, alternating on the way
    lam, se = slip_trend(vp, motion, revs)
    return math.isnan(lam) or lam + vp.verdict_z * se >= 0.0
