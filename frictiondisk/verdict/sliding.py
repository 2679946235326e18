"""Is a slave that slides as a whole in a sliding state, or on its way to sticking? (numba)
The EV_SLIDING evidence, read from the revolution ring; thresholds from VerdictParams.

A slip per revolution can oscillate by a few per cent from one revolution to the next (the
revolution samples the slave's own spring-mass oscillation: their beat) while its lower
envelope falls towards sticking. A trend fitted over a few revolutions then never
establishes the fall, and "not established" is no evidence of "not falling" (a
Stribeck disk from rest read as sliding at 91 s sticks at 171 s). So the sliding state
must also show its lowest slip per revolution not falling, compared over windows of at
least two of the oscillation's periods (`lowest_slip_holds`).

A spin that climbs towards the master's is no evidence against sliding by itself: an
approach to sticking shows in the slip, which these tests read. A disk from rest on a
large pure-sliding orbit spins up for thousands of seconds until its spin co-rotates with
the master (the second generator's scene 3/5 within 1e-8 of it at 15 000 s, 2/7 at 0.993
and still climbing), while its centre slides on, 5 to 12 m a revolution; watched to
15 000 s it does not stick. A spin at co-rotation is no whole-body stick while the centre
slides, and a guard that read every such climb as an approach to sticking left them
undetermined at every retry (docs/model.md section 6).
"""

import math

from frictiondisk.kernel.jit import kernel_jit
from frictiondisk.kernel.monitor import newest_revolution as _row

from .corotation import sliding_revolutions, slip_slope, slip_trend


@kernel_jit
def trough_spacing(motion, revs, count):
    """The oscillation period of the slip per revolution [revolutions], read from its
    troughs among the newest `count` revolutions: half the distance from the third-newest
    trough to the newest; 1.0 with fewer than three troughs. A trough is a revolution whose
    slip is below the one before and not above the one after (so the newest revolution,
    not yet confirmed, is none)."""
    found = 0
    newest = 0
    for back in range(1, count - 1):
        slip = revs[_row(motion, back)].slip
        if slip < revs[_row(motion, back + 1)].slip and slip <= revs[_row(motion, back - 1)].slip:
            if found == 0:
                newest = back
            found += 1
            if found == 3:
                return (back - newest) / 2.0
    return 1.0


@kernel_jit
def envelope_window(vp, motion, revs, count):
    """Revolutions H in each half of the lowest-slip comparison: vp.envelope_periods
    oscillation periods (trough_spacing over the `count` sliding revolutions), at least
    vp.envelope_min_revs."""
    period = trough_spacing(motion, revs, count)
    return max(vp.envelope_min_revs, int(math.ceil(vp.envelope_periods * period)))


@kernel_jit
def lowest_slip_holds(vp, rules, motion, revs, count, window):
    """Whether the lowest slip per revolution of the newest `window` revolutions is not
    below the lowest of the `window` before, less the integrator's tolerance atol + rtol s
    on that slip s; False with fewer than 2 `window` of the `count` sliding revolutions.
    Over a whole oscillation period each window holds a trough, so an oscillation cannot
    lift the newer window's lowest slip above a falling envelope."""
    if count < 2 * window:
        return False
    newer = math.inf
    older = math.inf
    for back in range(window):
        newer = min(newer, revs[_row(motion, back)].slip)
        older = min(older, revs[_row(motion, back + window)].slip)
    return newer >= older - (rules.atol + rules.rtol * older)


@kernel_jit
def _trend_not_falling(vp, motion, revs):
    """Whether the slip per revolution did not fall at every one of the last vp.slide_revs
    revolutions and its decay is not established at vp.verdict_z standard errors, neither by
    the slope of ln(slip) over them nor over the last vp.verdict_revs (a slip that
    alternates on its way down is still a fall)."""
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


@kernel_jit
def steady_sliding(vp, rules, motion, vs, revs):
    """Whether the run has slid as a whole (no whole-body stick) for vp.slide_revs
    revolutions at a slip per revolution whose fall is not established over the last
    revolutions (`_trend_not_falling`), and whose lowest value over the newest H
    revolutions is not below the lowest of the H before (`lowest_slip_holds`, H =
    envelope_window): a sliding orbit whose slip wanders about a level or grows. Writes the
    sliding revolutions and H it read into vs.sliding_revs and vs.envelope_revs (0, 0 where
    it did not slide as a whole for vp.slide_revs: for the label's reason)."""
    vs.sliding_revs = 0
    vs.envelope_revs = 0
    count = sliding_revolutions(motion, revs)
    if count < vp.slide_revs:
        return False
    vs.sliding_revs = count
    vs.envelope_revs = envelope_window(vp, motion, revs, count)
    if not _trend_not_falling(vp, motion, revs):
        return False
    return lowest_slip_holds(vp, rules, motion, revs, count, vs.envelope_revs)
