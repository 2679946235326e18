"""Where a falling slip per step goes. The law it falls by is read first (`decay_law`):
geometric (S_inf + A q^n) or algebraic (S_inf + A (n - n0)^-p: the slow creep onto the rim
of a sticking disc falls as t^-2). Both are read from the falls of the slip summed over
four blocks, which carry no S_inf, and the limit is the newest slip less the tail of the
falls still to come under that law: exact for its law, a floor S_inf kept (numba)."""

import math

from frictiondisk.kernel.jit import kernel_jit

LAW_BLOCKS = 4  # blocks of the fall: three ratios, whose middle one tests the law
LAW_ITERATIONS = 3  # refinements of (p, n0) by the blocks' exact sums (converged at 2)


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
def _block_fall(slip, n, k, j):
    """The fall of the slip over block j (0 oldest) of k steps, the newest ending at n - 1."""
    a = n - 1 - (LAW_BLOCKS - j) * k
    return slip[a] - slip[a + k]


@kernel_jit
def _power_sum(a, k, n0, q):
    """sum over i = a ... a + k - 1 of (i - n0)^-q."""
    total = 0.0
    for i in range(a, a + k):
        total += (i - n0) ** -q
    return total


@kernel_jit
def _scale(slip, n, k, j, j_next):
    """-k / ln(ratio) of two blocks' falls: constant for a geometric fall, (c - n0) / q for
    falls ~ (i - n0)^-q (c: the middle between the blocks' centres). inf where they do
    not shrink."""
    ratio = _block_fall(slip, n, k, j_next) / _block_fall(slip, n, k, j)
    return -k / math.log(ratio) if 0.0 < ratio < 1.0 else math.inf


@kernel_jit
def _on_line(z, j, a0, k, n0, q, c0):
    """-k / ln ratio z of blocks j, j + 1 less what the law (n0, q) itself puts off its
    line (c - n0) / q: the exact sums against their midpoint reading."""
    older = _power_sum(a0 + j * k, k, n0, q)
    newer = _power_sum(a0 + (j + 1) * k, k, n0, q)
    exact = -k / math.log(newer / older)
    return z - (exact - (c0 + j * k - n0) / q)


@kernel_jit
def decay_law(vp, slip, n):
    """(p, n0, k) of the slip's fall over the newer three quarters of the first n steps,
    in LAW_BLOCKS blocks of k steps (the newest ending at step n - 1, 0-based): p = inf
    for a geometric fall (the newest -k / ln ratio of successive blocks keeps
    vp.geometric_keep of the oldest one's), else the exponent of S_inf + A (i - n0)^-p,
    whose falls (i - n0)^-(p + 1) put the three -k / ln ratio on a line of slope 1/(p + 1)
    (within vp.law_bend of the middle one; then refined LAW_ITERATIONS times by the
    blocks' exact sums). (NaN, NaN, k): neither law, or blocks of fewer than 2 steps."""
    first = n // 4
    k = (n - 1 - first) // LAW_BLOCKS
    if k < 2:
        return math.nan, math.nan, k
    z0 = _scale(slip, n, k, 0, 1)
    z1 = _scale(slip, n, k, 1, 2)
    z2 = _scale(slip, n, k, 2, 3)
    if not (z0 < math.inf and z1 < math.inf and z2 < math.inf):
        return math.nan, math.nan, k
    if z2 * vp.geometric_keep <= z0 and z1 * vp.geometric_keep <= z0:
        return math.inf, math.nan, k
    c0 = n - 1 - (LAW_BLOCKS - 1) * k  # the middle between blocks 0 and 1 (their meeting)
    slope = (z2 - z0) / (2 * k)
    if not slope > 0.0 or abs(z1 - (z0 + slope * k)) > vp.law_bend * z1:
        return math.nan, math.nan, k
    q = 1.0 / slope
    n0 = c0 + 2 * k - q * z2
    a0 = n - 1 - LAW_BLOCKS * k
    for _ in range(LAW_ITERATIONS):
        if not n0 < a0:
            return math.nan, math.nan, k
        fixed0 = _on_line(z0, 0, a0, k, n0, q, c0)
        fixed2 = _on_line(z2, 2, a0, k, n0, q, c0)
        slope = (fixed2 - fixed0) / (2 * k)
        if not slope > 0.0:
            return math.nan, math.nan, k
        q = 1.0 / slope
        n0 = c0 + 2 * k - q * fixed2
    return q - 1.0, n0, k


@kernel_jit
def law_limit(vp, slip, n):
    """(limit [m], p): the limit of the slip per step under the law its fall follows
    (`decay_law`), the newest slip less the falls still to come: for a geometric fall the
    newest block's fall times rho / (1 - rho) (rho: the ratio of the newest two blocks),
    for a power law (p + 1 the falls' exponent) the newest block's fall times
    u / (v - u), u = (n - 1.5 - n0)^-p and v = (a - 0.5 - n0)^-p (a: the block's first
    step; the midpoint rule's sums). NaN where it follows neither law."""
    p, n0, k = decay_law(vp, slip, n)
    if math.isnan(p):
        return math.nan, p
    newest = _block_fall(slip, n, k, LAW_BLOCKS - 1)
    if math.isinf(p):
        rho = newest / _block_fall(slip, n, k, LAW_BLOCKS - 2)
        return slip[n - 1] - newest * rho / (1.0 - rho), p
    a = n - 1 - k
    u = (n - 1.5 - n0) ** -p
    v = (a - 0.5 - n0) ** -p
    return slip[n - 1] - newest * u / (v - u), p


@kernel_jit
def shakedown_limit(vp, slip, stick, n):
    """The extrapolated limit [m] of a slip per step that falls at every step over the
    newer three quarters of the sequence while the slave sticks as a whole and its
    sticking time does not fall, under the law that fall follows (`law_limit`). NaN if the
    slip does not fall so, or follows neither law.

    A slave that slides ever less must first stick as a whole (what it does then, a cycle
    or co-rotation, decides); no limit is read from a first fall (vp.shakedown_depth); a
    power law keeps its exponent as n grows (vp.log_lookback, vp.law_exponent_drift)."""
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
    limit, p = law_limit(vp, slip, n)
    if math.isnan(limit):
        return math.nan
    if not math.isinf(p):
        # a power law keeps its exponent as n grows; a transient, or noise on a slow creep,
        # changes it
        _, p_then = law_limit(vp, slip, int(round(vp.log_lookback * n)))
        if not abs(p_then - p) <= vp.law_exponent_drift * p:
            return math.nan
    return max(0.0, limit)
