"""Evidence from the motion's own section (numba): is a run that has not stuck converging
to a cycle, moving away from sticking, or shaking down to sticking? (docs/model.md section 6)

The monitor keeps two sections of the motion:

* cycles: the onset of every whole-body sticking phase (ring_all): the slave centre there,
  the arc it then sticks for, and the slip and time to the next onset;
* revolutions: the state at the end of every whole master revolution (rv): centre,
  velocity and spin rate, all in metres.

Each gives a sequence of section points p_n [m] with the slip s_n [m] and the sticking
time tau_n [s] of each step between them. The rules read those sequences only; averages
over windows are never evidence, because a transient's scatter hides its trend.

* EV_REPEAT: the last REPEAT_COUNT distances |p_n - p_{n-L}| lie within the integrator's
  own tolerance accumulated over a step (L = 1 .. MAX_LAG: a cycle that sticks L times
  per period): the motion has reached its cycle. Where it slips less than that tolerance
  a period, its slip per period must also be shown steady (kernel/steady_slip.py).
* EV_CONTRACT: the distances |p_n - p_{n-1}| shrink by a ratio q whose own changes shrink
  (or are tiny), and the ratio extrapolated from them stays <= Q_MAX: a geometric
  approach to a cycle, whose slip per step extrapolates to a limit above the slip
  tolerance (a cycle, not an approach to sticking). An approach with a growing ratio (a
  slow passage, or sticking ahead) is no evidence.
* EV_DEPART: for DEPART_STEPS steps the slip per step (above the slip tolerance) grows,
  the sticking time shrinks and the distances do not shrink: it moves away from sticking.
* EV_SHAKEDOWN (stick): the slip per step falls at every step over the newer three
  quarters of the sequence, and extrapolates to a limit <= the slip tolerance and at most
  SHAKEDOWN_ZERO of the slip still left (nothing; a floor below s0 is a cycle): Aitken's
  limit over equally spaced steps (geometric decay), or over steps n/2, n/sqrt 2, n (a power
  law, the slow creep onto a grazing sticking circle). Both are exact for their model.
"""

import math

from .jit import kernel_jit
from .monitor_slots import (
    EV_CONTRACT,
    EV_DEPART,
    EV_NONE,
    EV_REPEAT,
    EV_SHAKEDOWN,
    F_ATOL,
    F_CYCLE_TOL,
    F_EV_D,
    F_EV_LIMIT,
    F_EV_Q,
    F_EV_QUP,
    F_RTOL,
    F_SLIP_TOL,
    I_EV_LAG,
    I_EV_STEPS,
    I_NREV,
    I_RS_N,
    I_STRIBECK,
    RA_SLIP,
    RA_T0,
    RA_T1,
    RA_X,
    RA_Y,
    REV_RING,
    RV_EVER_ALL,
    RV_SLIP,
    RV_STICK_T,
    RV_T,
    RV_U,
    RV_V,
    RV_W,
    RV_X,
    RV_Y,
)
from .steady_slip import STEADY_FALL, period_slip, steady

SEQ_MAX = 512  # newest section points read (the revolution ring's length)
N_COORD = 5  # coordinates of a section point [m]: columns 0 .. 4 of a sequence
SEQ_SLIP = 5  # column of the slip per step [m]
SEQ_STICK = 6  # column of the whole-body sticking time per step [s]
N_SEQ = 7  # columns of a sequence (the driver's scratch array, SEQ_MAX rows)
REPEAT_COUNT = 3  # distances within tolerance that make a repeat
MAX_LAG = 3  # sticking phases per period of a cycle recognised by EV_REPEAT
CONTRACT_DISTANCES = 5  # distances behind a contraction ratio and its trend
Q_MAX = 0.98  # largest extrapolated contraction ratio accepted as convergence
RHO_MAX = 0.9  # the ratio's own changes must shrink at least this fast ...
Q_STEADY = 0.01  # ... unless each of them is below this
GEOMETRIC_KEEP = 0.75  # 1 - q now must keep this share of 1 - q half the sequence ago
CONTRACT_SLIP_FALL = 0.1  # share of the slip per step that may still fall on the way ...
# ... under a Stribeck law, whose friction rises as the slip slows, feeding its own fall:
# only what a steady slip may lose (docs/model.md section 6, study scene 1/43)
CONTRACT_SLIP_FALL_STRIBECK = STEADY_FALL
SLIP_STEADY = 1e-4  # changes of the slip per step below this share of it are no change
DEPART_STEPS = 4  # steps of growing slip and shrinking sticking time behind EV_DEPART
STICK_NOISE = 1e-9  # [s] sticking times closer than this are equal (event location ~1e-11 s)
APPROACH_STEPS = 8  # steps over which a creep onto a sticking circle is recognised ...
APPROACH_FALL = 1e-3  # ... by a fall of the slip per step by more than this share of it
SHAKEDOWN_STEPS = 8  # steps needed before a slip limit is extrapolated
# ... and only once the slip per step has fallen below this share of its largest value: a
# first fall that looks geometric can level off at a cycle (the default pin at x_ms 0.05,
# mu 0.0501: 3.1e-2 -> 5.3e-3 m a revolution in 10 revolutions, then a stick-slip cycle)
SHAKEDOWN_DEPTH = 1e-2
# ... and to a limit that is nothing beside the slip still left: a fall that levels off at
# a slip below s0 is a cycle there, not sticking (the demo disk at x_ms 0.12, mu = 0.142785:
# 1.4e-9 m a revolution falling to a limit of 8.2e-10 m, then rising again, at 1 500 s)
SHAKEDOWN_ZERO = 1e-2
MIN_SPACING = 4  # least spacing of an Aitken triple: at 2 a last transient looks a limit
# The second fall of an Aitken triple must be at most this share of the first: a slip
# falling almost linearly gives no well-conditioned limit (a disk at x_ms 0.065, mu 0.0653
# fell 9.9e-4 then 8.4e-4 m in 4 revolutions each, extrapolating to 0, then kept a cycle
# slipping 2e-3 m). Over log-spaced steps n/2, n/sqrt(2), n: S ~ n^-p with p >= 1.03.
AITKEN_SLOWING = 0.7
# A power law's log-spaced fall ratio does not grow with n: it may have grown by at most
# this much since LOOKBACK n (a fall that levels off at a cycle grows it)
LOG_LOOKBACK = 0.75
LOG_RATIO_DRIFT = 0.03


@kernel_jit
def cycle_sequence(mi, ring_all, omega, seq):
    """Fill seq (oldest first) with the section of the whole-body sticking onsets: point
    (x, y, omega |r| tau) [m], slip to the next onset [m], sticking time tau [s]. The
    newest onset closes the last step. Returns the count."""
    n_phases = min(mi[I_RS_N], ring_all.shape[0], SEQ_MAX + 1)
    n = n_phases - 1
    if n < 1:
        return 0
    first = mi[I_RS_N] - n_phases
    for j in range(n):
        a = (first + j) % ring_all.shape[0]
        b = (first + j + 1) % ring_all.shape[0]
        tau = ring_all[a, RA_T1] - ring_all[a, RA_T0]
        seq[j, 0] = ring_all[a, RA_X]
        seq[j, 1] = ring_all[a, RA_Y]
        seq[j, 2] = omega * math.hypot(ring_all[a, RA_X], ring_all[a, RA_Y]) * tau
        seq[j, 3] = 0.0
        seq[j, 4] = 0.0
        seq[j, SEQ_SLIP] = ring_all[b, RA_SLIP] - ring_all[a, RA_SLIP]
        seq[j, SEQ_STICK] = tau
    return n


@kernel_jit
def revolution_sequence(mi, rv, seq):
    """Fill seq (oldest first) with the section of the whole master revolutions of the
    current regime (the trailing revolutions that all did, or all did not, stick as a whole
    at some instant: a slave that slid for ten revolutions and then began to stick has
    changed its motion, and the sliding revolutions say nothing about the cycle now): the
    state at each revolution's end [m], its slip [m] and whole-body sticking time [s].
    Returns the count."""
    n = min(mi[I_NREV], REV_RING, SEQ_MAX)
    newest = rv[(mi[I_NREV] - 1) % REV_RING, RV_EVER_ALL]
    for back in range(n):
        if rv[(mi[I_NREV] - 1 - back) % REV_RING, RV_EVER_ALL] != newest:
            n = back
            break
    first = mi[I_NREV] - n
    for j in range(n):
        r = (first + j) % REV_RING
        seq[j, 0] = rv[r, RV_X]
        seq[j, 1] = rv[r, RV_Y]
        seq[j, 2] = rv[r, RV_U]
        seq[j, 3] = rv[r, RV_V]
        seq[j, 4] = rv[r, RV_W]
        seq[j, SEQ_SLIP] = rv[r, RV_SLIP]
        seq[j, SEQ_STICK] = rv[r, RV_STICK_T]
    return n


@kernel_jit
def _distance(pts, i, j):
    acc = 0.0
    for c in range(N_COORD):
        d = pts[i, c] - pts[j, c]
        acc += d * d
    return math.sqrt(acc)


@kernel_jit
def _repeat_tolerance(mf, pts, i):
    """How far section point i may move between repeats of a converged cycle [m]:
    numerics.cycle_tol, or the integrator's tolerance atol + rtol |p| if larger. The
    integration error of a periodic orbit repeats with it, so a converged cycle moves far
    less than its accumulated error bound (measured: 1e-10 m at rtol 1e-6)."""
    size = 0.0
    for c in range(N_COORD):
        size = max(size, abs(pts[i, c]))
    return max(mf[F_CYCLE_TOL], mf[F_ATOL] + mf[F_RTOL] * size)


@kernel_jit
def _approaching(slip, stick, n, atol):
    """Whether, over the newest APPROACH_STEPS steps, the slip per step fell by more than
    APPROACH_FALL of itself and atol [m] while the sticking time grew (beyond STICK_NOISE):
    a slave creeping onto a sticking circle, however little its section moves per step.
    Compared half against half, the largest slip and the shortest sticking time of each,
    so a step that now and then sticks throughout (slip 0) is not taken for the trend
    (well-posedness seed 6 scene 32, mu = 0.0765753: every fifth revolution of its creep
    sticks whole). The atol floor stays: without it slowly converging cycles read as
    approaches (a pin with eps = 1e-3 m/s below its Coulomb bound), so a creep that
    falls by less than atol over the window (that pin at rtol 1e-5: 7e-9 m against
    1e-8 m) is still read as a cycle."""
    back = min(APPROACH_STEPS, n - 1)
    if back < 1:
        return False
    half = (back + 1) // 2
    slip_new, slip_old = 0.0, 0.0
    stick_new, stick_old = math.inf, math.inf
    for k in range(half):
        slip_new = max(slip_new, slip[n - 1 - k])
        stick_new = min(stick_new, stick[n - 1 - k])
        slip_old = max(slip_old, slip[n - 1 - back + k])
        stick_old = min(stick_old, stick[n - 1 - back + k])
    fell = slip_new < slip_old * (1.0 - APPROACH_FALL) - atol
    return fell and stick_new > stick_old + STICK_NOISE


@kernel_jit
def _repeats(mf, mi, pts, slip, stick, n):
    """EV_REPEAT: the newest REPEAT_COUNT distances at some lag L <= MAX_LAG within
    tolerance, and, where they still shrink step after step, the travel still to come
    (geometric tail) within tolerance too: a slow algebraic approach moves little per
    step but far in all. Never while the motion creeps towards sticking (_approaching),
    nor at a lag whose slip per period is within the tolerance unless that slip is shown
    steady (steady_slip.steady): such a motion lies within tolerance of itself whether it
    cycles or creeps (well-posedness seed 2 scene 24, mu = 0.105: a pin creeping onto its
    sticking disc, its slip per revolution falling from 1.4e-5 to 1.8e-8 m over 2 400 s,
    was read as a cycle within cycle_tol 1e-6 m; watched on, it sticks at 4 771 s). A
    steady slip below the tolerance repeats: a walk at 3e-7 m a revolution (a pin at eps =
    1e-3 m/s, below its Coulomb bound) is no approach to sticking."""
    if _approaching(slip, stick, n, mf[F_ATOL]):
        return False
    for lag in range(1, MAX_LAG + 1):
        if n < lag + REPEAT_COUNT + 1:
            break
        ok = True
        shrinking = True
        worst = 0.0
        newest = _distance(pts, n - 1, n - 1 - lag)
        d_prev = 0.0
        tol = _repeat_tolerance(mf, pts, n - 1)
        if period_slip(slip, n, lag, 0) <= tol and not steady(slip, n, lag):
            continue  # it slips less than tol a period: within tol whether it cycles or creeps
        for back in range(REPEAT_COUNT + 1):
            i = n - 1 - back
            d = _distance(pts, i, i - lag)
            if back < REPEAT_COUNT:
                worst = max(worst, d)
                ok = ok and d <= tol
            if back > 0:
                shrinking = shrinking and d_prev < d  # the newer distance is the smaller
            d_prev = d
        if ok and shrinking:
            older = _distance(pts, n - 2, n - 2 - lag)
            q = newest / older
            ok = q < 1.0 and newest * q / (1.0 - q) <= tol
        if ok:
            mf[F_EV_D] = worst
            mi[I_EV_LAG] = lag
            return True
    return False


@kernel_jit
def _contracts(mf, pts, slip, n, s0, fall_share):
    """EV_CONTRACT: the newest CONTRACT_DISTANCES distances shrink geometrically at an
    established ratio, towards a cycle whose slip per step stays above s0 and keeps all
    but `fall_share` of itself."""
    m = CONTRACT_DISTANCES
    if n < m + 1:
        return False
    d_prev = _distance(pts, n - m, n - m - 1)
    q_prev = math.nan
    dq_prev = math.nan
    rho = 0.0
    small = True
    q = math.nan
    dq = 0.0
    for k in range(m - 1):
        i = n - m + 1 + k
        d = _distance(pts, i, i - 1)
        if not (d > 0.0 and d_prev > 0.0):
            return False
        q = d / d_prev
        if not math.isnan(q_prev):
            dq = q - q_prev
            small = small and abs(dq) <= Q_STEADY
            if not math.isnan(dq_prev):
                if dq * dq_prev < 0.0 and not (abs(dq) <= Q_STEADY and abs(dq_prev) <= Q_STEADY):
                    return False  # the ratio turns back and forth: no steady contraction
                if dq_prev != 0.0:
                    rho = max(rho, abs(dq / dq_prev))
            dq_prev = dq
        q_prev = q
        d_prev = d
    # the ratio still grows by dq a step, each change rho times the last: its limit (no
    # bound where its changes do not shrink fast enough)
    q_up = math.inf
    if small or rho <= RHO_MAX:
        grow = max(0.0, dq) * (rho / (1.0 - rho) if rho < 1.0 else 2.0)
        q_up = q + grow + (2.0 * Q_STEADY if small else 0.0)
    mf[F_EV_D] = d_prev
    mf[F_EV_Q] = q
    mf[F_EV_QUP] = q_up
    if not q_up <= Q_MAX:
        return False
    # geometric, not algebraic: 1 - q stays put from half the sequence ago to now (a power
    # law S ~ n^-p has 1 - q ~ p / n, which halves)
    half = n // 2
    if half < 2:
        return False
    q_half = _distance(pts, half, half - 1) / max(_distance(pts, half - 1, half - 2), 1e-300)
    if not (q_half < 1.0 and (1.0 - q) >= GEOMETRIC_KEEP * (1.0 - q_half)):
        return False
    mf[F_EV_LIMIT] = d_prev * q_up / (1.0 - q_up)
    # the cycle it converges to still slips, nearly as much as now: the slip per step,
    # extrapolated at the slower of its own ratio and the section's (the distances can
    # shrink fast along one direction while the slip follows a slower one), keeps all but
    # fall_share of itself: a slip that still falls by much is an approach to sticking,
    # whatever its section's ratio (the cases: docs/model.md section 6, "contract")
    r = max(q_up, _slip_ratio_bound(slip, n, m, max(s0, SLIP_STEADY * slip[n - 1])))
    if not r < 1.0:
        return False
    fall = abs(slip[n - 1] - slip[n - 2]) * r / (1.0 - r)
    return slip[n - 1] - fall > s0 and fall <= fall_share * slip[n - 1]


@kernel_jit
def _slip_ratio_bound(slip, n, m, floor):
    """A bound on the ratio by which the changes of the slip per step shrink, from the
    newest m steps: the largest of their ratios, raised by as much as the ratio grew over
    them (a ratio still growing has not yet met the slow direction that sets the cycle).
    Changes below `floor` [m] count as none (ratio 0); inf: a change after none."""
    r_first = math.nan
    r_last = 0.0
    r_max = 0.0
    for i in range(n - m + 2, n):
        e_new = abs(slip[i] - slip[i - 1])
        e_old = abs(slip[i - 1] - slip[i - 2])
        if e_new <= floor:
            r = 0.0
        elif e_old <= floor:
            return math.inf
        else:
            r = e_new / e_old
        if math.isnan(r_first):
            r_first = r
        r_last = r
        r_max = max(r_max, r)
    return r_max + max(0.0, r_last - r_first)


@kernel_jit
def _departs(mf, pts, slip, stick, n, s0):
    """EV_DEPART: for DEPART_STEPS steps the slip per step did not fall and the sticking
    time did not grow (beyond atol and STICK_NOISE), and the distances did not shrink: a
    departure from sticking, accelerating or steady (a slow ratchet away). Not below a slip
    s0 per step: there it is the law's floor (a pin on its rim, docs/model.md section 6)."""
    m = DEPART_STEPS
    if n < m + 1 or not slip[n - 1] > s0:
        return False
    for back in range(m - 1):
        i = n - 1 - back
        if not (slip[i] >= slip[i - 1] - mf[F_ATOL] and stick[i] <= stick[i - 1] + STICK_NOISE):
            return False
    d_new = _distance(pts, n - 1, n - 2)
    for back in range(1, m - 1):
        i = n - 1 - back
        d_old = _distance(pts, i, i - 1)
        if d_new < d_old:
            return False
        d_new = d_old
    mf[F_EV_D] = _distance(pts, n - 1, n - 2)
    mf[F_EV_Q] = mf[F_EV_D] / max(_distance(pts, n - 2, n - 3), 1e-300)
    return True


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
def _log_aitken(slip, n):
    """Aitken's limit over the log-spaced steps of the newer half (NaN: no slowing fall)."""
    a, b, c = _log_steps(n)
    return aitken_limit(slip[a - 1], slip[b - 1], slip[c - 1], AITKEN_SLOWING)


@kernel_jit
def shakedown_limit(slip, stick, n):
    """The extrapolated limit [m] of a slip per step that falls at every step over the
    newer three quarters of the sequence while the slave sticks as a whole and its
    sticking time does not fall: the
    smaller of Aitken's limits over steps (n - 2m, n - m, n) with m = n // 4 (geometric
    decay) and over steps (n/2, n/sqrt 2, n) (a power law). NaN if the slip does not fall so."""
    if n < SHAKEDOWN_STEPS:
        return math.nan
    if not stick[n - 1] > 0.0:
        # a slave that slides ever less must first stick as a whole; what it does then (a
        # cycle, or co-rotation) decides: a disk at x_ms 0.065, mu 0.06505 slid 0.317 ->
        # 2.7e-3 m a revolution, then kept a stick-slip cycle slipping 4e-4 m
        return math.nan
    start = n // 4
    for i in range(start + 1, n):
        if not slip[i] < slip[i - 1]:
            return math.nan
    peak = 0.0
    for i in range(n):
        peak = max(peak, slip[i])
    if slip[n - 1] > SHAKEDOWN_DEPTH * peak:
        return math.nan  # most of the way still to go: no limit is read from a first fall
    if stick[n - 1] < stick[start]:
        return math.nan  # sticking less and less: no approach to sticking
    m = n // 4
    limit = math.nan
    if m >= MIN_SPACING:
        limit = aitken_limit(slip[n - 1 - 2 * m], slip[n - 1 - m], slip[n - 1], AITKEN_SLOWING)
    # log-spaced over the newer half, n/2, n/sqrt(2), n: exact for S_inf + A n^-p, and clear
    # of the first transient (a co-rotating disk falling 0.256 -> 0.027 m in its first
    # revolution, then as a power law to a cycle slipping 1e-3 m, read 0 from n/4)
    log_spaced = _log_aitken(slip, n)
    if not math.isnan(log_spaced):
        # a power law keeps its fall ratio as n grows; a fall levelling off at a cycle
        # raises it (a co-rotating disk: 0.69 at 36 revolutions, on its way to 5e-4 m)
        earlier = int(round(LOG_LOOKBACK * n))
        r_now, r_then = _log_ratio(slip, n), _log_ratio(slip, earlier)
        if not (r_now <= r_then + LOG_RATIO_DRIFT):
            log_spaced = math.nan
    if math.isnan(limit) or log_spaced < limit:
        limit = log_spaced
    return limit


@kernel_jit
def section_evidence(mf, mi, seq, n, s0):
    """The evidence (EV_*) of the section sequence in the first n rows of seq; diagnostics
    go to the monitor's F_EV_* and I_EV_* slots. s0: the slip per step that counts as none
    [m]."""
    mf[F_EV_D] = math.nan
    mf[F_EV_Q] = math.nan
    mf[F_EV_QUP] = math.nan
    mf[F_EV_LIMIT] = math.nan
    mi[I_EV_LAG] = 0
    mi[I_EV_STEPS] = n
    if n < 2:
        return EV_NONE
    pts = seq[:, :N_COORD]
    slip = seq[:, SEQ_SLIP]
    stick = seq[:, SEQ_STICK]
    limit = shakedown_limit(slip, stick, n)
    if limit <= s0 and limit <= SHAKEDOWN_ZERO * slip[n - 1]:
        mf[F_EV_LIMIT] = limit
        return EV_SHAKEDOWN
    if _repeats(mf, mi, pts, slip, stick, n):
        return EV_REPEAT
    share = CONTRACT_SLIP_FALL_STRIBECK if mi[I_STRIBECK] == 1 else CONTRACT_SLIP_FALL
    if _contracts(mf, pts, slip, n, s0, share):
        return EV_CONTRACT
    if _departs(mf, pts, slip, stick, n, s0):
        return EV_DEPART
    return EV_NONE


@kernel_jit
def slip_tolerance(mf, period, hold):
    """The slip over a section step of `period` [s] that counts as none [m]: the per
    revolution tolerance eps T (monitor F_SLIP_TOL) scaled to the step."""
    return mf[F_SLIP_TOL] * max(period, 1e-300) / hold


@kernel_jit
def newest_period(mi, ring_all, rv, cycles):
    """Duration [s] of the newest step of the cycle (cycles) or revolution section."""
    if cycles:
        k = mi[I_RS_N] - 1
        a = (k - 1) % ring_all.shape[0]
        b = k % ring_all.shape[0]
        return ring_all[b, RA_T0] - ring_all[a, RA_T0]
    k = (mi[I_NREV] - 1) % REV_RING
    j = (mi[I_NREV] - 2) % REV_RING
    return rv[k, RV_T] - rv[j, RV_T]
