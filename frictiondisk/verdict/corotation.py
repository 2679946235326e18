"""The co-rotation rule (numba): permanent co-rotation (`stick`) against ratcheting (`creep`)
from the revolutions the slave spent on its small orbit (some contact stuck at every
instant), read from the revolution ring the monitor fills (kernel/monitor.py).

`slip_tol` = eps T [m] is the slip per revolution that counts as none: the slip that the
slide->stick threshold eps [m/s] leaves unresolved over one revolution T (a contact
re-sticks only once its plastic rate falls below eps, so slower slip is below the
friction law's own resolution). It is a model quantity: no integrator tolerance enters
it, so stick and creep mean the same at every rtol and atol. The thresholds are fields of
VerdictParams (vp).
"""

import math

from frictiondisk.kernel.jit import kernel_jit
from frictiondisk.kernel.monitor import newest_revolution as _row
from frictiondisk.kernel.records import REV_RING

from .extrapolation import aitken_limit
from .line_fit import slope_and_error
from .records import COROTATING, CREEPING, SETTLING
from .steady_slip import shown_steady


@kernel_jit
def still(rules, motion, row, steps):
    """Whether the revolution in `row` (just closed, `steps` integrator steps so far) moved
    nothing: centre drift and spin-phase drift (as the arc of the longest arm) within the
    integrator's own tolerance accumulated over its steps. Each step may err by atol +
    rtol |y|, so a stuck slave drifts by up to that many times it (a stuck pin at rtol
    1e-8 drifts 1.5e-9 m per revolution, more than one step's 1.5e-9 m)."""
    n_steps = max(1, steps - motion.rev_steps0)
    arm = motion.arm
    radius = math.sqrt(row.x * row.x + row.y * row.y)
    still_r = row.drift_r <= n_steps * (rules.atol + rules.rtol * radius)
    still_phi = abs(row.drift_phi) * arm <= n_steps * (rules.atol + rules.rtol * arm)
    return still_r and still_phi


@kernel_jit
def slip_trend(vp, motion, revs):
    """Mean log ratio lambda of successive slips per revolution over the last
    vp.verdict_revs revolutions, and its standard error [1/rev]; NaN, NaN if a slip is 0."""
    n = vp.verdict_revs - 1
    acc = 0.0
    acc2 = 0.0
    for back in range(n):
        new = revs[_row(motion, back)].slip
        old = revs[_row(motion, back + 1)].slip
        if not (new > 0.0 and old > 0.0):
            return math.nan, math.nan
        r = math.log(new / old)
        acc += r
        acc2 += r * r
    mean = acc / n
    var = max(0.0, (acc2 - n * mean * mean) / (n - 1))
    return mean, math.sqrt(var / n)


@kernel_jit
def slip_slope(motion, revs, count):
    """Least-squares slope of ln(slip per revolution) against the revolution over the last
    `count` revolutions, and its standard error [1/rev]; NaN, NaN if a slip is 0. Unlike
    the mean of successive ratios it is not masked by a slip that alternates from one
    revolution to the next about a falling level."""
    sum_k = sum_y = sum_kk = sum_ky = sum_yy = 0.0
    for back in range(count):
        slip = revs[_row(motion, back)].slip
        if not slip > 0.0:
            return math.nan, math.nan
        k = float(count - 1 - back)
        y = math.log(slip)
        sum_k += k
        sum_y += y
        sum_kk += k * k
        sum_ky += k * y
        sum_yy += y * y
    return slope_and_error(count, sum_k, sum_y, sum_kk, sum_ky, sum_yy)


@kernel_jit
def _aitken(motion, revs, m, shift):
    """Aitken's limit of the slip per revolution [m] from the revolutions shift, shift + m
    and shift + 2 m before the newest, and the decay ratio per revolution behind it;
    (NaN, NaN) unless the slip falls and its fall slows down (the only shape a limit can
    be read from). S = S_inf + A q^k gives S_inf exactly: 0 for geometric decay to
    shakedown, > 0 for a ratchet settling to its steady rate."""
    s_a = revs[_row(motion, shift + 2 * m)].slip
    s_b = revs[_row(motion, shift + m)].slip
    s_c = revs[_row(motion, shift)].slip
    limit = aitken_limit(s_a, s_b, s_c, 1.0)
    if math.isnan(limit):
        return math.nan, math.nan
    return limit, ((s_b - s_c) / (s_a - s_b)) ** (1.0 / m)


@kernel_jit
def _limit_slip(vp, motion, revs, n_orbit):
    """Aitken's limit S_inf of the slip per revolution [m] over the newer three quarters of
    the orbit history (spacing m = n_orbit // 4 >= vp.limit_min_spacing: the oldest quarter
    holds the fast transients of the approach), the decay ratio per revolution behind it,
    and the lowest and highest of the same estimates made 0 ... m revolutions earlier [m].
    A motion S_inf + A q^k gives every estimate exactly. A fall that slows down more than
    geometrically (a power law; a braked disk near its shakedown bound, whose ratchet dies
    out ever more slowly) gives estimates that fall with the slip, so the true limit lies
    below the newest; one that levels off faster gives estimates that rise. (NaN, NaN,
    NaN, NaN) if there is no limit to read; lowest -inf, highest inf if an earlier
    estimate has none."""
    m = min(n_orbit // 4, (REV_RING - 1) // 4)
    if m < vp.limit_min_spacing:
        return math.nan, math.nan, math.nan, math.nan
    s_inf, q = _aitken(motion, revs, m, 0)
    if math.isnan(s_inf):
        return math.nan, math.nan, math.nan, math.nan
    lowest = s_inf
    highest = s_inf
    for shift in range(1, min(m, n_orbit - 1 - 2 * m) + 1):
        s_then, _ = _aitken(motion, revs, m, shift)
        if math.isnan(s_then):
            return s_inf, q, -math.inf, math.inf
        lowest = min(lowest, s_then)
        highest = max(highest, s_then)
    return s_inf, q, lowest, highest


@kernel_jit
def corotation_verdict(vp, rules, motion, vs, revs):
    """COROTATING, CREEPING or SETTLING (not yet decided) at the revolution just closed;
    also vs.state and the measures behind it (vs.decay, remaining, limit, limit_spread).

    COROTATING: every contact stuck throughout the last revolution and it moved nothing
    (`still`); or, on the small orbit for vp.verdict_revs revolutions, each of them moved
    nothing and slipped <= slip_tol (contacts that graze their limit without net slip); or
    the slip per revolution decays geometrically (falling, its fall slowing as
    S_inf + A q^k) to an extrapolated limit S_inf with S_inf + spread <= slip_tol:
    shakedown.
    CREEPING: the slip per revolution exceeds slip_tol and either no longer falls (over
    the newer half of the orbit history) or falls towards a limit that holds at least
    vp.creep_share of it, with S_inf - spread > slip_tol and a spread within
    vp.limit_drift of S_inf: a settled ratchet. spread: how far the same estimate, made
    0 ... m revolutions earlier, ranged. Near a braked disk's shakedown bound the ratchet
    dies out ever more slowly, or levels off late, and the estimates wander with it; a
    limit decides only where they agree.
    Otherwise the verdict waits (and the run goes on, or ends undetermined).
    """
    vs.state = SETTLING
    if motion.n_rev < 1:
        return SETTLING
    tol = vs.slip_tol
    last = revs[_row(motion, 0)]
    slip = last.slip
    if last.all_stuck and last.still:
        vs.remaining = 0.0
        vs.state = COROTATING
        return COROTATING
    n_orbit = orbit_revolutions(motion, revs)
    if n_orbit < vp.verdict_revs:
        return SETTLING  # not (long enough) on the small orbit
    if _quiet(vp, motion, vs, revs):
        vs.remaining = 0.0
        vs.state = COROTATING  # grazing contacts, but no slip to resolve
        return COROTATING
    lam, se = slip_trend(vp, motion, revs)
    vs.decay = lam
    vs.decay_se = se
    s_inf, q, lowest, highest = _limit_slip(vp, motion, revs, n_orbit)
    vs.limit = s_inf
    spread = highest - lowest
    vs.limit_spread = spread
    if math.isnan(s_inf):
        if slip > tol and _shown_not_falling(vp, motion, revs, n_orbit):
            vs.state = CREEPING  # not falling: steady or growing
            return CREEPING
        return SETTLING
    vs.remaining = slip * q / (1.0 - q)
    if rules.observe:
        return SETTLING  # a limit is an extrapolation: only what is seen counts
    # the limit decides only where its estimates agree, and on one side of tol
    if s_inf - spread > tol and s_inf >= vp.creep_share * slip and spread <= vp.limit_drift * s_inf:
        # most of today's slip persists in a limit that holds still: a settled ratchet
        vs.state = CREEPING
        return CREEPING
    if s_inf + spread <= tol:
        vs.state = COROTATING  # geometric decay to no slip: shakedown
        return COROTATING
    return SETTLING


@kernel_jit
def _shown_not_falling(vp, motion, revs, n_orbit):
    """Whether the slip per revolution over the newer half of the orbit history (at least
    vp.verdict_revs revolutions) is shown not to fall: the least-squares slope of its
    logarithm is shown steady (steady_slip.shown_steady, the test of a repeat's slip).
    Comparing the newest slip with one a quarter of the history back called a disk whose
    slip fell geometrically `creep`: one revolution's slip scatters about a falling level."""
    count = min(max(vp.verdict_revs, n_orbit // 2), REV_RING)
    slope, se = slip_slope(motion, revs, count)
    if math.isnan(slope):
        return False
    return shown_steady(vp, slope, se, count)


@kernel_jit
def _quiet(vp, motion, vs, revs):
    """The last vp.verdict_revs revolutions each slipped <= eps T and moved nothing."""
    for back in range(vp.verdict_revs):
        row = revs[_row(motion, back)]
        if not (row.slip <= vs.slip_tol and row.still):
            return False
    return True


@kernel_jit
def orbit_revolutions(motion, revs):
    """Consecutive revolutions, newest first, on the small orbit (some contact stuck at
    every instant; at most the ring)."""
    count = 0
    for back in range(min(motion.n_rev, REV_RING)):
        if not revs[_row(motion, back)].any_stuck:
            break
        count += 1
    return count


@kernel_jit
def sliding_revolutions(motion, revs):
    """Consecutive revolutions, newest first, without whole-body sticking at any instant."""
    count = 0
    for back in range(min(motion.n_rev, REV_RING)):
        if revs[_row(motion, back)].ever_all:
            break
        count += 1
    return count


@kernel_jit
def on_orbit(vp, motion, revs):
    """Whether the slave has kept its small orbit for the vp.verdict_revs revolutions that
    corotation_verdict reads. Its slip per revolution is then that verdict's to read: a
    braked disk creeping onto sticking and one settling to a ratchet both slow down there,
    and the section's shakedown (the smaller of a geometric and a power-law limit) took
    the second for the first."""
    return orbit_revolutions(motion, revs) >= vp.verdict_revs


@kernel_jit
def still_settling(vp, rules, motion, vs, revs):
    """Whether an undecided run at its horizon is still on its way to a verdict of the
    co-rotation rule: (corotation) before vp.verdict_revs revolutions, or on the small
    orbit (some contact stuck at every instant of the last revolution), where
    corotation_verdict decides every orbit in time."""
    if not rules.corotation or vs.state != SETTLING:
        return False
    if motion.n_rev < vp.verdict_revs:
        return True  # too few revolutions to tell any of the outcomes apart
    return orbit_revolutions(motion, revs) > 0
