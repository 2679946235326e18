"""Run bookkeeping for the outcome rules of docs/model.md section 6 (numba).

The monitor sees the run through a few calls from the driver (begin, step, switch) and
keeps what the classifier needs: whole-body sticking phases (every contact in stick),
the first sticking radius R1, section points at slide->stick entries for the limit-cycle
convergence test, the largest radius while sliding, and the sticking intervals of the
recent past (ring buffers) for the final-window stick fraction.

It also compares the state one master revolution apart (monitor_revolution): the net
plastic slip of the revolution, the drift of the slave centre and of the spin phase in the
master frame, and whether the contacts stuck throughout. These per-revolution rates decide
permanent co-rotation (`stick`) against ratcheting (`creep`) under stick_rule corotation
(corotation_verdict).

All state lives in two arrays (mf: float64, mi: int64), two ring buffers of sticking
intervals and one of revolutions, so the same functions serve the numba driver and the
scipy cross-check.
"""

import math

import numpy as np

from .events import hermite_max
from .jit import kernel_jit

# mf indices
F_T_ALL = 0  # start of the current whole-body sticking phase [s] (NaN if not all stick)
F_T_ANY = 1  # start of the current "some contact sticks" phase [s] (NaN if none)
F_R1 = 2  # first sticking radius [m]
F_T_R1 = 3  # time of first sticking [s]
F_R_SECT = 4  # radius at the last slide->stick section point [m]
F_ANG_SECT = 5  # angle at the last section point [rad]
F_RMAX = 6  # largest |r| in the current sliding phase [m]
F_A = 7  # excess a of the last completed sliding phase [m]
F_SIZE = 8  # radius of the last sticking segment [m]
F_DR1 = 9  # signed radius change between the last two section points [m]
F_DR2 = 10  # the one before [m]
F_CYCLE_TOL = 11
F_T_REV = 12  # start of the current revolution [s]
F_SLIP_REV = 13  # slip integral at the start of the current revolution [m]
F_LAMBDA = 14  # mean log decay of the slip per revolution over the verdict window [1/rev]
F_LAMBDA_SE = 15  # its standard error [1/rev]
F_REMAIN = 16  # predicted slip still to come under geometric decay [m]
F_ARM = 17  # longest contact arm max |p_i| [m] (0 for the pin)
F_SLIP_TOL = 18  # slip per revolution that counts as none: atol + eps T [m]
F_S_INF = 19  # extrapolated limit of the slip per revolution [m]
N_MF = 20

# mi indices
I_ALL = 0  # 1 while every contact sticks
I_ANY = 1  # 1 while some contact sticks
I_NTRANS = 2  # contact mode switches
I_NSECT = 3  # section points seen
I_NAGREE = 4  # consecutive agreeing section points
I_RS_N = 5  # intervals pushed to the all-stick ring
I_RA_N = 6  # intervals pushed to the any-stick ring
I_CYCLE_COUNT = 7
I_NQ = 8
I_NREV = 9  # revolutions completed
I_REV_NOT_ALL = 10  # 1 once not every contact stuck during the current revolution
I_REV_NONE = 11  # 1 once no contact stuck during the current revolution
I_REV_NTRANS = 12  # mode switches before the current revolution
I_REV_EVER_ALL = 13  # 1 once every contact stuck at some instant of the current revolution
I_VERDICT = 14  # the last corotation_verdict (VERDICT_*)
I_REV_STEPS = 15  # integrator steps before the current revolution
N_MI = 16

# Columns of the revolution ring rv (one row per completed revolution, newest at
# (I_NREV - 1) % REV_RING)
RV_T = 0  # end of the revolution [s]
RV_SLIP = 1  # net plastic slip of the mean contact, sum_i w_i int |w_i'| dt [m]
RV_DRIFT_R = 2  # |r(t) - r(t - T)|: drift of the slave centre in the master frame [m]
RV_DRIFT_PHI = 3  # phi(t) - phi(t - T) - omega_m T: drift of the spin phase [rad]
RV_SWITCHES = 4  # contact mode switches during the revolution
RV_ALL_STUCK = 5  # 1 if every contact stuck throughout the revolution
RV_ANY_STUCK = 6  # 1 if some contact stuck at every instant of the revolution
RV_EVER_ALL = 7  # 1 if every contact stuck at some instant of the revolution
RV_STILL = 8  # 1 if centre and spin phase repeated within the integrator's tolerance
RV_STICK_T = 9  # time with every contact stuck during the revolution [s]
N_RV = 10
REV_RING = 64

# corotation_verdict
VERDICT_NONE = 0
VERDICT_STICK = 1
VERDICT_CREEP = 2

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

RING = 16384


@kernel_jit
def _radius(y):
    return math.sqrt(y[0] * y[0] + y[1] * y[1])


@kernel_jit
def _push(ring, count, t0, t1):
    k = count % ring.shape[0]
    ring[k, 0] = t0
    ring[k, 1] = t1


@kernel_jit
def monitor_begin(mf, mi, ring_all, ring_any, t, y, modes, nq, cycle_tol, cycle_count):
    """Initialise the monitor at the start of a run."""
    mf[:] = np.nan
    mi[:] = 0
    mf[F_RMAX] = _radius(y)
    mf[F_CYCLE_TOL] = cycle_tol
    mi[I_CYCLE_COUNT] = cycle_count
    mi[I_NQ] = nq
    mf[F_T_REV] = t
    mf[F_SLIP_REV] = 0.0
    _update_phases(mf, mi, ring_all, ring_any, t, y, modes)


@kernel_jit
def _update_phases(mf, mi, ring_all, ring_any, t, y, modes):
    n_stick = 0
    for i in range(modes.shape[0]):
        if modes[i] == 1:
            n_stick += 1
    all_now = n_stick == modes.shape[0]
    any_now = n_stick > 0
    if any_now and mi[I_ANY] == 0:
        mf[F_T_ANY] = t
    if not any_now and mi[I_ANY] == 1:
        _push(ring_any, mi[I_RA_N], mf[F_T_ANY], t)
        mi[I_RA_N] += 1
        mf[F_T_ANY] = np.nan
    mi[I_ANY] = 1 if any_now else 0
    if not all_now:
        mi[I_REV_NOT_ALL] = 1
    if not any_now:
        mi[I_REV_NONE] = 1
    if all_now:
        mi[I_REV_EVER_ALL] = 1
    if all_now and mi[I_ALL] == 0:
        _enter_body_stick(mf, mi, t, y)
    if not all_now and mi[I_ALL] == 1:
        _push(ring_all, mi[I_RS_N], mf[F_T_ALL], t)
        mi[I_RS_N] += 1
        mf[F_T_ALL] = np.nan
        mf[F_RMAX] = _radius(y)
    mi[I_ALL] = 1 if all_now else 0


@kernel_jit
def _enter_body_stick(mf, mi, t, y):
    """A slide->stick section point of the whole body."""
    radius = _radius(y)
    angle = math.atan2(y[1], y[0])
    mf[F_T_ALL] = t
    if math.isnan(mf[F_R1]):
        mf[F_R1] = radius
        mf[F_T_R1] = t
    else:
        mf[F_A] = mf[F_RMAX] - radius
        dr = radius - mf[F_R_SECT]
        dang = angle - mf[F_ANG_SECT]
        dang = (dang + math.pi) % (2.0 * math.pi) - math.pi
        tol = mf[F_CYCLE_TOL]
        # A slow outward creep (growing, one-signed radius steps) is a departure, not convergence.
        creeping = (
            not math.isnan(mf[F_DR2])
            and dr * mf[F_DR1] > 0.0
            and mf[F_DR1] * mf[F_DR2] > 0.0
            and abs(dr) > abs(mf[F_DR1]) > abs(mf[F_DR2])
        )
        # a creep of one sign with small, steady steps shows in the net drift
        drift = dr + (0.0 if math.isnan(mf[F_DR1]) else mf[F_DR1])
        drift += 0.0 if math.isnan(mf[F_DR2]) else mf[F_DR2]
        steady = abs(drift) <= tol
        if abs(dr) <= tol and abs(dang) * radius <= tol and steady and not creeping:
            mi[I_NAGREE] += 1
        else:
            mi[I_NAGREE] = 0
        mf[F_DR2] = mf[F_DR1]
        mf[F_DR1] = dr
    mf[F_R_SECT] = radius
    mf[F_ANG_SECT] = angle
    mf[F_SIZE] = radius
    mi[I_NSECT] += 1


@kernel_jit
def monitor_step(mf, mi, y0, y1, h):
    """Track the largest radius while sliding, using the cubic Hermite of |r| over the step."""
    if mi[I_ALL] == 1:
        return
    nq = mi[I_NQ]
    r0 = _radius(y0)
    r1 = _radius(y1)
    best = max(r0, r1)
    if r0 > 0.0 and r1 > 0.0:
        d0 = h * (y0[0] * y0[nq] + y0[1] * y0[nq + 1]) / r0
        d1 = h * (y1[0] * y1[nq] + y1[1] * y1[nq + 1]) / r1
        hm, hs = hermite_max(r0, r1, d0, d1)
        if hs >= 0.0 and hm > best:
            best = hm
    if best > mf[F_RMAX] or math.isnan(mf[F_RMAX]):
        mf[F_RMAX] = best


@kernel_jit
def monitor_switch(mf, mi, ring_all, ring_any, t, y, modes, n_switched):
    """Register contact mode switches at time t (modes are the new modes)."""
    mi[I_NTRANS] += n_switched
    _update_phases(mf, mi, ring_all, ring_any, t, y, modes)


@kernel_jit
def stuck_for(mf, mi, t):
    """How long every contact has stuck without interruption at time t [s] (0 if not)."""
    if mi[I_ALL] == 0:
        return 0.0
    return t - mf[F_T_ALL]


@kernel_jit
def cycle_converged(mi):
    return mi[I_NAGREE] >= mi[I_CYCLE_COUNT]


@kernel_jit
def _overlap(ring, count, open_start, t_lo, t_hi):
    total = 0.0
    n = min(count, ring.shape[0])
    for k in range(n):
        a = max(ring[k, 0], t_lo)
        b = min(ring[k, 1], t_hi)
        if b > a:
            total += b - a
    if not math.isnan(open_start):
        a = max(open_start, t_lo)
        if t_hi > a:
            total += t_hi - a
    return total


@kernel_jit
def window_fractions(mf, mi, ring_all, ring_any, t_end, window):
    """Fractions of [t_end - window, t_end] with every contact / some contact sticking."""
    t_lo = max(0.0, t_end - window)
    span = t_end - t_lo
    if span <= 0.0:
        frac_all = 1.0 if mi[I_ALL] == 1 else 0.0
        frac_any = 1.0 if mi[I_ANY] == 1 else 0.0
        return frac_all, frac_any
    frac_all = _overlap(ring_all, mi[I_RS_N], mf[F_T_ALL], t_lo, t_end) / span
    frac_any = _overlap(ring_any, mi[I_RA_N], mf[F_T_ANY], t_lo, t_end) / span
    return frac_all, frac_any


@kernel_jit
def begin_revolution(mf, mi, t, y, slip, yrev, steps):
    """Start a revolution at time t after `steps` integrator steps: remember the state
    (yrev) and the slip integral [m]."""
    mi[I_REV_STEPS] = steps
    mf[F_T_REV] = t
    mf[F_SLIP_REV] = slip
    mi[I_REV_NOT_ALL] = 1 - mi[I_ALL]
    mi[I_REV_NONE] = 1 - mi[I_ANY]
    mi[I_REV_EVER_ALL] = mi[I_ALL]
    mi[I_REV_NTRANS] = mi[I_NTRANS]
    yrev[:] = y


@kernel_jit
def monitor_revolution(mf, mi, rv, yrev, ring_all, t, y, slip, spin, rtol, atol, steps):
    """Close the revolution ending at t (state y, slip integral [m], `steps` integrator
    steps so far) and start the next.

    spin: the master's rotation over one revolution, omega_m T [rad]. The master frame has
    turned by a whole number of turns, so its drift is the plain difference of the states.
    RV_STILL compares the drifts with the integrator's own tolerance accumulated over the
    revolution's steps: each step may err by atol + rtol |y|, so a stuck slave drifts by
    up to that many times it (measured: a stuck pin at rtol 1e-8 drifts 1.5e-9 m per
    revolution, more than one step's 1.5e-9 m, whatever the horizon).
    """
    n_steps = max(1, steps - mi[I_REV_STEPS])
    nq = mi[I_NQ]
    k = mi[I_NREV] % REV_RING
    dx = y[0] - yrev[0]
    dy = y[1] - yrev[1]
    dphi = (y[2] - yrev[2] - spin) if nq == 3 else 0.0
    rv[k, RV_T] = t
    rv[k, RV_SLIP] = slip - mf[F_SLIP_REV]
    rv[k, RV_DRIFT_R] = math.sqrt(dx * dx + dy * dy)
    rv[k, RV_DRIFT_PHI] = dphi
    rv[k, RV_SWITCHES] = mi[I_NTRANS] - mi[I_REV_NTRANS]
    rv[k, RV_ALL_STUCK] = 1.0 - mi[I_REV_NOT_ALL]
    rv[k, RV_ANY_STUCK] = 1.0 - mi[I_REV_NONE]
    rv[k, RV_EVER_ALL] = mi[I_REV_EVER_ALL]
    arm = mf[F_ARM]
    radius = math.sqrt(y[0] * y[0] + y[1] * y[1])
    still_r = rv[k, RV_DRIFT_R] <= n_steps * (atol + rtol * radius)
    still_phi = abs(dphi) * arm <= n_steps * (atol + rtol * arm)
    rv[k, RV_STILL] = 1.0 if still_r and still_phi else 0.0
    rv[k, RV_STICK_T] = _overlap(ring_all, mi[I_RS_N], mf[F_T_ALL], mf[F_T_REV], t)
    mi[I_NREV] += 1
    begin_revolution(mf, mi, t, y, slip, yrev, steps)


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
