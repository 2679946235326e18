"""The step loop (numba): one run end to end, the kernel's steps and the verdict's machine.

diffrax's `_integrate.py` is the model: the loop carries one state record (RUN_STATE,
simulation/buffers.py: stepper, counters, energy, motion, verdict) and each pass does

1. the stop check: close a master revolution where one ends (kernel/monitor.py facts,
   then frictiondisk/verdict/machine.py `revolution_closed`), and ask the machine
   (`check`): step on, ask again (the horizon moved) or stop;
2. the work budget (options.max_steps, max_events);
3. one Rosenbrock step (RODAS4 or RODAS5, kernel/steppers.py) to the landing time the
   machine allows, judged by the step-size controller (kernel/controller.py);
4. events and switching inside the step (kernel/switching.py): at the earliest event the
   step is cut, the contacts switch, the monitor records it and the machine hears of a
   whole-body sticking phase that opened; otherwise the whole step is accepted;
5. saving: the energy integrals (kernel/energy.py), the monitor, the motion's own section
   (kernel/own_section.py), the trajectory (kernel/recording.py).

The loop imports the machine directly (not as an argument) so that numba caches it.
It never raises: it returns (status, t_end), the verdict's final state
(verdict/records.py) or one of the loop's failures (kernel/status.py).
"""

import math

import numpy as np

from frictiondisk.kernel import controller, monitor, own_section, steppers, switching
from frictiondisk.kernel import energy as en
from frictiondisk.kernel import status as st
from frictiondisk.kernel.events import SAME_TIME, T_TOL_ABS
from frictiondisk.kernel.jit import kernel_entry_allocating, kernel_jit, kernel_jit_allocating
from frictiondisk.kernel.linalg import copy_vector, stage_workspace
from frictiondisk.kernel.model import n_coords, rhs
from frictiondisk.kernel.recording import record_dense, record_state
from frictiondisk.kernel.rosenbrock import N_WORK_ROWS, dense_eval
from frictiondisk.verdict import machine
from frictiondisk.verdict.records import RECHECK, STOP
from frictiondisk.verdict.section_sequence import new_sequence

STEP_UNDERFLOW = 1e-14  # a step below this share of max(1, t) is an underflow


@kernel_jit_allocating
def _workspace(p, y, modes, options, vp):
    """Scratch of one run: state-sized vectors, the stage matrices, the RODAS work rows,
    one watch per contact, the state one revolution back, a section sequence, the bound's
    history."""
    n = y.shape[0]
    vectors = np.empty((8, n))  # y1, f, f1, ftmp, ybuf, ymid, and the own section's two
    jac, lu, piv = stage_workspace(n, n_coords(p), options.dense_lu)
    wk = np.empty((N_WORK_ROWS, n))
    watch = np.empty(modes.shape[0], dtype=switching.CONTACT_WATCH)
    yrev = np.empty(n)
    values = np.empty(vp.bound_blocks + 1)
    return vectors, jac, lu, piv, wk, watch, yrev, new_sequence(), values


@kernel_jit
def _begin(p, pts, options, rules, vp, y, modes, state, rings, recording, ws):
    """Everything at t = 0: rates, energy, band flags, the monitor, the machine, the first
    revolution, the first recorded row, the controller."""
    _, phases, intervals, _ = rings
    vectors, _, _, _, _, watch, yrev, _, _ = ws
    step = state.step
    counters = state.counters
    counters.steps = 0
    counters.rejected = 0
    counters.events = 0
    counters.refused = 0
    counters.recorded = 0
    counters.truncated = False
    step.t = 0.0
    rhs(p, pts, modes, y, vectors[1])
    en.begin(p, pts, modes, y, state.energy)
    switching.begin(p, pts, modes, y, watch)
    nq = n_coords(p)
    arm = 0.0
    if nq == 3:
        for i in range(pts.shape[0]):
            arm = max(arm, math.hypot(pts[i, 0], pts[i, 1]))
    monitor.begin(state.motion, phases, intervals, step.t, y, modes, nq, arm)
    own_section.begin(state.own, step.t, y, nq, state.energy.slip, state.motion.all_stuck)
    machine.begin(vp, rules, p, pts, state.motion, state.verdict)
    if state.motion.opened:
        machine.phase_opened(rules, state.motion, state.verdict)
    monitor.begin_revolution(state.motion, step.t, y, 0.0, yrev, 0)
    step.t_rev = rules.hold  # end of the current revolution [s]
    if options.record:
        record_state(recording, counters, step.t, y, modes)
    controller.start(step, options)
    step.t_last_event = -1.0
    step.same_time = 0


@kernel_jit
def _stop_check(p, pts, rules, vp, y, state, rings, ws):
    """Close the revolution that ends at the current instant, if one does, and ask the
    machine what to do (verdict/records.py STEP_ON, RECHECK, STOP)."""
    revs, phases, _, _ = rings
    _, _, _, _, _, _, yrev, seq, values = ws
    step = state.step
    motion = state.motion
    t = step.t
    t_eps = 1e-12 * max(1.0, abs(t))
    if t >= step.t_rev - t_eps:
        spin = p.omega_m * rules.hold  # the master's turn over one revolution [rad]
        monitor.close_revolution(motion, revs, yrev, phases, t, y, state.energy.slip, spin)
        step.t_rev += rules.hold
        steps = state.counters.steps
        machine.revolution_closed(
            vp, rules, p, pts, y, motion, state.verdict, revs, phases, seq, values, steps
        )
        monitor.begin_revolution(motion, t, y, state.energy.slip, yrev, steps)
    return machine.check(vp, rules, p, pts, t, motion, state.verdict, revs, phases, seq)


@kernel_jit
def _attempt(p, pts, options, rules, y, modes, state, rings, recording, ws):
    """One step attempt from the current instant: st.RUNNING (taken or rejected) or a
    failure status."""
    vectors, jac, lu, piv, wk, watch, _, _, _ = ws
    y1, f, f1, ftmp, ybuf = vectors[0], vectors[1], vectors[2], vectors[3], vectors[4]
    step = state.step
    t = step.t
    t_target = machine.landing_time(rules, state.motion, state.verdict, step.t_rev)
    h_free = min(step.h, options.h_max)  # the controller's step; a step cut short to land
    step.h = min(h_free, t_target - t)  # on t_target must not shrink the next one
    if step.h <= STEP_UNDERFLOW * max(1.0, t):
        return st.STEP_TOO_SMALL
    h = step.h
    ok = steppers.step(options, p, pts, modes, y, f, h, jac, lu, piv, wk, y1)
    error_estimate = wk[steppers.error_row(options)]
    judged = controller.judge(step, options, ok, y, y1, error_estimate, state.counters)
    if judged == controller.FAIL:
        return st.NONFINITE
    if judged == controller.REJECT:
        return st.RUNNING
    rhs(p, pts, modes, y1, f1)
    for j in range(y.shape[0]):
        if not math.isfinite(f1[j]):
            return st.NONFINITE
    state.counters.steps += 1
    stol = (T_TOL_ABS + 4e-16 * abs(t)) / h
    s_event = switching.earliest_event(
        p, pts, modes, y, y1, f, f1, h, wk, watch, stol, ybuf, ftmp, n_coords(p)
    )
    if s_event <= 1.0:
        return _switch(p, pts, options, rules, y, modes, state, rings, recording, ws, s_event, stol)
    _accept(p, pts, options, y, modes, state, rings, recording, ws, h_free)
    return st.RUNNING


@kernel_jit
def _switch(p, pts, options, rules, y, modes, state, rings, recording, ws, s_event, stol):
    """Cut the step at its earliest event (fraction s_event of it), switch the contacts
    there and record it: st.RUNNING, or st.ZENO after endless switching at one instant."""
    _, phases, intervals, own_steps = rings
    vectors, _, _, _, wk, watch, _, _, _ = ws
    y1, f, ybuf, ymid = vectors[0], vectors[1], vectors[4], vectors[5]
    step = state.step
    counters = state.counters
    t = step.t
    h = step.h
    t_ev = t + s_event * h
    if options.record and options.dt_out > 0.0:
        record_dense(recording, counters, t, h, s_event, y, y1, wk, modes, options.dt_out, ybuf)
    dense_eval(y, y1, wk, s_event, ybuf)
    slip = state.energy.slip
    en.integrate_piece(p, pts, modes, y, y1, wk, s_event, h, ybuf, ymid, state.energy)
    monitor.step(state.motion, y, ybuf, s_event * h)
    own_section.piece(
        state.own, own_steps, state.motion, phases, intervals, y, y1, wk, s_event, t, h,
        ybuf, ymid, vectors[6:8], slip, state.energy.slip,
    )  # fmt: skip
    if options.record:
        record_state(recording, counters, t_ev, ybuf, modes)
    copy_vector(ybuf, y)
    n_sw = switching.switch_at(p, pts, modes, y, f, watch, s_event, h, stol, counters)
    en.refresh(p, pts, modes, y, state.energy)  # the integrand changes with the modes
    monitor.switch(
        state.motion, phases, intervals, t_ev, y, modes, n_sw, state.energy.slip, counters.steps
    )
    if state.motion.opened:
        machine.phase_opened(rules, state.motion, state.verdict)
    counters.events += n_sw
    if t_ev - step.t_last_event < SAME_TIME:
        step.same_time += 1
        if step.same_time > 4 * modes.shape[0] + 8:
            return st.ZENO
    else:
        step.same_time = 0
    step.t_last_event = t_ev
    step.t = t_ev
    if options.record:
        record_state(recording, counters, step.t, y, modes)
    controller.switched(step, options)
    return st.RUNNING


@kernel_jit
def _accept(p, pts, options, y, modes, state, rings, recording, ws, h_free):
    """Accept the whole step (no event inside it) and choose the next."""
    _, phases, intervals, own_steps = rings
    vectors, _, _, _, wk, watch, _, _, _ = ws
    y1, f, f1, ybuf, ymid = vectors[0], vectors[1], vectors[2], vectors[4], vectors[5]
    step = state.step
    t = step.t
    h = step.h
    if options.record and options.dt_out > 0.0:
        record_dense(recording, state.counters, t, h, 1.0, y, y1, wk, modes, options.dt_out, ybuf)
    slip = state.energy.slip
    en.integrate_piece(p, pts, modes, y, y1, wk, 1.0, h, y1, ymid, state.energy)
    monitor.step(state.motion, y, y1, h)
    own_section.piece(
        state.own, own_steps, state.motion, phases, intervals, y, y1, wk, 1.0, t, h,
        y1, ymid, vectors[6:8], slip, state.energy.slip,
    )  # fmt: skip
    step.t = t + h
    copy_vector(y1, y)
    copy_vector(f1, f)
    if options.record and options.dt_out <= 0.0:
        record_state(recording, state.counters, step.t, y, modes)
    switching.step_accepted(p, pts, modes, y, watch)
    controller.accepted(step, options, h_free)


@kernel_entry_allocating
def run(p, pts, options, rules, vp, y, modes, state, rings, recording):
    """Integrate one scene from t = 0 until the verdict's machine stops it or the loop
    fails. Returns (status, t_end [s]).

    p: the parameter record (kernel/model.py PARAMETERS); pts (N, 3): contact points and
    weights; options (kernel/records.py OPTIONS), rules (verdict/records.py RULES), vp
    (verdict/params.py PARAMS): the run's inputs. y (initial state) and modes (int8, one
    per contact) are updated in place and hold the final state and modes. state
    (RUN_STATE, simulation/buffers.py) receives every named measure of the run; rings =
    (revolutions, phases, intervals, own steps) its ring buffers (kernel/records.py); recording =
    (rec_t, rec_y, rec_m) the trajectory buffers (kernel/recording.py). Steps end exactly
    at every whole master revolution, where the machine reads it.
    """
    ws = _workspace(p, y, modes, options, vp)
    _begin(p, pts, options, rules, vp, y, modes, state, rings, recording, ws)
    while True:
        action = _stop_check(p, pts, rules, vp, y, state, rings, ws)
        if action == STOP:
            return state.verdict.state, state.step.t
        if action == RECHECK:
            continue
        if state.counters.steps >= options.max_steps:
            return st.MAX_STEPS, state.step.t
        if state.counters.events >= options.max_events:
            return st.MAX_EVENTS, state.step.t
        status = _attempt(p, pts, options, rules, y, modes, state, rings, recording, ws)
        if status != st.RUNNING:
            return status, state.step.t
