"""Run bookkeeping for the outcome rules of docs/model.md section 6 (numba).

The monitor sees the run through a few calls from the driver (begin, step, switch) and
keeps what the classifier needs: whole-body sticking phases (every contact in stick),
the first sticking radius R1, section points at slide->stick entries for the limit-cycle
convergence test, the largest radius while sliding, and the sticking intervals of the
recent past (ring buffers) for the final-window stick fraction.

All state lives in two arrays (mf: float64, mi: int64) and two ring buffers, so the same
functions serve the numba driver and the scipy cross-check.
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
N_MF = 12

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
N_MI = 9

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
