"""Cross-check integrator: the model in plain numpy, integrated by scipy's Radau.

`simulate_radau` (selected by ``numerics.method: scipy-radau``) integrates the same scenes
as the numba kernel, but shares with it only what must be shared:

* the inputs: `initial_state` (state layout of kernel/model.py) and the config;
* the bookkeeping: the kernel's monitor functions (kernel/monitor.py) on the records of
  a `RunBuffers` (simulation/buffers.py), the verdict's rules for segments
  (verdict/segment_rules.py) and `result_builder.build_result`, so both integrators are
  labelled by the same rules.

Everything that could hide a bug is written again, from docs/model.md sections 2-4:
the right-hand side, the switching functions (|k_i| - F_St,i in stick, minus beta_i eps in
slide) and their time derivative (`NumpyModel` in simulation/numpy_model.py, parameters
read from the config, not from `pack_parameters`), and here event location (scipy's
`solve_ivp` events: brentq on Radau's dense output), simultaneous switches and refused
entries. A bug on either side shows as disagreement between the two.

Integration is piecewise: between switches the contact modes are fixed and `solve_ivp`
integrates one smooth ODE, with one terminal event per contact, w_i = sigma_i s_i
(sigma = +1 in stick, -1 in slide) crossing 0 upwards. Radau gets a finite-difference
Jacobian (scipy's own, one vectorized call of the numpy right-hand side per Jacobian)
and its sparsity (`NumpyModel.jacobian_sparsity`: each contact couples only to the
rigid-body coordinates), so it factors a sparse matrix: usable with hundreds of contacts.

Contacts in the hysteresis band of their mode (kernel/switching.py) watch their stick rate
ds/dt instead (a stuck one slides when it rises through 0, a sliding one sticks when it
falls through 0), located as events on both sides. Deliberate differences from the kernel
(the model is the same; these are numerics):
* A contact leaves the hysteresis band of its mode (kernel/switching.py) when its
  switching function changes sign: located here, tested at step ends by the step loop (it
  changes no dynamics, only which event is watched).
* scipy finds an event only where w changes sign between two step ends; a crossing and
  re-crossing inside one step (a graze, which the kernel's `find_graze` looks for) is
  missed. Keep h_max small when comparing runs near a graze.
* n_rejected is 0: solve_ivp does not report rejected steps.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from frictiondisk.kernel import monitor
from frictiondisk.kernel import status as st
from frictiondisk.simulation.buffers import RunBuffers
from frictiondisk.simulation.numpy_model import SLIDE, STICK, NumpyModel
from frictiondisk.simulation.pack import initial_state, new_rules
from frictiondisk.simulation.result import SimulationResult, Trajectory
from frictiondisk.simulation.result_builder import build_result
from frictiondisk.verdict import machine, segment_rules
from frictiondisk.verdict.params import VerdictParams
from frictiondisk.verdict.records import RECHECK, STOP

__all__ = ["NumpyModel", "simulate_radau"]

SAME_TIME = 1e-12  # [s] switches closer than this count as one instant (Zeno guard, as the kernel)
SIMULTANEOUS = 1e-9  # [s] crossings this close after a located one switch with it (kernel)
TINY_SEGMENT = 1e-14  # [s], relative to max(1, t): a segment this short is not integrated


class _StepBudget(Exception):
    """Raised from inside solve_ivp when the step budget numerics.max_steps is used up."""


@dataclasses.dataclass
class _Segment:
    """What one solve_ivp call between switches produced."""

    t: np.ndarray  # step ends, t[0] = segment start [s]
    y: np.ndarray  # states at t, shape (len(t), n), C-contiguous rows for the monitor
    kind: str  # "end" (reached t1), "event", "budget" or "failed"
    fired: list  # (kind, contact) of the terminal event: ("w" | "clear" | "enter", i)
    sol: object = None  # dense output (OdeSolution) if requested
    failure: int = 0  # kernel status code for kind == "failed"


class _RadauRun:
    """One run: the segment loop and the switching rules of the step loop
    (simulation/loop.py, kernel/switching.py); the stop rules are verdict/segment_rules.py."""

    def __init__(self, config, model: NumpyModel, record: bool, dt_out: float):
        num = config.numerics
        self.config = config
        self.model = model
        self.num = num
        self.record = record
        self.dt_out = dt_out
        n = model.n_contacts
        self.sparsity = model.jacobian_sparsity()
        self.modes = np.zeros(n, dtype=np.int8)
        self.band = np.zeros(n, dtype=np.int8)
        # contacts whose band was cleared at the last event: their s sits at 0 to round-off
        self.cleared = np.zeros(n, dtype=bool)
        # the motion, verdict and counters, in the step loop's records
        self.out = RunBuffers.allocate(
            np.zeros(model.n_states), self.modes, rules=new_rules(config), revolutions=False
        )
        self.n_steps = 0
        self.n_events = 0
        self.n_refused = 0
        self.rec_t: list[float] = []
        self.rec_y: list[np.ndarray] = []
        self.rec_m: list[np.ndarray] = []

    # --- recording -----------------------------------------------------------------------

    def _rec(self, t, y):
        if self.record:
            self.rec_t.append(float(t))
            self.rec_y.append(np.array(y, dtype=float))
            self.rec_m.append(self.modes.copy())

    def trajectory(self) -> Trajectory:
        nq = self.model.nq
        t = np.asarray(self.rec_t)
        y = np.vstack(self.rec_y) if self.rec_y else np.empty((0, self.model.n_states))
        m = np.vstack(self.rec_m) if self.rec_m else np.empty((0, self.model.n_contacts), np.int8)
        return Trajectory.from_states(t, y, m, nq)

    # --- one segment -----------------------------------------------------------------------

    def _integrate(self, t0: float, y0: np.ndarray, t1: float) -> _Segment:
        """Integrate from t0 to t1 in the current modes; stop at the first switching event."""
        model = self.model
        modes = self.modes.copy()
        band = self.band.copy()
        cache: dict = {}

        def fun(t, y):
            return model.rhs(y, modes)

        def s_all(t, y):
            # solve_ivp evaluates every event at each step end with the same y object
            if cache.get("y") is y and cache.get("t") == t:
                return cache["s"]
            s = model.switch(y, modes)
            cache.update(t=t, y=y, s=s)
            return s

        events = []
        labels = []
        for i in range(model.n_contacts):
            if band[i] and modes[i] == STICK:
                # stuck above the limit: s falling through 0 clears the band, |k| starting
                # to grow (stick rate rising through 0) makes it slide
                events.append(lambda t, y, i=i: -s_all(t, y)[i])
                labels.append(("clear", i))
                events.append(lambda t, y, i=i: model.stick_rate(y, modes, i))
                labels.append(("rise", i))
            elif band[i]:
                # sliding below the end-of-slide threshold: s rising through 0 clears the
                # band, a stick rate falling through 0 lets it enter stick
                events.append(lambda t, y, i=i: s_all(t, y)[i])
                labels.append(("clear", i))
                events.append(lambda t, y, i=i: -model.stick_rate(y, modes, i))
                labels.append(("enter", i))
            else:
                sigma = 1.0 if modes[i] == STICK else -1.0
                events.append(lambda t, y, i=i, sigma=sigma: sigma * s_all(t, y)[i])
                labels.append(("w", i))
        for ev in events:
            ev.terminal = True
            ev.direction = 1.0

        # Step watchdog: solve_ivp calls every event function once at t0 and once per
        # accepted step (root finding only calls *active* events, and this one never
        # changes sign), so it sees every step end. It enforces numerics.max_steps.
        budget = self.num.max_steps - self.n_steps
        seen_t: list[float] = []
        seen_y: list[np.ndarray] = []

        def watchdog(t, y):
            if len(seen_t) > budget:
                raise _StepBudget
            seen_t.append(float(t))
            seen_y.append(np.array(y, dtype=float))
            return 1.0

        watchdog.terminal = False
        watchdog.direction = 0.0

        def partial(kind, failure=0):
            ts = np.asarray(seen_t)
            ys = np.vstack(seen_y) if seen_y else y0[None, :].copy()
            return _Segment(ts, ys, kind, [], None, failure)

        dense = self.record and self.dt_out > 0.0
        try:
            with np.errstate(all="ignore"):
                sol = solve_ivp(
                    fun,
                    (t0, t1),
                    y0,
                    method="Radau",
                    rtol=self.num.rtol,
                    atol=self.num.atol,
                    max_step=self.num.h_max,
                    events=[*events, watchdog],
                    vectorized=True,
                    jac_sparsity=self.sparsity,
                    dense_output=dense,
                )
        except _StepBudget:
            return partial("budget")
        except (ArithmeticError, ValueError, np.linalg.LinAlgError, RuntimeError):
            # e.g. brentq on NaN event values, or splu's "Factor is exactly singular" (a
            # RuntimeError) on a NaN Jacobian: numerical trouble, never an exception to the user
            return partial("failed", self._failure_code(seen_y[-1] if seen_y else y0))
        ys = np.ascontiguousarray(sol.y.T)
        if sol.status == -1:
            return _Segment(sol.t, ys, "failed", [], None, self._failure_code(ys[-1]))
        if sol.status == 1:
            fired = [labels[k] for k in range(len(events)) if len(sol.t_events[k]) > 0]
            return _Segment(sol.t, ys, "event", fired, sol.sol)
        return _Segment(sol.t, ys, "end", [], sol.sol)

    def _failure_code(self, y) -> int:
        with np.errstate(all="ignore"):
            f = self.model.rhs(y, self.modes)
        if not (np.all(np.isfinite(y)) and np.all(np.isfinite(f))):
            return st.NONFINITE
        return st.STEP_TOO_SMALL

    def _account(self, seg: _Segment):
        """Monitor and record the accepted steps of a segment (the last one up to its event)."""
        ts, ys = seg.t, seg.y
        monitor.steps_through(self.out.motion, np.asarray(ts, dtype=float), ys)
        self.n_steps += len(ts) - 1
        if not self.record:
            return
        if self.dt_out > 0.0:
            if seg.sol is not None and len(ts) > 1:
                k0 = math.floor(ts[0] / self.dt_out) + 1
                k1 = math.floor(ts[-1] / self.dt_out)
                for k in range(k0, k1 + 1):
                    tk = k * self.dt_out
                    if ts[0] < tk <= ts[-1]:
                        self._rec(tk, seg.sol(tk))
            if seg.kind == "event":
                self._rec(ts[-1], ys[-1])  # the switching point, in the old modes
        else:
            for k in range(1, len(ts)):
                self._rec(ts[k], ys[k])

    # --- switching rules ---------------------------------------------------------------

    def _check_entries(self, y, entered) -> int:
        """Refused-entry rule of the kernel (`_check_entries`, docs/model.md section 3).

        A contact that entered stick whose s would increase under stick dynamics is refused:
        it stays in slide and counts in n_refused (not as a switch: its mode does not
        change). Every contact that switched gets its band flag. Returns the number refused.
        ds/dt: complex-step derivative of the numpy s along the numpy rhs (`switch_rate`).
        """
        model = self.model
        rate = model.switch_rate(y, model.rhs(y, self.modes))
        in_band = model.in_band(y, self.modes)
        for i in range(model.n_contacts):
            if entered[i] or self.band[i]:
                self.band[i] = int(in_band[i])
        refused = 0
        for i in np.nonzero(entered == 1)[0]:  # a re-entry (2) is consistent by construction
            if self.modes[i] == STICK and rate[i] > 0.0:
                self.modes[i] = SLIDE
                entered[i] = 0
                self.band[i] = 1  # sliding at its end-of-slide threshold: re-entry is watched
                refused += 1
        self.n_refused += refused
        return refused

    def _switch(self, t, y, seg: _Segment) -> int:
        """Apply the switches at a terminal event; returns the number of mode switches."""
        model = self.model
        n = model.n_contacts
        old_band = self.band.copy()
        entered = np.zeros(n, dtype=np.int8)
        n_sw = 0
        s = model.switch(y, self.modes)
        in_band = model.in_band(y, self.modes)
        sigma = np.where(self.modes == STICK, 1.0, -1.0)
        # w and its rate in the segment's modes: crossings within SIMULTANEOUS of the located
        # one are switched together (symmetric contact layouts cross within round-off)
        w = sigma * s
        w_ahead = w + SIMULTANEOUS * sigma * model.switch_rate(y, model.rhs(y, self.modes))
        fired_w = {i for kind, i in seg.fired if kind == "w"}
        for i in range(n):
            if old_band[i]:
                continue
            # a contact whose band was just cleared at a located root may sit on the far
            # side of 0 by round-off while moving away from its threshold: not a crossing
            past = w[i] >= 0.0 and not (self.cleared[i] and w_ahead[i] < 0.0)
            if i in fired_w or past or w_ahead[i] >= 0.0:
                self.modes[i] = SLIDE if self.modes[i] == STICK else STICK
                entered[i] = 1
                n_sw += 1
        self.cleared[:] = False
        for kind, i in seg.fired:
            if kind == "w":
                continue
            self.band[i] = 0
            self.cleared[i] = kind == "clear"
            if kind in ("enter", "rise") and in_band[i]:
                self.modes[i] = SLIDE if self.modes[i] == STICK else STICK
                entered[i] = 2 if kind == "enter" else 1
                n_sw += 1
        if entered.any():
            n_sw -= self._check_entries(y, entered)
        return n_sw

    # --- the run -------------------------------------------------------------------------

    def run(self, y: np.ndarray, modes: np.ndarray) -> tuple[int, float, np.ndarray]:
        """Integrate from t = 0 until a stop rule fires: (status, t_end, y_end)."""
        out = self.out
        rules, motion, verdict = out.rules, out.motion, out.verdict
        num = self.num
        self.modes[:] = modes
        self.band[:] = self.model.in_band(y, self.modes)
        t = 0.0
        phases, intervals = out.phases, out.intervals
        monitor.begin(motion, phases, intervals, t, y, self.modes, self.model.nq, 0.0)
        segment_rules.begin(rules, verdict)
        if motion["opened"]:
            machine.phase_opened(rules, motion, verdict)
        self._rec(t, y)
        t_last_event = -1.0
        n_same_time = 0

        while True:
            # ---- the verdict's stop rules ------------------------------------------------
            action = segment_rules.check(rules, motion, verdict, t)
            if action == STOP:
                return int(verdict["state"]), t, y
            if action == RECHECK:
                continue
            if self.n_steps >= num.max_steps:
                return st.MAX_STEPS, t, y
            if self.n_events >= num.max_events:
                return st.MAX_EVENTS, t, y

            # ---- one segment in fixed modes ---------------------------------------------
            t1 = segment_rules.segment_end(rules, motion, verdict)
            if t1 - t <= TINY_SEGMENT * max(1.0, t):
                t = t1  # closer than the time resolution: the target is reached
                continue
            seg = self._integrate(t, y, t1)
            self._account(seg)
            t = float(seg.t[-1])
            y = seg.y[-1].copy()
            if seg.kind == "budget":
                return st.MAX_STEPS, t, y
            if seg.kind == "failed":
                return seg.failure, t, y

            n_sw = 0
            if seg.kind == "event":
                if t - t_last_event < SAME_TIME:
                    n_same_time += 1
                    if n_same_time > 4 * self.model.n_contacts + 8:
                        return st.ZENO, t, y
                else:
                    n_same_time = 0
                t_last_event = t
                n_sw += self._switch(t, y, seg)
            if n_sw > 0:
                monitor.switch(motion, phases, intervals, t, y, self.modes, n_sw, math.nan, 0)
                if motion["opened"]:
                    machine.phase_opened(rules, motion, verdict)
                self.n_events += n_sw
                self._rec(t, y)


def simulate_radau(
    config,
    record: bool = False,
    dt_out: float = 0.0,
    *,
    dense_lu: bool = False,
    verdict: VerdictParams | None = None,
    objective_rate: bool = True,
) -> SimulationResult:
    """Run one scene with scipy's Radau (the cross-check and slow baseline of the kernel).

    Same model, switching rules, stopping rules and classification as the numba kernel
    (`frictiondisk.simulation.simulate.simulate` with method rodas4), from an independent numpy
    implementation of the equations and scipy's event location.

    record: keep the trajectory: every solver step, or dense-output samples every dt_out
    seconds if dt_out > 0; switching instants are recorded twice (old and new modes).
    Numerical failure never raises: it ends the run as `undetermined` with the reason.
    dense_lu: no stage matrix here (an argument of every method, simulation/simulate.py);
    verdict: the thresholds of the label. objective_rate=False integrates the contact state without the rotation term of docs/model.md
    section 3 (u_i = v_i): a study variant (studies/brake/rotation_term.py), not the model.
    """
    wall0 = time.perf_counter()
    model = NumpyModel.from_config(config, objective_rate=objective_rate)
    y0 = initial_state(config).astype(float)
    run = _RadauRun(config, model, record, dt_out)
    status, t_end, y_end = run.run(y0, model.initial_modes(y0))
    wall = time.perf_counter() - wall0
    run.out.finish(status, t_end, y_end)
    # solve_ivp does not report rejected steps (Radau's OdeSolver keeps no such counter),
    # so n_rejected is 0 = unknown, not "none rejected".
    run.out.set_counters(steps=run.n_steps, rejected=0, refused=run.n_refused)
    trajectory = run.trajectory() if record else None
    return build_result(config, run.out, wall, trajectory, verdict=verdict or VerdictParams())
