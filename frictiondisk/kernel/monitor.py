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
(corotation_verdict, kernel/verdict.py; re-exported here).

All state lives in two arrays (mf: float64, mi: int64), two ring buffers of sticking
intervals and one of revolutions, so the same functions serve the numba driver and the
scipy cross-check. Their slot layout (F_*, I_*, RV_*, ...) is kernel/monitor_slots.py,
re-exported here.
"""

import math

import numpy as np

from .events import hermite_max
from .jit import kernel_jit
from .monitor_slots import (  # noqa: F401  (re-exported: mon.F_*, mon.I_*, ...)
    EV_CANNOT,
    EV_CONTRACT,
    EV_DEPART,
    EV_NONE,
    EV_REPEAT,
    EV_SHAKEDOWN,
    EV_SLIDING,
    F_A,
    F_ANG_SECT,
    F_ARM,
    F_ATOL,
    F_CYCLE_TOL,
    F_DR1,
    F_DR2,
    F_EV_D,
    F_EV_LIMIT,
    F_EV_Q,
    F_EV_QUP,
    F_LAMBDA,
    F_LAMBDA_SE,
    F_R1,
    F_R_SECT,
    F_REMAIN,
    F_RMAX,
    F_RTOL,
    F_S_INF,
    F_S_INF_SPREAD,
    F_SIZE,
    F_SLIP_ALL,
    F_SLIP_REV,
    F_SLIP_TOL,
    F_STEPS_ALL,
    F_T_ALL,
    F_T_ANY,
    F_T_R1,
    F_T_REV,
    F_X_ALL,
    F_Y_ALL,
    I_ALL,
    I_ANY,
    I_BOUND,
    I_CYCLE_COUNT,
    I_EV_LAG,
    I_EV_SOURCE,
    I_EV_STEPS,
    I_EVIDENCE,
    I_NAGREE,
    I_NQ,
    I_NREV,
    I_NSECT,
    I_NTRANS,
    I_OBSERVE,
    I_RA_N,
    I_REV_EVER_ALL,
    I_REV_NONE,
    I_REV_NOT_ALL,
    I_REV_NTRANS,
    I_REV_STEPS,
    I_RS_N,
    I_STRIBECK,
    I_VERDICT,
    N_MF,
    N_MI,
    N_RA,
    N_RV,
    RA_SLIP,
    RA_STEPS,
    RA_T0,
    RA_T1,
    RA_X,
    RA_Y,
    REV_RING,
    RING,
    RV_ALL_STUCK,
    RV_ANY_STUCK,
    RV_DRIFT_PHI,
    RV_DRIFT_R,
    RV_EVER_ALL,
    RV_RESERVE,
    RV_SLIP,
    RV_STICK_T,
    RV_STILL,
    RV_SWITCHES,
    RV_T,
    RV_U,
    RV_V,
    RV_W,
    RV_X,
    RV_Y,
    SOURCE_CYCLES,
    SOURCE_REVOLUTIONS,
    VERDICT_CREEP,
    VERDICT_NONE,
    VERDICT_SHAKEN,
    VERDICT_STICK,
)
from .verdict import (  # noqa: F401  (re-exported: mon.corotation_verdict, ...)
    AITKEN_MIN_SPACING,
    VERDICT_REVS,
    VERDICT_Z,
    cannot_corotate,
    corotation_verdict,
    evidence_at_horizon,
    horizon_evidence,
    shaken_down,
    still_settling,
)


@kernel_jit
def _radius(y):
    return math.sqrt(y[0] * y[0] + y[1] * y[1])


@kernel_jit
def _push(ring, count, t0, t1):
    k = count % ring.shape[0]
    ring[k, RA_T0] = t0
    ring[k, RA_T1] = t1


@kernel_jit
def _push_phase(mf, mi, ring_all, t):
    """Close the whole-body sticking phase that ends at t: its interval and section point."""
    k = mi[I_RS_N] % ring_all.shape[0]
    ring_all[k, RA_T0] = mf[F_T_ALL]
    ring_all[k, RA_T1] = t
    ring_all[k, RA_X] = mf[F_X_ALL]
    ring_all[k, RA_Y] = mf[F_Y_ALL]
    ring_all[k, RA_SLIP] = mf[F_SLIP_ALL]
    ring_all[k, RA_STEPS] = mf[F_STEPS_ALL]
    mi[I_RS_N] += 1


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
    _update_phases(mf, mi, ring_all, ring_any, t, y, modes, 0.0, 0)


@kernel_jit
def _update_phases(mf, mi, ring_all, ring_any, t, y, modes, slip, steps):
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
        mf[F_X_ALL] = y[0]
        mf[F_Y_ALL] = y[1]
        mf[F_SLIP_ALL] = slip
        mf[F_STEPS_ALL] = steps
    if not all_now and mi[I_ALL] == 1:
        _push_phase(mf, mi, ring_all, t)
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
def monitor_switch(mf, mi, ring_all, ring_any, t, y, modes, n_switched, slip, steps):
    """Register contact mode switches at time t (modes are the new modes; slip: the slip
    integral [m] so far, NaN without the measure; steps: integrator steps so far)."""
    mi[I_NTRANS] += n_switched
    _update_phases(mf, mi, ring_all, ring_any, t, y, modes, slip, steps)


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
    period = t - mf[F_T_REV]
    scale = period / spin if spin > 0.0 else 1.0  # 1 / omega_m [s]
    rv[k, RV_X] = y[0]
    rv[k, RV_Y] = y[1]
    rv[k, RV_U] = y[nq] * scale
    rv[k, RV_V] = y[nq + 1] * scale
    rv[k, RV_W] = y[nq + 2] * arm * scale if nq == 3 else 0.0
    rv[k, RV_RESERVE] = math.nan  # the driver writes it where the bound applies
    mi[I_NREV] += 1
    begin_revolution(mf, mi, t, y, slip, yrev, steps)
