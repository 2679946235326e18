"""The least-squares line through points (x, y), from their running sums (numba): the slope
and its standard error, as the slip-trend rules of verdict/corotation.py and
verdict/steady_slip.py read ln(slip) against the step."""

import math

from frictiondisk.kernel.jit import kernel_jit


@kernel_jit
def slope_and_error(count, sum_x, sum_y, sum_xx, sum_xy, sum_yy):
    """Slope of the least-squares line through `count` >= 3 points and its standard error,
    from the sums of x, y, x^2, x y and y^2 over them."""
    sxx = sum_xx - sum_x * sum_x / count
    sxy = sum_xy - sum_x * sum_y / count
    syy = sum_yy - sum_y * sum_y / count
    slope = sxy / sxx
    rss = max(0.0, syy - slope * sxy)
    return slope, math.sqrt(rss / (count - 2) / sxx)
