"""One run's buffers: `RunBuffers` owns every record and array the step loop reads or fills.

RUN_STATE is the loop's state record (diffrax's `State`): the stepper and its controller,
the counters, the energy integrals, the motion's facts (kernel/records.py) and the
verdict's machine (frictiondisk/verdict/records.py), nested by name. `RunBuffers` keeps it
together with the inputs (the parameter record, the contacts, options, rules), the ring
buffers and the trajectory buffers from allocation to labelling: the caller fills the
inputs, `run()` hands them to the loop (simulation/loop.py), the result builder reads
them back by name. An integrator without the loop (the scipy-Radau cross-check) allocates
one with `revolutions=False` and fills the motion, verdict and counters itself.
Units: SI (times [s], lengths [m], energies [J]).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from frictiondisk.kernel.energy import ENERGY
from frictiondisk.kernel.records import (
    COUNTERS,
    INTERVAL,
    MOTION,
    OPTIONS,
    OWN,
    OWN_RING,
    OWN_STEP,
    PHASE,
    REV_RING,
    REVOLUTION,
    RING,
    STEPPER,
    one,
)
from frictiondisk.verdict.params import VerdictParams
from frictiondisk.verdict.records import RULES, VERDICT

RUN_STATE = np.dtype(
    [
        ("step", STEPPER),
        ("counters", COUNTERS),
        ("energy", ENERGY),
        ("motion", MOTION),
        ("own", OWN),
        ("verdict", VERDICT),
    ]
)

# (record, its field names) of RUN_STATE, in order: what `RunBuffers.values` zips
STATE_FIELDS = tuple((name, RUN_STATE[name].names) for name in RUN_STATE.names)


@dataclasses.dataclass(eq=False)
class RunBuffers:
    """The buffers of one run (shapes: n states, N contacts, cap recorded rows).

    Inputs: p (a kernel/model.py PARAMETERS record; None without the loop), pts (N, 3),
    options (OPTIONS), rules (RULES), thresholds (VerdictParams); y (n) the state, initial
    then final [SI]; modes (N, int8). state: the RUN_STATE record. Rings: revolutions
    (REV_RING REVOLUTION rows; None for an integrator without them), phases (RING PHASE
    rows), intervals (RING INTERVAL rows), own_steps (OWN_RING OWN_STEP rows: the motion's
    own section, kernel/own_section.py; None without the loop). Recording: rec_t (cap) [s], rec_y (cap, n),
    rec_m (cap, N). status (kernel/status.py or the verdict's final state; 0 before the
    run) and t_end [s].
    """

    p: np.void | None
    pts: np.ndarray | None
    y: np.ndarray
    modes: np.ndarray
    options: np.void
    rules: np.void
    thresholds: VerdictParams
    state: np.void
    revolutions: np.ndarray | None
    phases: np.ndarray
    intervals: np.ndarray
    own_steps: np.ndarray | None
    rec_t: np.ndarray
    rec_y: np.ndarray
    rec_m: np.ndarray
    status: int = 0
    t_end: float = math.nan

    @classmethod
    def allocate(
        cls,
        y0: np.ndarray,
        modes: np.ndarray,
        capacity: int = 1,
        p: np.void | None = None,
        pts: np.ndarray | None = None,
        *,
        thresholds: VerdictParams | None = None,
        options: np.void | None = None,
        rules: np.void | None = None,
        revolutions: bool = True,
    ) -> RunBuffers:
        """Buffers for a run from state y0 in contact modes (both copied), with room for
        `capacity` recorded rows (>= 1). Options and rules: the records given (None: at 0,
        as the counters start)."""
        y = np.array(y0, dtype=np.float64)
        n, ncon = y.shape[0], modes.shape[0]
        cap = max(1, int(capacity))
        return cls(
            p=p,
            pts=pts,
            y=y,
            modes=np.array(modes, dtype=np.int8),
            options=one(OPTIONS) if options is None else options,
            rules=one(RULES) if rules is None else rules,
            thresholds=thresholds or VerdictParams(),
            state=one(RUN_STATE),
            revolutions=np.zeros(REV_RING, dtype=REVOLUTION) if revolutions else None,
            phases=np.empty(RING, dtype=PHASE),
            intervals=np.empty(RING, dtype=INTERVAL),
            own_steps=np.zeros(OWN_RING, dtype=OWN_STEP) if revolutions else None,
            rec_t=np.empty(cap),
            rec_y=np.empty((cap, n)),
            rec_m=np.empty((cap, ncon), dtype=np.int8),
        )

    def run(self) -> RunBuffers:
        """Integrate with the step loop (simulation/loop.py): y and modes end as the final
        state, status and t_end [s] are set. Returns self."""
        from frictiondisk.simulation.loop import run

        if self.p is None or self.pts is None or self.revolutions is None or self.own_steps is None:
            raise ValueError("these RunBuffers were allocated without the loop's inputs")
        status, t_end = run(
            self.p,
            self.pts,
            self.options,
            self.rules,
            self.thresholds.record(),
            self.y,
            self.modes,
            self.state,
            (self.revolutions, self.phases, self.intervals, self.own_steps),
            (self.rec_t, self.rec_y, self.rec_m),
        )
        self.status, self.t_end = int(status), float(t_end)
        return self

    def finish(self, status: int, t_end: float, y_end: np.ndarray) -> None:
        """Set the outcome of a run integrated elsewhere: status, t_end [s], final state.
        `modes` keeps its initial values: such an integrator tracks its own modes."""
        self.status, self.t_end = int(status), float(t_end)
        self.y = np.asarray(y_end, dtype=np.float64)

    def set_counters(self, steps: int, rejected: int, refused: int) -> None:
        """Counters of a run integrated elsewhere."""
        counters = self.state["counters"]
        counters["steps"] = steps
        counters["rejected"] = rejected
        counters["refused"] = refused

    # --- read back -------------------------------------------------------------------

    @property
    def motion(self) -> np.void:
        """The MOTION record (kernel/records.py)."""
        return self.state["motion"]

    @property
    def own(self) -> np.void:
        """The OWN record: the own section's state (kernel/records.py)."""
        return self.state["own"]

    @property
    def verdict(self) -> np.void:
        """The VERDICT record (frictiondisk/verdict/records.py)."""
        return self.state["verdict"]

    @property
    def steps(self) -> int:
        """Accepted integrator steps."""
        return int(self.state["counters"]["steps"])

    @property
    def rejected(self) -> int:
        """Rejected steps (0 = unknown for scipy-Radau)."""
        return int(self.state["counters"]["rejected"])

    @property
    def refused(self) -> int:
        """Refused stick entries (docs/model.md section 3)."""
        return int(self.state["counters"]["refused"])

    @property
    def recorded(self) -> int:
        """Rows written to rec_t, rec_y, rec_m."""
        return int(self.state["counters"]["recorded"])

    @property
    def truncated(self) -> bool:
        """Whether the recording ran out of rows."""
        return bool(self.state["counters"]["truncated"])

    @property
    def budget_spent(self) -> bool:
        """Whether a run still settling hit the horizon budget (numerics.horizon_budget)."""
        return bool(self.verdict["budget_spent"])

    @property
    def work_in(self) -> float:
        """Work put in by the master up to t_end [J]."""
        return float(self.state["energy"]["w_in"])

    @property
    def work_dissipated(self) -> float:
        """Energy dissipated up to t_end [J]."""
        return float(self.state["energy"]["w_diss"])

    @property
    def slip_total(self) -> float:
        """Net plastic slip of the mean contact up to t_end [m]; NaN without the ring."""
        return math.nan if self.revolutions is None else float(self.state["energy"]["slip"])

    def values(self) -> dict[str, dict[str, Any]]:
        """The state record's values as plain Python numbers, by record and field name
        ({"motion": {"r1": ..., ...}, "verdict": ..., ...}): one read of the whole record
        instead of one per field, a copy that later writes do not reach."""
        return {
            name: dict(zip(fields, record, strict=True))
            for (name, fields), record in zip(STATE_FIELDS, self.state.item(), strict=True)
        }

    def recorded_rows(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(t [s], y, modes) of the recorded rows (views into the buffers)."""
        k = self.recorded
        return self.rec_t[:k], self.rec_y[:k], self.rec_m[:k]
