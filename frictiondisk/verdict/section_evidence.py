"""Evidence from the motion's own section (numba): is a run that has not stuck converging
to a cycle, moving away from sticking, or shaking down to sticking? (docs/model.md section 6)

The rules read a section sequence only (verdict/section_sequence.py: points p_n [m], the
slip s_n [m] and sticking time tau_n [s] of each step); averages over windows are never
evidence, because a transient's scatter hides its trend. The thresholds are fields of
VerdictParams (vp); the cases that pin them are rows of tests/test_verdict_cases.py.

* EV_REPEAT: the last repeat_count distances |p_n - p_{n-L}| lie within the integrator's
  own tolerance accumulated over a step (L = 1 .. max_lag: a cycle that sticks L times per
  period): the motion has reached its cycle. Where it slips less than that tolerance a
  period, its slip per period must also be shown steady (verdict/steady_slip.py).
* EV_CONTRACT: the distances |p_n - p_{n-1}| shrink by a ratio q whose own changes shrink
  (or are tiny), and the ratio extrapolated from them stays <= q_max: a geometric
  approach to a cycle, whose slip per step extrapolates to a limit above the slip
  tolerance (a cycle, not an approach to sticking). An approach with a growing ratio (a
  slow passage, or sticking ahead) is no evidence.
* EV_DEPART: for depart_steps steps the slip per step (above the slip tolerance) grows,
  the sticking time shrinks and the distances do not shrink: it moves away from sticking.
  Under numerics.follow_departures_until (a certification run's check of an extrapolated
  verdict sets it to the end of its strict budget, short of the further reach of its
  retries) a departure decides only at the last horizon before that time, and only where
  the slave stuck as a whole in each of its steps: a departure is a motion in progress, and
  where it lands (a large cycle, or a stick: generator 1's 1/42 sticks at 435 s after 100
  revolutions of growing slip) its trend cannot tell; a sliding slave has no sticking to
  depart from (generator 1's 1/43: its check read a pure-sliding disk's oscillating slip as
  a departure at 2 000 s, and the disk sticks at 7 232 s).
* EV_SHAKEDOWN (stick): the slip per step falls at every step over the newer three
  quarters of the sequence, and extrapolates to a limit <= the slip tolerance and at most
  shakedown_zero of the slip still left (verdict/extrapolation.py).

Each rule writes its diagnostics (ev_distance, ev_ratio, ev_ratio_bound, ev_limit,
ev_lag, ev_points) into the VERDICT record vs as it goes.
"""

import math

from frictiondisk.kernel.jit import kernel_jit

from .budget import still_following
from .extrapolation import shakedown_limit
from .records import EV_CONTRACT, EV_DEPART, EV_NONE, EV_REPEAT, EV_SHAKEDOWN
from .section_sequence import N_COORD
from .steady_slip import period_slip, steady


@kernel_jit
def _distance(pts, i, j):
    acc = 0.0
    for c in range(N_COORD):
        d = pts[i, c] - pts[j, c]
        acc += d * d
    return math.sqrt(acc)


@kernel_jit
def _repeat_tolerance(rules, pts, i):
    """How far section point i may move between repeats of a converged cycle [m]:
    numerics.cycle_tol, or the integrator's tolerance atol + rtol |p| if larger. The
    integration error of a periodic orbit repeats with it, so a converged cycle moves far
    less than its accumulated error bound (measured: 1e-10 m at rtol 1e-6)."""
    size = 0.0
    for c in range(N_COORD):
        size = max(size, abs(pts[i, c]))
    return max(rules.cycle_tol, rules.atol + rules.rtol * size)


@kernel_jit
def _approaching(vp, slip, stick, n, atol):
    """Whether, over the newest vp.approach_steps steps, the slip per step fell by more
    than vp.approach_fall of itself and atol [m] while the sticking time grew (beyond
    vp.stick_noise): a slave creeping onto a sticking circle, however little its section
    moves per step. Compared half against half, the largest slip and the shortest sticking
    time of each, so a step that now and then sticks throughout (slip 0) is not taken for
    the trend. The atol floor stays: without it slowly converging cycles read as
    approaches, so a creep that falls by less than atol over the window is still read as
    a cycle."""
    back = min(vp.approach_steps, n - 1)
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
    fell = slip_new < slip_old * (1.0 - vp.approach_fall) - atol
    return fell and stick_new > stick_old + vp.stick_noise


@kernel_jit
def _repeats(vp, rules, vs, pts, slip, stick, n, s0):
    """EV_REPEAT: the newest vp.repeat_count distances at some lag L <= vp.max_lag within
    tolerance, and, where they still shrink step after step, the travel still to come
    (geometric tail) within tolerance too: a slow algebraic approach moves little per
    step but far in all. Never while the motion creeps towards sticking (_approaching),
    nor at a lag whose slip per period is within the tolerance unless that slip is shown
    steady (steady_slip.steady): such a motion lies within tolerance of itself whether it
    cycles, creeps onto sticking or departs from it. A steady slip below the tolerance
    repeats. s0: the slip per step that counts as none [m]."""
    if _approaching(vp, slip, stick, n, rules.atol):
        return False
    for lag in range(1, vp.max_lag + 1):
        if n < lag + vp.repeat_count + 1:
            break
        ok = True
        shrinking = True
        worst = 0.0
        newest = _distance(pts, n - 1, n - 1 - lag)
        d_prev = 0.0
        tol = _repeat_tolerance(rules, pts, n - 1)
        if period_slip(slip, n, lag, 0) <= tol and not steady(vp, slip, n, lag, s0):
            continue  # it slips less than tol a period: within tol whether it cycles or creeps
        for back in range(vp.repeat_count + 1):
            i = n - 1 - back
            d = _distance(pts, i, i - lag)
            if back < vp.repeat_count:
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
            vs.ev_distance = worst
            vs.ev_lag = lag
            return True
    return False


@kernel_jit
def _ratio_bound(vp, pts, n):
    """(steady, q, q_up, d): the contraction ratio q of the newest vp.contract_distances
    distances, the bound q_up it extrapolates to (inf: its changes do not shrink fast
    enough) and the newest distance d; steady False where not every distance is positive
    or the ratio turns back and forth (no steady contraction)."""
    m = vp.contract_distances
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
            return False, math.nan, math.nan, d_prev
        q = d / d_prev
        if not math.isnan(q_prev):
            dq = q - q_prev
            small = small and abs(dq) <= vp.q_steady
            if not math.isnan(dq_prev):
                if dq * dq_prev < 0.0 and not (
                    abs(dq) <= vp.q_steady and abs(dq_prev) <= vp.q_steady
                ):
                    return False, math.nan, math.nan, d_prev  # turns back and forth
                if dq_prev != 0.0:
                    rho = max(rho, abs(dq / dq_prev))
            dq_prev = dq
        q_prev = q
        d_prev = d
    # the ratio still grows by dq a step, each change rho times the last: its limit (no
    # bound where its changes do not shrink fast enough)
    q_up = math.inf
    if small or rho <= vp.rho_max:
        grow = max(0.0, dq) * (rho / (1.0 - rho) if rho < 1.0 else 2.0)
        q_up = q + grow + (2.0 * vp.q_steady if small else 0.0)
    return True, q, q_up, d_prev


@kernel_jit
def _contracts(vp, vs, pts, slip, n, s0, fall_share):
    """EV_CONTRACT: the newest vp.contract_distances distances shrink geometrically at an
    established ratio, towards a cycle whose slip per step stays above s0 and keeps all
    but `fall_share` of itself."""
    m = vp.contract_distances
    if n < m + 1:
        return False
    steady_ratio, q, q_up, d_prev = _ratio_bound(vp, pts, n)
    if not steady_ratio:
        return False
    vs.ev_distance = d_prev
    vs.ev_ratio = q
    vs.ev_ratio_bound = q_up
    if not q_up <= vp.q_max:
        return False
    # geometric, not algebraic: 1 - q stays put from half the sequence ago to now (a power
    # law S ~ n^-p has 1 - q ~ p / n, which halves)
    half = n // 2
    if half < 2:
        return False
    q_half = _distance(pts, half, half - 1) / max(_distance(pts, half - 1, half - 2), 1e-300)
    if not (q_half < 1.0 and (1.0 - q) >= vp.geometric_keep * (1.0 - q_half)):
        return False
    vs.ev_limit = d_prev * q_up / (1.0 - q_up)
    if not _limit_off_sticking(vs, pts, n):
        return False
    # the cycle it converges to still slips, nearly as much as now: the slip per step,
    # extrapolated at the slower of its own ratio and the section's (the distances can
    # shrink fast along one direction while the slip follows a slower one), keeps all but
    # fall_share of itself: a slip that still falls by much is an approach to sticking,
    # whatever its section's ratio (the cases: docs/model.md section 6, "contract")
    r = max(q_up, _slip_ratio_bound(slip, n, m, max(s0, vp.slip_steady * slip[n - 1])))
    if not r < 1.0:
        return False
    fall = abs(slip[n - 1] - slip[n - 2]) * r / (1.0 - r)
    return slip[n - 1] - fall > s0 and fall <= fall_share * slip[n - 1]


@kernel_jit
def sticking_radius(p, pts):
    """R* [m]: no co-rotating circle beyond this radius can hold, on any layout: a slave
    co-rotating on a circle of radius R needs a contact force that reaches c_s |x_ms| +
    g R once a revolution (the preload turns against the body frame), and no contact
    pattern carries more than its friction limit plus the band beta eps of its stuck
    contacts, sum (mu F_n,i + beta_i eps) w_i; a braked disk needs more (its torque).
    -inf where no circle holds (g R* < 0), inf where g = 0."""
    hold = 0.0
    for i in range(pts.shape[0]):
        hold += (p.mu * p.F_n_i + p.beta_i * p.eps) * pts[i, 2]
    reserve = hold - p.c_s * abs(p.x_ms)
    g = math.hypot(p.c_s - p.m_s * p.omega_m * p.omega_m, p.beta_s * p.omega_m)
    if g == 0.0:
        return math.inf if reserve >= 0.0 else -math.inf
    return reserve / g if reserve >= 0.0 else -math.inf


@kernel_jit
def _limit_off_sticking(vs, pts, n):
    """Whether the limit of a contracting section lies outside the sticking region by more
    than its own error: every point within the travel still to come (vs.ev_limit, at the
    ratio's bound) of the newest point lies beyond vs.stick_radius from the master axis.
    A limit that may lie where the slave can co-rotate for good is no evidence of a cycle
    that still slips: the section of a slave spiralling out of an unstable sliding state
    inside its sticking disc contracts at first, and the slave then sticks (a Stribeck
    pin, r 0.78, mu 0.11174375: contracting by 0.65 a revolution towards a sliding state
    at |r| ~0.03 m inside R* = 0.05 m at 30 s, it sticks at 84 s)."""
    radius = math.hypot(pts[n - 1, 0], pts[n - 1, 1])
    return radius - vs.ev_limit > vs.stick_radius


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
def _departs(vp, rules, vs, pts, slip, stick, n, s0):
    """EV_DEPART: for vp.depart_steps steps the slip per step did not fall and the sticking
    time did not grow (beyond atol and vp.stick_noise), and the distances did not shrink: a
    departure from sticking, accelerating or steady (a slow ratchet away). Not below a slip
    s0 per step: there it is the law's floor (a pin on its rim, docs/model.md section 6)."""
    m = vp.depart_steps
    if n < m + 1 or not slip[n - 1] > s0:
        return False
    for back in range(m - 1):
        i = n - 1 - back
        if not (slip[i] >= slip[i - 1] - rules.atol and stick[i] <= stick[i - 1] + vp.stick_noise):
            return False
    d_new = _distance(pts, n - 1, n - 2)
    for back in range(1, m - 1):
        i = n - 1 - back
        d_old = _distance(pts, i, i - 1)
        if d_new < d_old:
            return False
        d_new = d_old
    vs.ev_distance = _distance(pts, n - 1, n - 2)
    vs.ev_ratio = vs.ev_distance / max(_distance(pts, n - 2, n - 3), 1e-300)
    return True


@kernel_jit
def section_evidence(vp, rules, vs, seq, n, s0):
    """The evidence (EV_*) of the section sequence seq = (points, slip, stick), first n
    rows; diagnostics go to vs. s0: the slip per step that counts as none [m]."""
    vs.ev_distance = math.nan
    vs.ev_ratio = math.nan
    vs.ev_ratio_bound = math.nan
    vs.ev_limit = math.nan
    vs.ev_lag = 0
    vs.ev_points = n
    if n < 2:
        return EV_NONE
    pts, slip, stick = seq
    limit = shakedown_limit(vp, slip, stick, n)
    if limit <= s0 and limit <= vp.shakedown_zero * slip[n - 1]:
        vs.ev_limit = limit
        return EV_SHAKEDOWN
    if _repeats(vp, rules, vs, pts, slip, stick, n, s0):
        return EV_REPEAT
    share = vp.contract_slip_fall_stribeck if vs.stribeck else vp.contract_slip_fall
    if _contracts(vp, vs, pts, slip, n, s0, share):
        return EV_CONTRACT
    if _departs(vp, rules, vs, pts, slip, stick, n, s0):
        t_eps = 1e-12 * max(1.0, abs(vs.t_stop))  # as machine.check's
        if rules.follow_until > 0.0 and (
            still_following(rules, vs.t_stop, t_eps) or not _sticks_throughout(vp, stick, n)
        ):
            return EV_NONE  # followed to where it lands
        return EV_DEPART
    return EV_NONE


@kernel_jit
def _sticks_throughout(vp, stick, n):
    """Whether the slave stuck as a whole in each of the newest vp.depart_steps steps: a
    departure *from sticking* (a sliding slave's revolutions show no sticking to depart
    from; the sliding rule reads them)."""
    for i in range(n - vp.depart_steps, n):
        if not stick[i] > 0.0:
            return False
    return True
