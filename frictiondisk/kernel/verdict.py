"""The co-rotation verdict and the evidence a run needs to end without sticking (numba).

From the revolution ring rv that the monitor fills (kernel/monitor.py, monitor_revolution):
`corotation_verdict` decides permanent co-rotation (`stick`) against ratcheting (`creep`)
under stick_rule corotation. `shaken_down` decides `stick` from the motion's own section
(kernel/sections.py): a slip per cycle or revolution that falls to nothing.
`horizon_evidence` tells whether a run without a verdict at its horizon may end as not
stick: only on evidence from the section (a cycle reached, a geometric approach to one, a
departure from sticking); otherwise it must go on. The thresholds of
these rules are the constants below and in kernel/sections.py.
"""

import math

from . import sections as sec
from . import shakedown_bound as sdb
from .jit import kernel_jit
from .line_fit import slope_and_error
from .model import P_BETAB, P_BETAI, P_CS, P_EPS, P_FNI, P_MU, P_OMEGA, P_XMS
from .monitor_slots import (
    EV_CANNOT,
    EV_NONE,
    EV_REPEAT,
    EV_SHAKEDOWN,
    EV_SLIDING,
    F_ARM,
    F_ATOL,
    F_LAMBDA,
    F_LAMBDA_SE,
    F_REMAIN,
    F_RTOL,
    F_S_INF,
    F_S_INF_SPREAD,
    F_SLIP_TOL,
    I_BOUND,
    I_EV_SOURCE,
    I_EVIDENCE,
    I_NREV,
    I_OBSERVE,
    I_RS_N,
    I_VERDICT,
    RA_T0,
    REV_RING,
    RV_ALL_STUCK,
    RV_ANY_STUCK,
    RV_EVER_ALL,
    RV_SLIP,
    RV_STILL,
    RV_T,
    RV_W,
    SOURCE_CYCLES,
    SOURCE_REVOLUTIONS,
    VERDICT_CREEP,
    VERDICT_NONE,
    VERDICT_STICK,
)
from .steady_slip import shown_steady

# Revolutions behind a verdict on the slip trend. Five give four decay ratios, enough for
# a standard error; fewer make one grazing contact's lumpy slip look like a trend.
VERDICT_REVS = 5
# Revolutions of whole-body sliding behind EV_SLIDING: a slip that fell at every one of
# them is an approach to sticking; one that did not wanders or grows.
SLIDE_REVS = 8
# Standard errors by which a decay must be established (about 97.5 % one-sided).
VERDICT_Z = 2.0
# Spacing (revolutions) below which Aitken's limit is not trusted: measured on the braked
# disk, spacings of 2 revolutions still mistake the last fast transient for the limit
# (from rest, beta_b = 0.005, mu = 0.22: limit 4.5e-8 m read at 51 s, true limit 0).
AITKEN_MIN_SPACING = 4
# Largest spread of the limit's estimates (made 0 ... m revolutions back), as a fraction of
# the limit, for a ratchet to count as settled. An exact S_inf + A q^k spreads by 0; the
# braked disks that the well-posedness study found creeping onto sticking spread by 13-96 %
# (seed 5 scene 29: 10.3 ... 9.1e-9 m over 4 revolutions; it sticks at 482 s).
LIMIT_DRIFT = 0.02


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
def _slip_slope(mi, rv, count):
    """Least-squares slope of ln(slip per revolution) against the revolution over the last
    `count` revolutions, and its standard error [1/rev]; NaN, NaN if a slip is 0. Unlike
    the mean of successive ratios it is not masked by a slip that alternates from one
    revolution to the next about a falling level."""
    sum_k = sum_y = sum_kk = sum_ky = sum_yy = 0.0
    for back in range(count):
        slip = rv[_row(mi, back), RV_SLIP]
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
def _aitken(mi, rv, m, shift):
    """Aitken's limit of the slip per revolution [m] from the revolutions shift, shift + m
    and shift + 2 m before the newest, and the decay ratio per revolution behind it;
    (NaN, NaN) unless the slip falls and its fall slows down (the only shape a limit can
    be read from). S = S_inf + A q^k gives S_inf exactly: 0 for geometric decay to
    shakedown, > 0 for a ratchet settling to its steady rate."""
    s_a = rv[_row(mi, shift + 2 * m), RV_SLIP]
    s_b = rv[_row(mi, shift + m), RV_SLIP]
    s_c = rv[_row(mi, shift), RV_SLIP]
    limit = sec.aitken_limit(s_a, s_b, s_c, 1.0)
    if math.isnan(limit):
        return math.nan, math.nan
    return limit, ((s_b - s_c) / (s_a - s_b)) ** (1.0 / m)


@kernel_jit
def _limit_slip(mi, rv, n_orbit):
    """Aitken's limit S_inf of the slip per revolution [m] over the newer three quarters of
    the orbit history (spacing m = n_orbit // 4 >= AITKEN_MIN_SPACING: the oldest quarter
    holds the fast transients of the approach), the decay ratio per revolution behind it,
    and the lowest and highest of the same estimates made 0 ... m revolutions earlier [m].
    A motion S_inf + A q^k gives every estimate exactly. A fall that slows down more than
    geometrically (a power law; a braked disk near its shakedown bound, whose ratchet dies
    out ever more slowly) gives estimates that fall with the slip, so the true limit lies
    below the newest; one that levels off faster gives estimates that rise. (NaN, NaN,
    NaN, NaN) if there is no limit to read; lowest -inf, highest inf if an earlier
    estimate has none."""
    m = min(n_orbit // 4, (REV_RING - 1) // 4)
    if m < AITKEN_MIN_SPACING:
        return math.nan, math.nan, math.nan, math.nan
    s_inf, q = _aitken(mi, rv, m, 0)
    if math.isnan(s_inf):
        return math.nan, math.nan, math.nan, math.nan
    lowest = s_inf
    highest = s_inf
    for shift in range(1, min(m, n_orbit - 1 - 2 * m) + 1):
        s_then, _ = _aitken(mi, rv, m, shift)
        if math.isnan(s_then):
            return s_inf, q, -math.inf, math.inf
        lowest = min(lowest, s_then)
        highest = max(highest, s_then)
    return s_inf, q, lowest, highest


@kernel_jit
def corotation_verdict(mf, mi, rv):
    """Permanent co-rotation (`stick`), ratcheting (`creep`) or not yet decided, from the
    revolutions the slave spent on its small orbit (some contact stuck at every instant).
    `tol` = eps T [m] is the slip per revolution that counts as none: the slip that the
    slide->stick threshold eps [m/s] leaves unresolved over one revolution T (a contact
    re-sticks only once its plastic rate falls below eps, so slower slip is below the
    friction law's own resolution). It is a model quantity: no integrator tolerance enters
    it, so stick and creep mean the same at every rtol and atol.

    stick: every contact stuck throughout the last revolution and it moved nothing (centre
    drift and spin-phase drift, as the arc of the longest arm, within the integrator's
    tolerance atol + rtol |r|, atol + rtol |arm|: RV_STILL); or, on the small orbit for
    VERDICT_REVS revolutions, each of them moved nothing and slipped <= tol (contacts that
    graze their limit without net slip); or the slip
    per revolution decays geometrically (falling, its fall slowing as S_inf + A q^k) to
    an extrapolated limit S_inf with S_inf + spread <= tol: shakedown.
    creep: the slip per revolution exceeds tol and either no longer falls (over the newer
    half of the orbit history) or falls towards a limit that holds at least half of it,
    with S_inf - spread > tol and a spread within LIMIT_DRIFT of S_inf: a settled ratchet.
    spread: how far the same estimate, made 0 ... m revolutions earlier, ranged. Near a
    braked disk's shakedown bound the ratchet dies out ever more slowly, or levels off
    late, and the estimates wander with it; a limit decides only where they agree.
    Otherwise the verdict waits (and the run goes on, or ends undetermined).
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
    if _quiet(mf, mi, rv):
        mf[F_REMAIN] = 0.0
        mi[I_VERDICT] = VERDICT_STICK  # grazing contacts, but no slip to resolve
        return VERDICT_STICK
    lam, se = _slip_trend(mf, mi, rv)
    mf[F_LAMBDA] = lam
    mf[F_LAMBDA_SE] = se
    s_inf, q, lowest, highest = _limit_slip(mi, rv, n_orbit)
    mf[F_S_INF] = s_inf
    spread = highest - lowest
    mf[F_S_INF_SPREAD] = spread
    if math.isnan(s_inf):
        if slip > tol and _shown_not_falling(mi, rv, n_orbit):
            mi[I_VERDICT] = VERDICT_CREEP  # not falling: steady or growing
            return VERDICT_CREEP
        return VERDICT_NONE
    mf[F_REMAIN] = slip * q / (1.0 - q)
    if mi[I_OBSERVE] == 1:
        return VERDICT_NONE  # a limit is an extrapolation: only what is seen counts
    # the limit decides only where its estimates agree, and on one side of tol
    if s_inf - spread > tol and s_inf >= 0.5 * slip and spread <= LIMIT_DRIFT * s_inf:
        # most of today's slip persists in a limit that holds still: a settled ratchet
        mi[I_VERDICT] = VERDICT_CREEP
        return VERDICT_CREEP
    if s_inf + spread <= tol:
        mi[I_VERDICT] = VERDICT_STICK  # geometric decay to no slip: shakedown
        return VERDICT_STICK
    return VERDICT_NONE


@kernel_jit
def _shown_not_falling(mi, rv, n_orbit):
    """Whether the slip per revolution over the newer half of the orbit history (at least
    VERDICT_REVS revolutions) is shown not to fall: the least-squares slope of its
    logarithm is shown steady (steady_slip.shown_steady, the test of a repeat's slip).
    Comparing the newest slip with one a quarter of the history back called a disk whose
    slip fell by 9 % a revolution `creep` (well-posedness seed 1 scene 17, mu = 0.2945,
    at 59 s: its slip falls geometrically from 7e-9 to 6.5e-10 m by 600 s and it sticks):
    one revolution's slip scatters about a falling level."""
    count = min(max(VERDICT_REVS, n_orbit // 2), REV_RING)
    slope, se = _slip_slope(mi, rv, count)
    if math.isnan(slope):
        return False
    return shown_steady(slope, se, count)


@kernel_jit
def _quiet(mf, mi, rv):
    """The last VERDICT_REVS revolutions each slipped <= eps T and moved nothing."""
    for back in range(VERDICT_REVS):
        row = _row(mi, back)
        if not (rv[row, RV_SLIP] <= mf[F_SLIP_TOL] and rv[row, RV_STILL] == 1.0):
            return False
    return True


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
def _on_orbit(mi, rv):
    """Whether the slave has kept its small orbit (some contact stuck at every instant) for
    the VERDICT_REVS revolutions that corotation_verdict reads. Its slip per revolution is
    then that verdict's to read: a braked disk creeping onto sticking and one settling to
    a ratchet both slow down there, and the section's shakedown (the smaller of a
    geometric and a power-law limit) took the second for the first (well-posedness seed 5
    scene 11, mu = 0.26081: read as shaken down at 151 s, ratchets 2.3e-8 m a revolution
    for good)."""
    return _run_length(mi, rv, RV_ANY_STUCK, 1.0) >= VERDICT_REVS


@kernel_jit
def still_settling(mf, mi, rv, corotation):
    """Whether an undecided run at its horizon is still on its way to a verdict of the
    co-rotation rule: (corotation) before VERDICT_REVS revolutions, or on the small orbit
    (some contact stuck at every instant of the last revolution), where
    corotation_verdict decides every orbit in time."""
    if not corotation or mi[I_VERDICT] != VERDICT_NONE:
        return False
    if mi[I_NREV] < VERDICT_REVS:
        return True  # too few revolutions to tell any of the outcomes apart
    return _run_length(mi, rv, RV_ANY_STUCK, 1.0) > 0


@kernel_jit
def _spinning_up(mf, mi, rv):
    """Whether the slave's spin came closer to co-rotation, by more than the integrator's
    tolerance, at each of the last SLIDE_REVS revolutions: an approach to sticking, not a
    sliding state. A Stribeck disk from rest (well-posedness seed 1 scene 11) spins up at
    every revolution while its slip per revolution rises now and then: read as sliding at
    145 s, it sticks at 162 s. (A spin drifting away from co-rotation, as a braked disk's
    does while it slowly leaves sticking, is no approach.) In metres: the spin rate times
    the longest arm over omega_m, which is the arm itself at co-rotation (0 for the pin)."""
    arm = mf[F_ARM]
    if arm <= 0.0:
        return False
    for back in range(SLIDE_REVS - 1):
        new = abs(rv[_row(mi, back), RV_W] - arm)
        old = abs(rv[_row(mi, back + 1), RV_W] - arm)
        if not new < old - (mf[F_ATOL] + mf[F_RTOL] * arm):
            return False
    return True


@kernel_jit
def steady_sliding(mf, mi, rv):
    """Whether the run has slid as a whole (no whole-body stick) for SLIDE_REVS revolutions
    at a slip per revolution that did not fall at every one of them (a slip falling
    revolution after revolution is an approach to sticking, however slowly it falls: a
    Stribeck disk spinning up slides 0.2 m a revolution, 1 % less each time, and sticks
    at 97 s), whose decay is not established at VERDICT_Z standard errors, neither by the
    slope of ln(slip) over the SLIDE_REVS revolutions nor over the last VERDICT_REVS
    (a pin at seed 6 scene 32, mu = 0.07647, slid 2.4, 2.5, 1.8, 1.8, 1.4, 1.3 e-2 m a
    revolution, read as sliding at 121 s; it sticks at 292 s): a sliding orbit whose
    slip wanders about a level (its period not the master's) or grows."""
    if _run_length(mi, rv, RV_EVER_ALL, 0.0) < SLIDE_REVS:
        return False
    if _spinning_up(mf, mi, rv):
        return False
    falling = True
    for back in range(SLIDE_REVS - 1):
        falling = falling and rv[_row(mi, back), RV_SLIP] < rv[_row(mi, back + 1), RV_SLIP]
    if falling:
        return False
    slope, slope_se = _slip_slope(mi, rv, SLIDE_REVS)
    if slope + VERDICT_Z * slope_se < 0.0:
        return False  # falls over the window, alternating on the way (seed 6 scene 32)
    lam, se = _slip_trend(mf, mi, rv)
    return math.isnan(lam) or lam + VERDICT_Z * se >= 0.0


@kernel_jit
def _cycles_recent(mi, ring_all, rv):
    """Whether the newest whole-body sticking phase began within the last two revolutions
    (older cycles say nothing about the motion now)."""
    if mi[I_RS_N] < 1 or mi[I_NREV] < 2:
        return False
    newest = ring_all[(mi[I_RS_N] - 1) % ring_all.shape[0], RA_T0]
    return newest >= rv[_row(mi, 1), RV_T] - (rv[_row(mi, 0), RV_T] - rv[_row(mi, 1), RV_T])


@kernel_jit
def _section(mf, mi, ring_all, rv, omega, hold, seq, source):
    """The evidence of the cycle or revolution section (kernel/sections.py); seq: scratch
    (sections.SEQ_MAX, sections.N_SEQ)."""
    if source == SOURCE_CYCLES:
        if not _cycles_recent(mi, ring_all, rv):
            return EV_NONE
        n = sec.cycle_sequence(mi, ring_all, omega, seq)
    else:
        n = sec.revolution_sequence(mi, rv, seq)
    if n < 2:
        return EV_NONE
    period = sec.newest_period(mi, ring_all, rv, source == SOURCE_CYCLES)
    return sec.section_evidence(mf, mi, seq, n, sec.slip_tolerance(mf, period, hold))


@kernel_jit
def shaken_down(mf, mi, ring_all, rv, omega, hold, seq):
    """Whether the slip per cycle (whole-body sticking onsets, while they are recent) or per
    revolution falls to an extrapolated limit within tolerance: `stick` by shakedown
    (kernel/sections.py, EV_SHAKEDOWN). Sets the monitor's evidence slots."""
    if mi[I_OBSERVE] == 1:
        return False  # a limit is an extrapolation: only what is seen counts
    for source in (SOURCE_CYCLES, SOURCE_REVOLUTIONS):
        if source == SOURCE_REVOLUTIONS and _on_orbit(mi, rv):
            continue  # corotation_verdict reads this slip, with its estimates' agreement
        if _section(mf, mi, ring_all, rv, omega, hold, seq, source) == EV_SHAKEDOWN:
            mi[I_EVIDENCE] = EV_SHAKEDOWN
            mi[I_EV_SOURCE] = source
            return True
    return False


@kernel_jit
def horizon_evidence(mf, mi, ring_all, rv, omega, hold, seq):
    """The evidence (EV_*) on which an undecided run at its horizon may end as not stick:
    the section of its recent whole-body sticking onsets or of its revolutions shows a
    cycle reached, a geometric approach to one or a departure from sticking (a sliding
    slave's revolutions are its section: a steady sliding state repeats or is approached
    geometrically), or it slides on without approaching sticking (EV_SLIDING). EV_NONE: it
    must go on (or end undetermined). A shakedown found here is EV_SHAKEDOWN (stick).
    Sets the monitor's evidence slots."""
    best = EV_NONE
    observe = mi[I_OBSERVE] == 1
    for source in (SOURCE_CYCLES, SOURCE_REVOLUTIONS):
        ev = _section(mf, mi, ring_all, rv, omega, hold, seq, source)
        if ev == EV_REPEAT or (ev != EV_NONE and not observe):
            best = ev
            mi[I_EV_SOURCE] = source
            break
    if best == EV_NONE and not observe and steady_sliding(mf, mi, rv):
        best = EV_SLIDING
        mi[I_EV_SOURCE] = SOURCE_REVOLUTIONS
    mi[I_EVIDENCE] = best
    return best


@kernel_jit
def cannot_corotate(p, pts, arm, bound):
    """Whether no permanent co-rotation can be held at all, whatever the circle: a rigidly
    co-rotating slave needs a contact force whose largest value over a revolution is at
    least the spring's pull c_s |x_ms| (the preload sweeps every direction; docs/model.md
    section 7), and a torque beta_b omega_m that no contact force pattern within mu F_n
    can carry beyond a lever of the longest arm. Below either, the slave can never stick:
    a bound, not a measurement (kernel/sections.py EV_CANNOT). The band beta eps of the
    stuck contacts is added to the friction limit. arm: longest contact arm [m] (0: pin).
    bound: the shakedown bound applies (kernel/shakedown_bound.py); then also below the
    least shakedown demand of any circle, by more than the bound's margin."""
    hold = 0.0
    for i in range(pts.shape[0]):
        hold += (p[P_MU] * p[P_FNI] + p[P_BETAI] * p[P_EPS]) * pts[i, 2]
    pull = p[P_CS] * abs(p[P_XMS])
    if arm > 0.0:
        pull = max(pull, abs(p[P_BETAB] * p[P_OMEGA]) / arm)
    if hold < pull:
        return True
    if not bound:
        return False
    return sdb.floor_reserve(p, pts) < -sdb.run_margin(p)


@kernel_jit
def evidence_at_horizon(p, pts, mf, mi, ring_all, rv, omega, hold, seq, corotation, held):
    """What an undecided run at its horizon may end on (EV_*; EV_NONE: it must go on): a
    bound that no co-rotation can pass (EV_CANNOT), its section (horizon_evidence), or,
    stick_rule contacts, a sticking phase already held or open (then EV_REPEAT: the rule's
    own decision follows in the driver). A run still settling towards a co-rotation verdict
    (still_settling) goes on. Under stick_rule contacts a shakedown to co-rotation with
    grazing contacts is no `stick` (that rule needs every contact stuck for a revolution)
    and counts as not-stick evidence."""
    if cannot_corotate(p, pts, mf[F_ARM], mi[I_BOUND] == 1):
        mi[I_EVIDENCE] = EV_CANNOT
        return EV_CANNOT
    if held:
        return EV_REPEAT
    evidence = horizon_evidence(mf, mi, ring_all, rv, omega, hold, seq)
    if evidence == EV_SHAKEDOWN and corotation:
        if mi[I_EV_SOURCE] == SOURCE_REVOLUTIONS and _on_orbit(mi, rv):
            return EV_NONE  # as in shaken_down: corotation_verdict decides this slip
        return EV_SHAKEDOWN
    if still_settling(mf, mi, rv, corotation):
        return EV_NONE
    return evidence
