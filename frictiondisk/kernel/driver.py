"""The run loop: steps, switching events, budget and stopping rules (numba).

`run` never raises: it returns a status code (kernel/status.py) and fills the monitor
arrays, from which frictiondisk.simulate builds the outcome.

Hysteresis band (docs/model.md section 3). Stick ends at |k| = F_St, slide ends at
|k| = F_St + beta eps, so a contact that has just switched sits inside a band where its
own exit threshold is behind it: a new stick contact has |k| = F_St + beta eps > F_St, a
new slide contact |k| = F_St < F_St + beta eps. Such a contact is flagged `band` and
watches a rate instead of its switching function:
* stuck in the band (above the limit): it slides as soon as |k| starts to grow
  (KIND_RISE); otherwise it could stay stuck above the limit for ever;
* sliding in the band (plastic rate below eps): it sticks as soon as stick dynamics
  would not raise |k| (KIND_REENTRY).
It leaves the band when its switching function changes sign, which is tested at step
ends (then the ordinary crossing rules apply).
"""

import math

import numpy as np

from . import energy as en
from . import monitor as mon
from . import sections as sec
from . import shakedown_bound as sdb
from . import status as st
from .events import KIND_REENTRY, KIND_RISE, KIND_SWITCH, brent_root, find_graze
from .jit import kernel_jit
from .linalg import stage_workspace
from .model import (
    P_EPS,
    P_OMEGA,
    P_STR_R,
    SLIDE,
    STICK,
    n_coords,
    rhs,
    stick_rate_given,
    switch_rate,
    switch_value,
)
from .recording import record_dense, record_state
from .rodas import (
    N_WORK_ROWS,
    W_K6,
    dense_eval,
    dense_eval_contact,
    error_norm,
    next_step_factor,
    reject_factor,
    rodas_step,
)

# Integer options (iopt)
O_METHOD = 0  # 0 = adaptive RODAS4, 1 = fixed-step RODAS4
O_MAX_STEPS = 1
O_MAX_EVENTS = 2
O_CYCLE_COUNT = 3
O_CONVERGE = 4  # 1 = run until the limit cycle converged (or t_max)
O_STOP_ON_STICK = 5
O_RECORD = 6
O_STICK_RULE = 7  # RULE_CONTACTS or RULE_COROTATION
O_DENSE_LU = 8  # 1 = dense LU of the stage matrix (O(N^3), for comparison), 0 = arrow (O(N))
O_OBSERVE = 9  # 1 = verdicts only on what the run shows (numerics.evidence observe)
O_BOUND = 10  # 1 = the shakedown bound reads this run (kernel/shakedown_bound.py)
N_IOPT = 11

RULE_CONTACTS = 0  # stick = every contact stuck for one revolution
RULE_COROTATION = 1  # stick = co-rotation without net slip (monitor.corotation_verdict)

# Float options (fopt)
O_RTOL = 0
O_ATOL = 1
O_DT = 2  # fixed step [s]
O_HMAX = 3  # largest step [s]
O_HORIZON = 4  # t_decide or t_max [s]
O_CYCLE_TOL = 5  # [m]
O_HOLD = 6  # uninterrupted sticking that decides `stick` [s]
O_DT_OUT = 7  # recording interval [s]; 0 = every step
O_BUDGET = 8  # largest horizon an undecided run may extend to [s]
N_FOPT = 9

# Driver counters (out_i)
C_STEPS = 0
C_REJECTED = 1
C_EVENTS = 2
C_REFUSED = 3
# 4, 5: C_RECORDED and C_TRUNCATED (kernel/recording.py)
C_EXTENDED = 6  # 1 while the horizon is extended to finish a sticking phase; 2 once it broke
C_SETTLE_REVS = 7  # revolutions the horizon was extended by for a run still settling
C_BUDGET_SPENT = 8  # 1 if a run still settling hit the horizon budget
N_OUT_I = 9

SAME_TIME = 1e-12  # [s] events closer than this count as one instant (Zeno guard)
SIMULTANEOUS = 1e-9  # [s] crossings this close are switched together
T_TOL_ABS = 1e-11  # [s] time tolerance of the event root finder


@kernel_jit
def _in_band(p, pts, modes, y, i):
    """Whether contact i is inside the hysteresis band of its mode (module docstring)."""
    g = switch_value(p, pts, y, i, modes[i])
    return g > 0.0 if modes[i] == STICK else g <= 0.0


@kernel_jit
def _check_entries(p, pts, modes, y, f, entered, band, out_i):
    """Refused-entry check after switches (docs/model.md section 3). Returns the number refused.

    A contact entering stick by crossing its threshold (entered = 1) is refused (stays in
    slide) if, with stick dynamics, |k| - F_St would increase. A re-entry (entered = 2) is
    consistent by construction: it happens where that rate has just fallen through 0.
    Every contact that switched gets its band flag. Leaves f = rhs(y) in the final modes.
    """
    rhs(p, pts, modes, y, f)
    for i in range(modes.shape[0]):
        if entered[i] > 0 or band[i] == 1:
            band[i] = 1 if _in_band(p, pts, modes, y, i) else 0
    n_refused = 0
    for i in range(modes.shape[0]):
        if entered[i] == 1 and modes[i] == STICK and switch_rate(p, pts, y, f, i) > 0.0:
            modes[i] = SLIDE
            entered[i] = 0
            band[i] = 1  # sliding at its end-of-slide threshold: re-entry is watched
            n_refused += 1
    if n_refused > 0:
        out_i[C_REFUSED] += n_refused
        rhs(p, pts, modes, y, f)
    return n_refused


@kernel_jit
def run(
    p,
    pts,
    y,
    modes,
    iopt,
    fopt,
    rec_t,
    rec_y,
    rec_m,
    mf,
    mi,
    ring_all,
    ring_any,
    rv,
    yrev,
    out_i,
    out_f,
):
    """Integrate one scene from t = 0 until a stopping rule fires.

    Returns (status code, final time [s]). y (initial state) and modes (int8, one per
    contact) are updated in place and hold the final state and modes. out_f (float64,
    energy.N_OUT_F) receives the work put in and dissipated and the net plastic slip up to
    the final time (kernel/energy.py). rv (monitor.REV_RING, monitor.N_RV) receives the
    per-revolution measures; yrev (like y) is scratch space for the state one revolution
    back. Steps end exactly at every whole master revolution, where they are compared.
    """
    n = y.shape[0]
    ncon = modes.shape[0]
    nq = n_coords(p)
    fixed = iopt[O_METHOD] == 1
    rtol = fopt[O_RTOL]
    atol = fopt[O_ATOL]
    h_max = fopt[O_HMAX]
    horizon = fopt[O_HORIZON]
    hold = fopt[O_HOLD]
    dt_out = fopt[O_DT_OUT]
    record = iopt[O_RECORD] == 1
    converge = iopt[O_CONVERGE] == 1
    stop_on_stick = iopt[O_STOP_ON_STICK] == 1
    corotation = iopt[O_STICK_RULE] == RULE_COROTATION
    budget = fopt[O_BUDGET]
    spin = p[P_OMEGA] * hold  # the master's turn over one revolution [rad]
    bound = corotation and iopt[O_BOUND] == 1
    bound_values = np.empty(sdb.BLOCKS + 1)

    y1 = np.empty(n)
    f = np.empty(n)
    f1 = np.empty(n)
    ftmp = np.empty(n)
    ybuf = np.empty(n)
    ymid = np.empty(n)
    jac, lu, piv = stage_workspace(n, nq, iopt[O_DENSE_LU] == 1)
    seq = np.empty((sec.SEQ_MAX, sec.N_SEQ))  # scratch for the section (kernel/sections.py)
    # below this bound no co-rotation can hold: no shakedown is extrapolated there
    omega = p[P_OMEGA]
    wk = np.empty((N_WORK_ROWS, n))
    fresh = np.zeros(ncon, dtype=np.int8)
    band = np.zeros(ncon, dtype=np.int8)
    entered = np.zeros(ncon, dtype=np.int8)
    root_s = np.empty(ncon)
    root_kind = np.zeros(ncon, dtype=np.int8)
    out_i[:] = 0

    t = 0.0
    rhs(p, pts, modes, y, f)
    en.begin(p, pts, modes, y, out_f)
    for i in range(ncon):
        band[i] = 1 if _in_band(p, pts, modes, y, i) else 0
    mon.monitor_begin(
        mf, mi, ring_all, ring_any, t, y, modes, nq, fopt[O_CYCLE_TOL], iopt[O_CYCLE_COUNT]
    )
    mon.begin_revolution(mf, mi, t, y, 0.0, yrev, 0)
    # A slip per revolution below what the slide->stick threshold eps lets slide
    # unresolved over a revolution is none (kernel/monitor.py). A model quantity: adding
    # the integrator's atol made the braked disk's mu* move with atol (docs/model.md 6).
    mf[mon.F_SLIP_TOL] = p[P_EPS] * hold
    mf[mon.F_RTOL] = rtol
    mf[mon.F_ATOL] = atol
    mi[mon.I_OBSERVE] = iopt[O_OBSERVE]
    mi[mon.I_STRIBECK] = 1 if p[P_STR_R] < 1.0 else 0
    mf[mon.F_ARM] = 0.0
    if nq == 3:
        for i in range(ncon):
            mf[mon.F_ARM] = max(mf[mon.F_ARM], math.hypot(pts[i, 0], pts[i, 1]))
    mi[mon.I_BOUND] = 1 if bound else 0
    cannot_stick = mon.cannot_corotate(p, pts, mf[mon.F_ARM], bound)
    t_rev = hold  # end of the current revolution [s]
    if record:
        record_state(rec_t, rec_y, rec_m, out_i, t, y, modes)

    h = fopt[O_DT] if fixed else min(h_max, 1e-4)
    err = 1.0
    err_old = 0.0
    h_old = h
    first = True
    t_last_event = -1.0
    n_same_time = 0
    t_stop = horizon

    while True:
        # ---- stopping rules --------------------------------------------------------------
        t_eps = 1e-12 * max(1.0, abs(t))
        verdict = mon.VERDICT_NONE
        says = 0  # the shakedown bound's verdict at a revolution closed at this t
        if t >= t_rev - t_eps:
            mon.monitor_revolution(
                mf,
                mi,
                rv,
                yrev,
                ring_all,
                t,
                y,
                out_f[en.E_SLIP],
                spin,
                rtol,
                atol,
                out_i[C_STEPS],
            )
            t_rev += hold
            if bound:
                says = sdb.close_revolution(p, pts, y, rv, mi[mon.I_NREV], bound_values)
            verdict = mon.corotation_verdict(mf, mi, rv)
            if (
                corotation
                and verdict == mon.VERDICT_NONE
                and not cannot_stick
                and mon.shaken_down(mf, mi, ring_all, rv, omega, hold, seq)
            ):
                verdict = mon.VERDICT_SHAKEN
                mi[mon.I_VERDICT] = verdict
            stuck = verdict == mon.VERDICT_STICK or verdict == mon.VERDICT_SHAKEN
            if bound and stuck and not sdb.holds_here(p, rv, mi[mon.I_NREV]):
                verdict = mon.VERDICT_NONE
                mi[mon.I_VERDICT] = verdict
        if corotation:
            if stop_on_stick and verdict == mon.VERDICT_STICK:
                return st.COROTATING, t
            if stop_on_stick and verdict == mon.VERDICT_SHAKEN:
                return st.SHAKEN_DOWN, t
            if not converge and verdict == mon.VERDICT_CREEP:
                return st.CREEPING, t
            if (says == 1 and stop_on_stick) or (says == -1 and not converge):
                return st.BOUND_DECIDED, t  # Melan or Koiter (outcome/shakedown_verdict.py)
        elif stop_on_stick and mon.stuck_for(mf, mi, t) >= hold - t_eps:
            return st.STICK_HELD, t
        if converge and mon.cycle_converged(mi):
            return st.CYCLE_CONVERGED, t
        if t >= t_stop - t_eps:
            if corotation and mi[mon.I_VERDICT] == mon.VERDICT_STICK:
                return st.COROTATING, t  # decided, kept running for stop_on_stick false
            if corotation and mi[mon.I_VERDICT] == mon.VERDICT_SHAKEN:
                return st.SHAKEN_DOWN, t
            if corotation and mi[mon.I_VERDICT] == mon.VERDICT_CREEP:
                return st.CREEPING, t
            # contacts: a held phase is `stick`; an open one is finished first (below)
            held = not corotation and (
                mon.stuck_for(mf, mi, t) >= hold - t_eps
                or (mi[mon.I_ALL] == 1 and out_i[C_EXTENDED] == 0)
            )
            go_on = False
            if not converge:
                evidence = mon.evidence_at_horizon(
                    p, pts, mf, mi, ring_all, rv, omega, hold, seq, corotation, held
                )
                if evidence == mon.EV_SHAKEDOWN and corotation:
                    if not bound or sdb.holds_here(p, rv, mi[mon.I_NREV]):
                        return st.SHAKEN_DOWN, t
                    evidence = mon.EV_NONE
                go_on = evidence == mon.EV_NONE
            if go_on:  # no not-stick verdict without evidence: extend, within the budget
                if t_stop + hold <= budget + t_eps:
                    out_i[C_SETTLE_REVS] += 1
                    t_stop += hold
                    continue
                out_i[C_BUDGET_SPENT] = 1
            if mi[mon.I_ALL] == 1 and out_i[C_EXTENDED] == 0:
                # Never stop inside a sticking phase that may still decide `stick`: it must
                # last one revolution (contacts), or cover the first whole revolution of the
                # grid after it began (corotation).
                out_i[C_EXTENDED] = 1
                if corotation:
                    t_stop = (math.floor(mf[mon.F_T_ALL] / hold) + 2.0) * hold
                else:
                    t_stop = mf[mon.F_T_ALL] + hold
                if t < t_stop - t_eps:
                    out_i[C_BUDGET_SPENT] = 0
                    continue
            return (st.TMAX_REACHED if converge else st.HORIZON_REACHED), t
        if not corotation and out_i[C_EXTENDED] == 1 and mi[mon.I_ALL] == 0:
            out_i[C_EXTENDED] = 2  # the open sticking phase broke: decide now, by the rules above
            t_stop = t
            continue
        if out_i[C_STEPS] >= iopt[O_MAX_STEPS]:
            return st.MAX_STEPS, t
        if out_i[C_EVENTS] >= iopt[O_MAX_EVENTS]:
            return st.MAX_EVENTS, t

        # ---- one step -----------------------------------------------------------------------
        t_target = min(t_stop, t_rev)
        if stop_on_stick and not corotation and mi[mon.I_ALL] == 1:
            t_target = min(t_target, mf[mon.F_T_ALL] + hold)  # end exactly at the decision
        h_free = min(h, h_max)  # the controller's step; a step cut short to land on
        h = min(h_free, t_target - t)  # t_target must not shrink the next one
        if h <= 1e-14 * max(1.0, t):
            return st.STEP_TOO_SMALL, t
        ok = rodas_step(p, pts, modes, y, f, h, jac, lu, piv, wk, y1)
        if fixed:
            if not ok:
                return st.NONFINITE, t
        else:
            err = error_norm(y, y1, wk[W_K6], rtol, atol) if ok else math.inf
            if not (err <= 1.0):
                out_i[C_REJECTED] += 1
                h *= reject_factor(err)
                continue
        rhs(p, pts, modes, y1, f1)
        for j in range(n):
            if not math.isfinite(f1[j]):
                return st.NONFINITE, t
        out_i[C_STEPS] += 1

        # ---- events inside the step ------------------------------------------------------
        stol = (T_TOL_ABS + 4e-16 * abs(t)) / h
        s_event = 2.0
        for i in range(ncon):
            root_s[i] = 2.0
            sigma = 1.0 if modes[i] == STICK else -1.0
            if band[i] == 1:
                kind = KIND_RISE if modes[i] == STICK else KIND_REENTRY
                sign = 1.0 if kind == KIND_RISE else -1.0
                w0 = sign * stick_rate_given(p, pts, modes, y, f, i, ftmp)
                w1 = sign * stick_rate_given(p, pts, modes, y1, f1, i, ftmp)
            else:
                kind = KIND_SWITCH
                w0 = sigma * switch_value(p, pts, y, i, modes[i])
                w1 = sigma * switch_value(p, pts, y1, i, modes[i])
            if w0 >= 0.0:
                if fresh[i] == 0:
                    # past its threshold without having just switched (a crossing missed
                    # inside an earlier step): switch it here rather than hide it
                    root_s[i] = 0.0
                    root_kind[i] = kind
                    s_event = 0.0
                    continue
                # just switched (w = 0 to round-off): count only a fresh crossing after a dip
                w0 = -1e-300
            s_hi = -1.0
            w_hi = 0.0
            if w1 >= 0.0:
                s_hi = 1.0
                w_hi = w1
            elif kind == KIND_SWITCH:
                d0 = sigma * switch_rate(p, pts, y, f, i) * h
                d1 = sigma * switch_rate(p, pts, y1, f1, i) * h
                sg = find_graze(p, pts, modes, y, y1, wk, i, sigma, w0, w1, d0, d1, ybuf, ftmp)
                if sg > 0.0:
                    s_hi = sg
                    dense_eval_contact(y, y1, wk, sg, ybuf, nq, i)
                    w_hi = sigma * switch_value(p, pts, ybuf, i, modes[i])
            if s_hi > 0.0:
                sr = brent_root(
                    p, pts, modes, y, y1, wk, i, sigma, kind, 0.0, w0, s_hi, w_hi, stol, ybuf, ftmp
                )
                if fresh[i] == 1 and sr <= stol:
                    continue  # the switch we just made, seen again through round-off
                root_s[i] = sr
                root_kind[i] = kind
                if sr < s_event:
                    s_event = sr

        if s_event <= 1.0:
            t_ev = t + s_event * h
            if record and dt_out > 0.0:
                record_dense(
                    rec_t, rec_y, rec_m, out_i, t, h, s_event, y, y1, wk, modes, dt_out, ybuf
                )
            dense_eval(y, y1, wk, s_event, ybuf)
            en.integrate_piece(p, pts, modes, y, y1, wk, s_event, h, ybuf, ymid, out_f)
            mon.monitor_step(mf, mi, y, ybuf, s_event * h)
            if record:
                record_state(rec_t, rec_y, rec_m, out_i, t_ev, ybuf, modes)
            y[:] = ybuf
            window = max(SIMULTANEOUS / h, stol)
            for i in range(ncon):
                entered[i] = 0
                fresh[i] = 0
                if root_s[i] > s_event + window:
                    continue
                if root_kind[i] != KIND_SWITCH:
                    # a band contact whose rate turned: switch only if it is still in the
                    # band here, else it is an ordinary contact of its mode from now on
                    still_in_band = _in_band(p, pts, modes, y, i)
                    band[i] = 0
                    if not still_in_band:
                        continue
                entered[i] = 2 if root_kind[i] == KIND_REENTRY else 1
                modes[i] = SLIDE if modes[i] == STICK else STICK
                fresh[i] = 1
            _check_entries(p, pts, modes, y, f, entered, band, out_i)
            en.refresh(p, pts, modes, y, out_f)  # the integrand changes with the modes
            n_sw = 0
            for i in range(ncon):
                n_sw += 1 if entered[i] > 0 else 0
            mon.monitor_switch(
                mf, mi, ring_all, ring_any, t_ev, y, modes, n_sw, out_f[en.E_SLIP], out_i[C_STEPS]
            )
            out_i[C_EVENTS] += n_sw
            if t_ev - t_last_event < SAME_TIME:
                n_same_time += 1
                if n_same_time > 4 * ncon + 8:
                    return st.ZENO, t
            else:
                n_same_time = 0
            t_last_event = t_ev
            t = t_ev
            if record:
                record_state(rec_t, rec_y, rec_m, out_i, t, y, modes)
            first = True  # the dynamics changed: no step-size prediction across the switch
            if fixed:
                h = fopt[O_DT]
            continue

        # ---- accept the whole step ---------------------------------------------------------
        if record and dt_out > 0.0:
            record_dense(rec_t, rec_y, rec_m, out_i, t, h, 1.0, y, y1, wk, modes, dt_out, ybuf)
        en.integrate_piece(p, pts, modes, y, y1, wk, 1.0, h, y1, ymid, out_f)
        mon.monitor_step(mf, mi, y, y1, h)
        t += h
        y[:] = y1
        f[:] = f1
        for i in range(ncon):
            fresh[i] = 0
        if record and dt_out <= 0.0:
            record_state(rec_t, rec_y, rec_m, out_i, t, y, modes)

        # A band contact whose switching function changed sign is an ordinary one again.
        for i in range(ncon):
            if band[i] == 1 and not _in_band(p, pts, modes, y, i):
                band[i] = 0

        if fixed:
            h = fopt[O_DT]
        elif h < 0.5 * h_free:
            h = h_free
        else:
            err_safe = max(err, 1e-10)
            fac = next_step_factor(err_safe, err_old, h, h_old, first)
            h_old = h
            err_old = max(err_safe, 1e-2)
            first = False
            h *= fac
