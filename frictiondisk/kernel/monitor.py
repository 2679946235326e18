"""What the motion did, recorded as it runs (numba): the facts the verdict judges.

The monitor sees the run through a few calls from the step loop (begin, step, switch,
close and begin a revolution) and keeps, in the MOTION record (kernel/records.py):
whole-body sticking phases (every contact in stick) and the intervals with some contact
stuck (ring buffers), the first sticking radius R1, the section points at whole-body
slide->stick entries (radius and angle, the radius steps between them), the largest
radius while sliding, and per master revolution (a REVOLUTION row): the net plastic slip,
the drift of the slave centre and of the spin phase in the master frame, whether the
contacts stuck throughout, and the state at its end. Facts only: no thresholds. What they
mean (a cycle, co-rotation, a ratchet) is decided in frictiondisk/verdict/.

The same functions serve the numba step loop (frictiondisk/simulation/loop.py) and the
scipy cross-check (frictiondisk/simulation/radau.py).
"""

import math

from .events import hermite_max
from .jit import kernel_entry, kernel_jit
from .linalg import copy_vector
from .records import REV_RING


@kernel_jit
def _radius(y):
    return math.sqrt(y[0] * y[0] + y[1] * y[1])


@kernel_jit
def begin(motion, phases, intervals, t, y, modes, nq, arm):
    """Start the record at time t in state y and contact modes; nq: 2 (pin) or 3 (disk);
    arm: the longest contact arm [m] (0 for the pin)."""
    motion.nq = nq
    motion.arm = arm
    motion.all_stuck = False
    motion.some_stuck = False
    motion.opened = False
    motion.switches = 0
    motion.t_all = math.nan
    motion.t_any = math.nan
    motion.x_all = math.nan
    motion.y_all = math.nan
    motion.slip_all = math.nan
    motion.steps_all = math.nan
    motion.n_phases = 0
    motion.n_intervals = 0
    motion.r1 = math.nan
    motion.t_r1 = math.nan
    motion.n_sect = 0
    motion.r_sect = math.nan
    motion.ang_sect = math.nan
    motion.sect_dr = math.nan
    motion.sect_dr1 = math.nan
    motion.sect_dr2 = math.nan
    motion.sect_arc = math.nan
    motion.rmax = _radius(y)
    motion.a = math.nan
    motion.size = math.nan
    motion.n_rev = 0
    motion.rev_t0 = t
    motion.rev_slip0 = 0.0
    motion.rev_steps0 = 0
    motion.rev_switches0 = 0
    motion.rev_not_all = False
    motion.rev_none = False
    motion.rev_ever_all = False
    _update_phases(motion, phases, intervals, t, y, modes, 0.0, 0)


@kernel_jit
def _push_phase(motion, phases, t):
    """Close the whole-body sticking phase that ends at t: its interval and section point."""
    row = phases[motion.n_phases % phases.shape[0]]
    row.t0 = motion.t_all
    row.t1 = t
    row.x = motion.x_all
    row.y = motion.y_all
    row.slip = motion.slip_all
    row.steps = motion.steps_all
    motion.n_phases += 1


@kernel_jit
def _update_phases(motion, phases, intervals, t, y, modes, slip, steps):
    n_stick = 0
    for i in range(modes.shape[0]):
        if modes[i] == 1:
            n_stick += 1
    all_now = n_stick == modes.shape[0]
    any_now = n_stick > 0
    if any_now and not motion.some_stuck:
        motion.t_any = t
    if not any_now and motion.some_stuck:
        row = intervals[motion.n_intervals % intervals.shape[0]]
        row.t0 = motion.t_any
        row.t1 = t
        motion.n_intervals += 1
        motion.t_any = math.nan
    motion.some_stuck = any_now
    if not all_now:
        motion.rev_not_all = True
    if not any_now:
        motion.rev_none = True
    if all_now:
        motion.rev_ever_all = True
    motion.opened = all_now and not motion.all_stuck
    if motion.opened:
        _section_point(motion, t, y)
        motion.x_all = y[0]
        motion.y_all = y[1]
        motion.slip_all = slip
        motion.steps_all = steps
    if not all_now and motion.all_stuck:
        _push_phase(motion, phases, t)
        motion.t_all = math.nan
        motion.rmax = _radius(y)
    motion.all_stuck = all_now


@kernel_jit
def _section_point(motion, t, y):
    """A whole-body slide->stick entry at t: the first sticking radius, or the step from
    the last section point (radius change, arc) and the excess of the sliding phase."""
    radius = _radius(y)
    angle = math.atan2(y[1], y[0])
    motion.t_all = t
    if math.isnan(motion.r1):
        motion.r1 = radius
        motion.t_r1 = t
    else:
        motion.a = motion.rmax - radius
        dang = angle - motion.ang_sect
        dang = (dang + math.pi) % (2.0 * math.pi) - math.pi
        motion.sect_dr2 = motion.sect_dr1
        motion.sect_dr1 = motion.sect_dr
        motion.sect_dr = radius - motion.r_sect
        motion.sect_arc = abs(dang) * radius
    motion.r_sect = radius
    motion.ang_sect = angle
    motion.size = radius
    motion.n_sect += 1


@kernel_jit
def step(motion, y0, y1, h):
    """Track the largest radius while sliding, using the cubic Hermite of |r| over the step."""
    if motion.all_stuck:
        return
    nq = motion.nq
    r0 = _radius(y0)
    r1 = _radius(y1)
    best = max(r0, r1)
    if r0 > 0.0 and r1 > 0.0:
        d0 = h * (y0[0] * y0[nq] + y0[1] * y0[nq + 1]) / r0
        d1 = h * (y1[0] * y1[nq] + y1[1] * y1[nq + 1]) / r1
        hm, hs = hermite_max(r0, r1, d0, d1)
        if hs >= 0.0 and hm > best:
            best = hm
    if best > motion.rmax or math.isnan(motion.rmax):
        motion.rmax = best


@kernel_jit
def steps_through(motion, ts, ys):
    """`step` over the accepted steps of a segment: states ys[k] (C-contiguous rows) at
    times ts[k] [s]. One call per segment for an integrator driven from Python."""
    for k in range(1, ts.shape[0]):
        step(motion, ys[k - 1], ys[k], ts[k] - ts[k - 1])


@kernel_jit
def switch(motion, phases, intervals, t, y, modes, n_switched, slip, steps):
    """Register contact mode switches at time t (modes are the new modes; slip: the slip
    integral [m] so far, NaN without the measure; steps: integrator steps so far).
    motion.opened tells whether a whole-body sticking phase opened here."""
    motion.switches += n_switched
    _update_phases(motion, phases, intervals, t, y, modes, slip, steps)


@kernel_entry
def stuck_for(motion, t):
    """How long every contact has stuck without interruption at time t [s] (0 if not)."""
    if not motion.all_stuck:
        return 0.0
    return t - motion.t_all


@kernel_jit
def _overlap(starts, ends, count, open_start, t_lo, t_hi):
    """Time in [t_lo, t_hi] covered by the first min(count, len(starts)) intervals
    (starts, ends: the t0 and t1 fields of a ring) and by an open one from open_start
    (NaN: none) [s]."""
    total = 0.0
    n = min(count, starts.shape[0])
    for k in range(n):
        a = max(starts[k], t_lo)
        b = min(ends[k], t_hi)
        if b > a:
            total += b - a
    if not math.isnan(open_start):
        a = max(open_start, t_lo)
        if t_hi > a:
            total += t_hi - a
    return total


@kernel_entry
def window_fractions(motion, phases, intervals, t_end, window):
    """Fractions of [t_end - window, t_end] with every contact / some contact sticking."""
    t_lo = max(0.0, t_end - window)
    span = t_end - t_lo
    if span <= 0.0:
        frac_all = 1.0 if motion.all_stuck else 0.0
        frac_any = 1.0 if motion.some_stuck else 0.0
        return frac_all, frac_any
    frac_all = _overlap(phases.t0, phases.t1, motion.n_phases, motion.t_all, t_lo, t_end) / span
    frac_any = (
        _overlap(intervals.t0, intervals.t1, motion.n_intervals, motion.t_any, t_lo, t_end) / span
    )
    return frac_all, frac_any


@kernel_jit
def begin_revolution(motion, t, y, slip, yrev, steps):
    """Start a revolution at time t after `steps` integrator steps: remember the state
    (yrev) and the slip integral [m]."""
    motion.rev_steps0 = steps
    motion.rev_t0 = t
    motion.rev_slip0 = slip
    motion.rev_not_all = not motion.all_stuck
    motion.rev_none = not motion.some_stuck
    motion.rev_ever_all = motion.all_stuck
    motion.rev_switches0 = motion.switches
    copy_vector(y, yrev)


@kernel_jit
def close_revolution(motion, revs, yrev, phases, t, y, slip, spin):
    """Close the revolution ending at t (state y, slip integral [m]) into its row of the
    revolution ring `revs`, and count it. Start the next with `begin_revolution` (after the
    verdict has read this one: it needs the steps taken in it).

    spin: the master's rotation over one revolution, omega_m T [rad]. The master frame has
    turned by a whole number of turns, so its drift is the plain difference of the states.
    `still` is left to the verdict (frictiondisk/verdict/machine.py) and `reserve` NaN.
    """
    nq = motion.nq
    row = revs[motion.n_rev % REV_RING]
    dx = y[0] - yrev[0]
    dy = y[1] - yrev[1]
    dphi = (y[2] - yrev[2] - spin) if nq == 3 else 0.0
    row.t = t
    row.slip = slip - motion.rev_slip0
    row.drift_r = math.sqrt(dx * dx + dy * dy)
    row.drift_phi = dphi
    row.switches = motion.switches - motion.rev_switches0
    row.all_stuck = not motion.rev_not_all
    row.any_stuck = not motion.rev_none
    row.ever_all = motion.rev_ever_all
    row.still = False
    row.stick_t = _overlap(phases.t0, phases.t1, motion.n_phases, motion.t_all, motion.rev_t0, t)
    period = t - motion.rev_t0
    scale = period / spin if spin > 0.0 else 1.0  # 1 / omega_m [s]
    arm = motion.arm
    row.x = y[0]
    row.y = y[1]
    row.u = y[nq] * scale
    row.v = y[nq + 1] * scale
    row.w = y[nq + 2] * arm * scale if nq == 3 else 0.0
    row.reserve = math.nan
    motion.n_rev += 1


@kernel_jit
def newest_revolution(motion, back):
    """Ring row of the revolution `back` revolutions before the newest (0 = newest)."""
    return (motion.n_rev - 1 - back) % REV_RING
