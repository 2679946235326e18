"""The co-rotation verdict and the tests on a run still settling (numba).

From the revolution ring rv that the monitor fills (kernel/monitor.py, monitor_revolution):
`corotation_verdict` decides permanent co-rotation (`stick`) against ratcheting (`creep`)
under stick_rule corotation; `still_settling` and `trend_to_stick` tell whether a run
without a verdict at its horizon is still on its way to one. The thresholds of these rules
are the constants below.
"""

import math

from .jit import kernel_jit
from .monitor_slots import (
    F_LAMBDA,
    F_LAMBDA_SE,
    F_REMAIN,
    F_S_INF,
    F_SLIP_TOL,
    I_NREV,
    I_VERDICT,
    REV_RING,
    RV_ALL_STUCK,
    RV_ANY_STUCK,
    RV_EVER_ALL,
    RV_SLIP,
    RV_STICK_T,
    RV_STILL,
    RV_T,
    VERDICT_CREEP,
    VERDICT_NONE,
    VERDICT_STICK,
)

# Revolutions behind a verdict on the slip trend. Five give four decay ratios, enough for
# a standard error; fewer make one grazing contact's lumpy slip look like a trend.
VERDICT_REVS = 5
# Standard errors by which a decay must be established (about 97.5 % one-sided).
VERDICT_Z = 2.0
# Stationarity (trend_to_stick): two windows of TREND_REVS revolutions each are compared.
# Three revolutions average the stick-slip cycle's beat against the master revolution; a
# slow measure that moves towards stick by more than TREND_REL of its size (slip) or of a
# revolution (stick time) from one window to the next is a trend.
TREND_REVS = 3
TREND_REL = 0.02
# Spacing (revolutions) below which Aitken's limit is not trusted: measured on the braked
# disk, spacings of 2 revolutions still mistake the last fast transient for the limit
# (from rest, beta_b = 0.005, mu = 0.22: limit 4.5e-8 m read at 51 s, true limit 0).
AITKEN_MIN_SPACING = 4


@kernel_jit
def _row(mi, back):
    """Ring row of the revolution `back` revolutions before the newest (0 = newest)."""
    return (mi[I_NREV] - 1 - back) % REV_RING


@kernel_jit
def _slip_trend(mf, mi, rv):
    """Mean log ratio lambda of successive slips per revolution over the last VERDICT_REVS
    revolutions, and its standard error [1/rev]; NaN, NaN if a slip is 0."""
    n = VERDICT_REVS - 1
    acc = 0.0
    acc2 = 0.0
    for back in range(n):
        new = rv[_row(mi, back), RV_SLIP]
        old = rv[_row(mi, back + 1), RV_SLIP]
        if not (new > 0.0 and old > 0.0):
            return math.nan, math.nan
        r = math.log(new / old)
        acc += r
        acc2 += r * r
    mean = acc / n
    var = max(0.0, (acc2 - n * mean * mean) / (n - 1))
    return mean, math.sqrt(var / n)


@kernel_jit
def _limit_slip(mi, rv, n_orbit):
    """Aitken's extrapolated limit of the slip per revolution [m] from three revolutions m
    apart over the newer half of the orbit history (m = n_orbit // 4 >= AITKEN_MIN_SPACING: the older half
    holds the fast transients of the approach), and the decay ratio per revolution behind
    it; (NaN, NaN) unless the slip falls and its fall slows down (the only shape a limit
    can be read from). S = S_inf + A q^k gives S_inf exactly: 0 for
    geometric decay to shakedown, > 0 for a ratchet settling to its steady rate."""
    m = min(n_orbit // 4, (REV_RING - 1) // 2)
    if m < AITKEN_MIN_SPACING:
        return math.nan, math.nan
    s_a = rv[_row(mi, 2 * m), RV_SLIP]
    s_b = rv[_row(mi, m), RV_SLIP]
    s_c = rv[_row(mi, 0), RV_SLIP]
    d1 = s_a - s_b
    d2 = s_b - s_c
    if not (d1 > d2 > 0.0):
        return math.nan, math.nan
    return max(0.0, s_c - d2 * d2 / (d1 - d2)), (d2 / d1) ** (1.0 / m)


@kernel_jit
def corotation_verdict(mf, mi, rv):
    """Permanent co-rotation (`stick`), ratcheting (`creep`) or not yet decided, from the
    revolutions the slave spent on its small orbit (some contact stuck at every instant).
    `tol` = atol + eps T [m] is the slip per revolution that counts as none: the position
    tolerance, plus the slip that the slide->stick threshold eps [m/s] leaves unresolved
    over one revolution T (a contact re-sticks only once its plastic rate falls below
    eps, so slower slip is below the friction law's own resolution).

    stick: every contact stuck throughout the last revolution and it moved nothing (centre
    drift and spin-phase drift, as the arc of the longest arm, within the integrator's
    tolerance atol + rtol |r|, atol + rtol |arm|: RV_STILL); or, on the small orbit for
    VERDICT_REVS revolutions, each of them moved nothing and slipped <= tol (contacts that
    graze their limit without net slip); or the slip
    per revolution decays geometrically (falling, its fall slowing as S_inf + A q^k) to
    an extrapolated limit S_inf <= tol: shakedown.
    creep: the slip per revolution exceeds tol and either no longer falls (over the newer
    half of the orbit history) or falls towards a limit S_inf > tol that already holds
    at least half of it: a steady ratchet.
    Between the two (a limit above tol but well below today's slip) the verdict waits.
    Needs VERDICT_REVS revolutions on the orbit.
    """
    mi[I_VERDICT] = VERDICT_NONE
    n = mi[I_NREV]
    if n < 1:
        return VERDICT_NONE
    tol = mf[F_SLIP_TOL]
    last = _row(mi, 0)
    slip = rv[last, RV_SLIP]
    if rv[last, RV_ALL_STUCK] == 1.0 and rv[last, RV_STILL] == 1.0:
        mf[F_REMAIN] = 0.0
        mi[I_VERDICT] = VERDICT_STICK
        return VERDICT_STICK
    n_orbit = _run_length(mi, rv, RV_ANY_STUCK, 1.0)
    if n_orbit < VERDICT_REVS:
        return VERDICT_NONE  # not (long enough) on the small orbit
    quiet = True
    for back in range(VERDICT_REVS):
        row = _row(mi, back)
        quiet = quiet and rv[row, RV_SLIP] <= tol and rv[row, RV_STILL] == 1.0
    if quiet:
        mf[F_REMAIN] = 0.0
        mi[I_VERDICT] = VERDICT_STICK  # grazing contacts, but no slip to resolve
        return VERDICT_STICK
    lam, se = _slip_trend(mf, mi, rv)
    mf[F_LAMBDA] = lam
    mf[F_LAMBDA_SE] = se
    s_inf, q = _limit_slip(mi, rv, n_orbit)
    mf[F_S_INF] = s_inf
    if math.isnan(s_inf):
        m = n_orbit // 4
        if m >= 1 and slip > tol and slip >= rv[_row(mi, m), RV_SLIP]:
            mi[I_VERDICT] = VERDICT_CREEP  # not falling: steady or growing
            return VERDICT_CREEP
        return VERDICT_NONE
    mf[F_REMAIN] = slip * q / (1.0 - q)
    if s_inf > tol and s_inf >= 0.5 * slip:
        # most of today's slip persists in the limit: the ratchet has settled
        mi[I_VERDICT] = VERDICT_CREEP
        return VERDICT_CREEP
    if s_inf <= tol:
        mi[I_VERDICT] = VERDICT_STICK  # geometric decay to no slip: shakedown
        return VERDICT_STICK
    return VERDICT_NONE


@kernel_jit
def _run_length(mi, rv, column, value):
    """Consecutive revolutions, newest first, whose `column` equals value (at most the ring)."""
    count = 0
    for back in range(min(mi[I_NREV], REV_RING)):
        if rv[_row(mi, back), column] != value:
            break
        count += 1
    return count


@kernel_jit
def still_settling(mf, mi, rv, corotation):
    """Whether an undecided run at its horizon is still on its way to a decision: sliding
    as a whole (never all contacts stuck) for VERDICT_REVS revolutions with its slip per
    revolution decaying towards a sticking circle (not settling at a steady sliding rate,
    by the same Aitken limit as corotation_verdict's), or (corotation: the stick_rule) before
    VERDICT_REVS revolutions, or on the small orbit (some contact stuck at every instant of
    the last revolution), where corotation_verdict has not spoken yet."""
    if corotation and mi[I_VERDICT] != VERDICT_NONE:
        return False
    if corotation and mi[I_NREV] < VERDICT_REVS:
        return True  # too few revolutions to tell any of the outcomes apart
    if mi[I_NREV] < 1:
        return False
    on_orbit = _run_length(mi, rv, RV_ANY_STUCK, 1.0) if corotation else 0
    sliding = _run_length(mi, rv, RV_EVER_ALL, 0.0)
    if on_orbit > 0:
        return True  # corotation_verdict decides every orbit in time; until then, wait
    if sliding < VERDICT_REVS:
        return False
    lam, se = _slip_trend(mf, mi, rv)
    if math.isnan(lam) or lam + VERDICT_Z * se >= 0.0:
        return False  # steady (or growing) sliding
    # falling: towards a sticking circle (limit 0), unless it visibly settles at a steady
    # sliding rate that already holds most of it (limit > tol)
    s_inf, _ = _limit_slip(mi, rv, sliding)
    slip = rv[_row(mi, 0), RV_SLIP]
    return not (s_inf > mf[F_SLIP_TOL] and s_inf >= 0.5 * slip)


@kernel_jit
def _window_change(mi, rv, column, m):
    """Mean of `column` over the newest m revolutions minus its mean over the m before, and
    the standard error of that difference from the scatter within the windows."""
    new = 0.0
    old = 0.0
    for back in range(m):
        new += rv[_row(mi, back), column]
        old += rv[_row(mi, back + m), column]
    new /= m
    old /= m
    scatter = 0.0
    for back in range(m):
        scatter += (rv[_row(mi, back), column] - new) ** 2
        scatter += (rv[_row(mi, back + m), column] - old) ** 2
    variance = scatter / (2 * (m - 1))  # pooled, per revolution
    return new - old, old, math.sqrt(2.0 * variance / m)


@kernel_jit
def trend_to_stick(mf, mi, rv):
    """Whether a run without a verdict is not yet shown stationary: fewer than
    2 TREND_REVS revolutions, or from the older to the newer window of TREND_REVS
    revolutions a slow measure moved towards permanent stick: the slip per revolution fell
    (by more than TREND_REL of it and more than the slip tolerance), or the whole-body
    stick time per revolution grew (by more than TREND_REL of a revolution). A change
    counts only beyond VERDICT_Z standard errors of the scatter within the windows: a
    converged stick-slip cycle whose period is not the master's beats against the
    revolutions, and that beat is no trend. A disk spinning up while it slides shows in
    its falling slip. The spin drift alone is no evidence: a self-centred disk spins up
    towards omega_m for ever at a steady slip per revolution and never sticks. A run that
    is steady, or moves away from stick, is not trending to stick."""
    m = TREND_REVS
    if mi[I_NREV] < 2 * m:
        return True
    change, old, se = _window_change(mi, rv, RV_SLIP, m)
    if -change > max(TREND_REL * old, mf[F_SLIP_TOL], VERDICT_Z * se):
        return True
    period = rv[_row(mi, 0), RV_T] - rv[_row(mi, 1), RV_T]
    change, old, se = _window_change(mi, rv, RV_STICK_T, m)
    return change > max(TREND_REL * period, VERDICT_Z * se)
