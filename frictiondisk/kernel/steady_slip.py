"""Is a small slip per period steady? (numba; kernel/sections.py asks before it takes a
motion that slips less than its repeat tolerance a period for a cycle.)

Such a motion lies within that tolerance of itself whether it cycles or creeps onto
sticking, so its section repeating says nothing; only a slip per period shown steady does.
"""

import math

from .jit import kernel_jit
from .line_fit import slope_and_error

# A slip per period within the repeat tolerance must be shown steady for a repeat: over the
# newest FALL_WINDOW steps (at least FALL_MIN periods) it loses at most STEADY_FALL, at
# FALL_Z standard errors of its trend
FALL_WINDOW = 128
FALL_MIN = 8
STEADY_FALL = 0.01
FALL_Z = 2.0


@kernel_jit
def shown_steady(slope, se, count):
    """Whether a least-squares trend of ln(slip) over `count` points, `slope` per point with
    standard error `se`, is shown not to fall: less FALL_Z standard errors, it loses at
    most STEADY_FALL over the span."""
    return (slope - FALL_Z * se) * (count - 1) >= -STEADY_FALL


@kernel_jit
def period_slip(slip, n, lag, back):
    """Slip over period `back` (0 = newest) of `lag` steps of the sequence `slip` [m]."""
    total = 0.0
    for k in range(lag):
        total += slip[n - 1 - back * lag - k]
    return total


@kernel_jit
def steady(slip, n, lag):
    """Whether the slip per period of `lag` steps is shown steady over the newest
    FALL_WINDOW steps (or all there are, at least FALL_MIN periods): the least-squares
    slope of its logarithm, less FALL_Z standard errors, loses at most STEADY_FALL over the
    window. Shown, not merely not refuted: a creep's slip can switch irregularly between
    levels while it falls (seed 0 scene 0, mu = 0.085: 1.45e-8 and 1.28e-8 m a revolution,
    0.13 % less each revolution), and a test for a fall, made at every step, lets one
    such step through sooner or later. Summed per period, because a cycle section
    alternates between long and short sticking phases (seed 2 scene 24, mu = 0.105: steps
    of 1.2e-8 and 2.2e-13 m)."""
    count = min(FALL_WINDOW, n) // lag
    if count < FALL_MIN:
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
    return shown_steady(slope, se, count)
