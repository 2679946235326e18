"""Where a falling slip per step goes: Aitken's limit, over equally spaced steps (geometric
decay) or log-spaced ones (a power law, the slow creep onto a grazing sticking circle).
Both are exact for their model (numba)."""

import math

from frictiondisk.kernel.jit import kernel_jit


@kernel_jit
def aitken_limit(s_a, s_b, s_c, slowing):
    """Aitken's limit of three terms: NaN unless they fall and their fall slows down to at
    most `slowing` times the fall before."""
    d1 = s_a - s_b
    d2 = s_b - s_c
    if not (d1 > d2 > 0.0 and d2 <= slowing * d1):
        return math.nan
    return max(0.0, s_c - d2 * d2 / (d1 - d2))


@kernel_jit
def _log_steps(n):
    """Log-spaced steps of the newer half: n/2, n/sqrt(2), n (1-based)."""
    return n // 2, int(round(n / math.sqrt(2.0))), n


@kernel_jit
def _log_ratio(slip, n):
    """The fall over (n/sqrt(2), n) over the fall over (n/2, n/sqrt(2)): (sqrt 2)^-p for a
    power law S_inf + A n^-p, whatever n."""
    a, b, c = _log_steps(n)
    d1 = slip[a - 1] - slip[b - 1]
    d2 = slip[b - 1] - slip[c - 1]
    return d2 / d1 if d1 > 0.0 else math.inf


@kernel_jit
def _log_aitken(vp, slip, n):
    """Aitken's limit over the log-spaced steps of the newer half (NaN: no slowing fall)."""
    a, b, c = _log_steps(n)
    return aitken_limit(slip[a - 1], slip[b - 1], slip[c - 1], vp.aitken_slowing)


@kernel_jit
def shakedown_limit(vp, slip, stick, n):
    """The extrapolated limit [m] of a slip per step that falls at every step over the
    newer three quarters of the sequence while the slave sticks as a whole and its
    sticking time does not fall: the smaller of Aitken's limits over steps
    (n - 2m, n - m, n) with m = n // 4 (geometric decay) and over steps
    (n/2, n/sqrt 2, n) (a power law). NaN if the slip does not fall so.

    A slave that slides ever less must first stick as a whole (what it does then, a cycle
    or co-rotation, decides); no limit is read from a first fall (vp.shakedown_depth); a
    power law keeps its log-spaced fall ratio as n grows, a fall levelling off at a cycle
    raises it (vp.log_lookback, vp.log_ratio_drift)."""
    if n < vp.shakedown_steps:
        return math.nan
    if not stick[n - 1] > 0.0:
        return math.nan
    start = n // 4
    for i in range(start + 1, n):
        if not slip[i] < slip[i - 1]:
            return math.nan
    peak = 0.0
    for i in range(n):
        peak = max(peak, slip[i])
    if slip[n - 1] > vp.shakedown_depth * peak:
        return math.nan  # most of the way still to go: no limit is read from a first fall
    if stick[n - 1] < stick[start]:
        return math.nan  # sticking less and less: no approach to sticking
    m = n // 4
    limit = math.nan
    if m >= vp.section_min_spacing:
        limit = aitken_limit(slip[n - 1 - 2 * m], slip[n - 1 - m], slip[n - 1], vp.aitken_slowing)
    # log-spaced over the newer half, n/2, n/sqrt(2), n: exact for S_inf + A n^-p, and clear
    # of the first transient
    log_spaced = _log_aitken(vp, slip, n)
    if not math.isnan(log_spaced):
        earlier = int(round(vp.log_lookback * n))
        r_now, r_then = _log_ratio(slip, n), _log_ratio(slip, earlier)
        if not (r_now <= r_then + vp.log_ratio_drift):
            log_spaced = math.nan
    if math.isnan(limit) or log_spaced < limit:
        limit = log_spaced
    return limit
