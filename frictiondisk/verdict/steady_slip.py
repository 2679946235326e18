"""Is a small slip per period steady? (numba; verdict/section_evidence.py asks before it
takes a motion that slips less than its repeat tolerance a period for a cycle, and the
co-rotation rule asks whether a slip per revolution is shown not to fall.)

Such a motion lies within that tolerance of itself whether it cycles, creeps onto
sticking or departs from it, so its section repeating says nothing; only a slip per period
shown steady does: shown not to fall, and (above the slip that counts as none) not shown
to rise.
Shown, not merely not refuted: a creep's slip can switch irregularly between levels while
it falls, and a test for a fall, made at every step, lets one such step through sooner or
later. Summed per period, because a cycle's section can alternate between long and short
sticking phases. The thresholds: VerdictParams fall_window, fall_min, steady_fall, fall_z.
"""

import math

from frictiondisk.kernel.jit import kernel_jit

from .line_fit import slope_and_error


@kernel_jit
def shown_steady(vp, slope, se, count):
    """Whether a least-squares trend of ln(slip) over `count` points, `slope` per point with
    standard error `se`, is shown not to fall: less vp.fall_z standard errors, it loses at
    most vp.steady_fall over the span."""
    return (slope - vp.fall_z * se) * (count - 1) >= -vp.steady_fall


@kernel_jit
def shown_rising(vp, slope, se, count):
    """Whether that trend is shown to rise: less vp.fall_z standard errors, it gains more
    than vp.steady_fall over the span."""
    return (slope - vp.fall_z * se) * (count - 1) > vp.steady_fall


@kernel_jit
def period_slip(slip, n, lag, back):
    """Slip over period `back` (0 = newest) of `lag` steps of the sequence `slip` [m]."""
    total = 0.0
    for k in range(lag):
        total += slip[n - 1 - back * lag - k]
    return total


@kernel_jit
def steady(vp, slip, n, lag, s0):
    """Whether the slip per period of `lag` steps is shown steady over the newest
    vp.fall_window steps (or all there are, at least vp.fall_min periods): the least-squares
    slope of its logarithm is shown not to fall (`shown_steady`) and, where the newest
    period slips more than lag x s0 (s0: the slip per step that counts as none [m]), not
    shown to rise (`shown_rising`): a slip that grows below the repeat tolerance is a
    departure in progress (it may end in a large slip and a stick: generator 1's 1/42), not
    a cycle. Below lag x s0 the slip is none, and its changes are noise."""
    count = min(vp.fall_window, n) // lag
    if count < vp.fall_min:
        return False
    sum_k = sum_y = sum_kk = sum_ky = sum_yy = 0.0
    for back in range(count):
        total = period_slip(slip, n, lag, back)
        if not total > 0.0:
            return False
        x = float(count - 1 - back)
        y = math.log(total)
        sum_k += x
        sum_y += y
        sum_kk += x * x
        sum_ky += x * y
        sum_yy += y * y
    slope, se = slope_and_error(count, sum_k, sum_y, sum_kk, sum_ky, sum_yy)
    if not shown_steady(vp, slope, se, count):
        return False
    return period_slip(slip, n, lag, 0) <= lag * s0 or not shown_rising(vp, slope, se, count)
