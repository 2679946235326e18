"""The motion's own section (numba): one row each time the velocity's direction has turned a
whole turn (docs/model.md section 6, "The motion's own section").

A sliding slave is autonomous in the rotating problem: its own period (a whirl, the
spiral of self-centring) has nothing to do with the master's revolution. The section is
where the unwrapped velocity phase psi = atan2(ydot, xdot) reaches the next multiple of
2 pi after the last row's, forwards or backwards (so a non-convex orbit that turns back
and forth across one multiple is counted once): there ydot = 0 and xdot > 0. The crossing
is located on the step's dense output by bisection. Each row (kernel/records.py OWN_STEP)
holds the state there and what the motion did since the row before: the time mean, least
and largest |r| (Simpson and the cubic Hermite of |r|), the least and largest x and y (the
centre's extent, cubic Hermite), the largest speed, the spin, the plastic slip, the
sticking times and switches, and whether every contact stuck at some instant (`locked`).
A locked row ends a sliding regime: `OWN.start` then moves past it.

A slave at rest turns its velocity on noise, or not at all: where the velocity has not
turned within REST_SPAN times the longest row so far (before the first row: the master's
revolution), a row is closed by time (turn 0).
The section so keeps its newest rows (a run's measures are never those of an old row),
and at rest the rows' durations double, so rest adds a row per doubling of the time and
does not fill the ring.

Facts only: what they mean is decided in frictiondisk/verdict/motion_evidence.py. The
step loop calls `begin` at t = 0 and `piece` after every accepted piece of a step (the
whole step, or the part up to an event), after the energy integrals (whose midpoint state
it reuses) and the monitor.
"""

import math

from .events import hermite_max
from .jit import kernel_jit
from .monitor import window_fractions
from .records import OWN_RING
from .rosenbrock import dense_eval_contact

TWO_PI = 2.0 * math.pi
BISECTIONS = 60  # halvings of the step fraction: below round-off of any step
REST_SPAN = 2.0  # a step open this many times the longest row is closed by time


@kernel_jit
def _radius(y):
    return math.sqrt(y[0] * y[0] + y[1] * y[1])


@kernel_jit
def _speed(y, nq):
    return math.sqrt(y[nq] * y[nq] + y[nq + 1] * y[nq + 1])


@kernel_jit
def _wrap(angle):
    """angle mapped to [-pi, pi)."""
    return (angle + math.pi) % TWO_PI - math.pi


@kernel_jit
def _open(own, t, y, nq, slip, switches, locked):
    """Start a step of the section at time t in state y."""
    own.t0 = t
    own.slip0 = slip
    own.phi0 = y[2] if nq == 3 else 0.0
    own.switches0 = switches
    own.r_int = 0.0
    own.r_min = _radius(y)
    own.r_max = own.r_min
    own.v_max = _speed(y, nq)
    own.x_min = y[0]
    own.x_max = y[0]
    own.y_min = y[1]
    own.y_max = y[1]
    own.locked = locked


@kernel_jit
def begin(own, t, y, nq, slip, all_stuck):
    """The section at t = 0 in state y (slip: the slip integral [m])."""
    own.n = 0
    own.start = 0
    own.psi = math.atan2(y[nq + 1], y[nq]) if _speed(y, nq) > 0.0 else math.nan
    own.level = math.nan
    own.longest = 0.0
    _open(own, t, y, nq, slip, 0, all_stuck)


@kernel_jit
def _span(lo, hi, wa, wb, da, db):
    """(least, largest) of lo, hi and the cubic Hermite through end values wa, wb with end
    slopes da, db (per unit of the piece)."""
    lo = min(lo, wa, wb)
    hi = max(hi, wa, wb)
    top, at = hermite_max(wa, wb, da, db)
    if at >= 0.0:
        hi = max(hi, top)
    low, at = hermite_max(-wa, -wb, -da, -db)
    if at >= 0.0:
        lo = min(lo, -low)
    return lo, hi


@kernel_jit
def _extremes(own, ya, yb, nq, dt):
    """Least and largest |r| on a piece of duration dt [s] with end states ya, yb (the cubic
    Hermite of |r| through the end values and rates)."""
    ra = _radius(ya)
    rb = _radius(yb)
    own.r_min = min(own.r_min, ra, rb)
    own.r_max = max(own.r_max, ra, rb)
    if ra > 0.0 and rb > 0.0:
        da = dt * (ya[0] * ya[nq] + ya[1] * ya[nq + 1]) / ra
        db = dt * (yb[0] * yb[nq] + yb[1] * yb[nq + 1]) / rb
        top, at = hermite_max(ra, rb, da, db)
        if at >= 0.0:
            own.r_max = max(own.r_max, top)
        low, at = hermite_max(-ra, -rb, -da, -db)
        if at >= 0.0:
            own.r_min = min(own.r_min, -low)
    own.x_min, own.x_max = _span(own.x_min, own.x_max, ya[0], yb[0], dt * ya[nq], dt * yb[nq])
    own.y_min, own.y_max = _span(
        own.y_min, own.y_max, ya[1], yb[1], dt * ya[nq + 1], dt * yb[nq + 1]
    )


@kernel_jit
def _add(own, ya, ym, yb, nq, dt):
    """Add a piece of duration dt [s] with end states ya, yb and midpoint ym."""
    own.r_int += dt / 6.0 * (_radius(ya) + 4.0 * _radius(ym) + _radius(yb))
    own.v_max = max(own.v_max, _speed(ya, nq), _speed(ym, nq), _speed(yb, nq))
    _extremes(own, ya, yb, nq, dt)


@kernel_jit
def _crossing(y0, y1, wk, s_end, target, nq, out):
    """Step fraction in (0, s_end] where the velocity phase reaches `target` [rad] (it does
    within the piece); the rigid-body state there is left in out."""
    lo = 0.0
    hi = s_end
    dense_eval_contact(y0, y1, wk, lo, out, nq, 0)
    g_lo = _wrap(math.atan2(out[nq + 1], out[nq]) - target)
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        dense_eval_contact(y0, y1, wk, mid, out, nq, 0)
        g = _wrap(math.atan2(out[nq + 1], out[nq]) - target)
        if (g < 0.0) == (g_lo < 0.0):
            lo = mid
        else:
            hi = mid
    dense_eval_contact(y0, y1, wk, hi, out, nq, 0)
    return hi


@kernel_jit
def _close(own, ring, motion, phases, intervals, t, y, nq, slip, turn):
    """Close the open step at time t in (rigid-body) state y into its row; slip: the slip
    integral there [m]; turn: +1 or -1."""
    row = ring[own.n % OWN_RING]
    dt = t - own.t0
    frac_all, frac_any = window_fractions(motion, phases, intervals, t, dt)
    row.t = t
    row.dt = dt
    row.x = y[0]
    row.y = y[1]
    row.xd = y[nq]
    row.yd = y[nq + 1]
    row.phid = y[nq + 2] if nq == 3 else 0.0
    row.r_mean = own.r_int / dt if dt > 0.0 else _radius(y)
    row.r_min = own.r_min
    row.r_max = own.r_max
    row.v_max = own.v_max
    row.x_min = own.x_min
    row.x_max = own.x_max
    row.y_min = own.y_min
    row.y_max = own.y_max
    row.spin = (y[2] - own.phi0) if nq == 3 else 0.0
    row.slip = slip - own.slip0
    row.stick_all_t = frac_all * dt
    row.stick_any_t = frac_any * dt
    row.switches = motion.switches - own.switches0
    row.turn = turn
    row.locked = own.locked or row.stick_all_t > 0.0 or motion.all_stuck
    own.longest = max(own.longest, dt)
    own.n += 1
    if row.locked:
        own.start = own.n  # a sliding regime starts after a step with whole-body sticking


@kernel_jit
def piece(
    own, ring, motion, phases, intervals, y0, y1, wk, s_end, t, h, y_end, ymid, ys, slip_a, slip_b
):
    """Read the piece [t, t + s_end h] of the step from y0 (dense output y0, y1, wk; its
    end state y_end, its midpoint ymid) and close a row where the velocity phase reaches
    the next whole turn in it. ys (2, n): scratch. slip_a, slip_b: the slip integral at the
    piece's start and end [m]. motion, phases, intervals: the monitor's records (kernel/monitor.py)."""
    nq = motion.nq
    if motion.all_stuck:
        own.locked = True
    speed = _speed(y_end, nq)
    psi = math.nan
    if speed > 0.0:
        raw = math.atan2(y_end[nq + 1], y_end[nq])
        psi = raw if math.isnan(own.psi) else own.psi + _wrap(raw - _wrap(own.psi))
    target = math.nan
    if not math.isnan(psi) and not math.isnan(own.psi):
        if math.isnan(own.level):
            k0 = math.floor(own.psi / TWO_PI)
            k1 = math.floor(psi / TWO_PI)
            if k1 != k0:
                target = TWO_PI * max(k0, k1)
        elif psi >= own.level + TWO_PI:
            target = own.level + TWO_PI
        elif psi <= own.level - TWO_PI:
            target = own.level - TWO_PI
    if not math.isnan(psi):
        own.psi = psi
    if math.isnan(target):
        _add(own, y0, ymid, y_end, nq, s_end * h)
        t_end = t + s_end * h
        longest = own.longest
        if longest == 0.0 and motion.n_rev > 0:
            longest = motion.rev_t0 / motion.n_rev  # no row yet: the master's revolution
        if longest > 0.0 and t_end - own.t0 >= REST_SPAN * longest:
            # the velocity has not turned: at rest (or turning on noise); close by time
            _close(own, ring, motion, phases, intervals, t_end, y_end, nq, slip_b, 0)
            _open(own, t_end, y_end, nq, slip_b, motion.switches, motion.all_stuck)
        return
    ystar, ym = ys[0], ys[1]
    s_cut = _crossing(y0, y1, wk, s_end, target, nq, ystar)
    dense_eval_contact(y0, y1, wk, 0.5 * s_cut, ym, nq, 0)
    _add(own, y0, ym, ystar, nq, s_cut * h)
    slip = slip_a + (slip_b - slip_a) * (s_cut / s_end)
    t_cut = t + s_cut * h
    if not math.isnan(own.level):
        turn = 1 if target > own.level else -1
        _close(own, ring, motion, phases, intervals, t_cut, ystar, nq, slip, turn)
    own.level = target
    _open(own, t_cut, ystar, nq, slip, motion.switches, motion.all_stuck)
    dense_eval_contact(y0, y1, wk, 0.5 * (s_cut + s_end), ym, nq, 0)
    _add(own, ystar, ym, y_end, nq, (s_end - s_cut) * h)
