"""One run's buffers: `KernelRun` owns every array the kernel's entry point reads or fills.

`driver.run` takes 17 plain arrays (numba compiles best with those); `KernelRun` keeps
them together from allocation to classification: the caller fills the options, `run()`
splats them into the kernel, and the result builder reads the monitor state and the
counters back by name. An integrator without the kernel (the scipy-Radau cross-check)
allocates one with `revolutions=False` and fills the monitor state and counters itself.
Units: SI (times [s], lengths [m], energies [J]).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from . import driver, recording
from . import energy as en
from . import monitor as mon


@dataclasses.dataclass(eq=False)
class KernelRun:
    """The buffers of one run (shapes: n states, N contacts, cap recorded rows).

    Inputs: p (model.N_PARAMS) and pts (N, 3) (None without the kernel), y (n) the state,
    initial then final [SI], modes (N, int8), iopt / fopt (driver.O_* options).
    Recording: rec_t (cap) [s], rec_y (cap, n), rec_m (cap, N). Monitor state: mf, mi,
    ring_all, ring_any (kernel/monitor_slots.py). Revolution ring: rv (REV_RING, N_RV) and
    yrev (n) scratch; None for an integrator without them. Outputs: out_i (driver.C_*),
    out_f (energy.E_*), status (kernel/status.py; 0 before the run) and t_end [s].
    """

    p: np.ndarray | None
    pts: np.ndarray | None
    y: np.ndarray
    modes: np.ndarray
    iopt: np.ndarray
    fopt: np.ndarray
    rec_t: np.ndarray
    rec_y: np.ndarray
    rec_m: np.ndarray
    mf: np.ndarray
    mi: np.ndarray
    ring_all: np.ndarray
    ring_any: np.ndarray
    rv: np.ndarray | None
    yrev: np.ndarray | None
    out_i: np.ndarray
    out_f: np.ndarray
    status: int = 0
    t_end: float = math.nan

    @classmethod
    def allocate(
        cls,
        y0: np.ndarray,
        modes: np.ndarray,
        capacity: int = 1,
        p: np.ndarray | None = None,
        pts: np.ndarray | None = None,
        *,
        revolutions: bool = True,
    ) -> KernelRun:
        """Buffers for a run from state y0 in contact modes (both copied), with room for
        `capacity` recorded rows (>= 1). Options and counters start at 0."""
        y = np.array(y0, dtype=np.float64)
        n, ncon = y.shape[0], modes.shape[0]
        cap = max(1, int(capacity))
        return cls(
            p=p,
            pts=pts,
            y=y,
            modes=np.array(modes, dtype=np.int8),
            iopt=np.zeros(driver.N_IOPT, dtype=np.int64),
            fopt=np.zeros(driver.N_FOPT),
            rec_t=np.empty(cap),
            rec_y=np.empty((cap, n)),
            rec_m=np.empty((cap, ncon), dtype=np.int8),
            mf=np.empty(mon.N_MF),
            mi=np.empty(mon.N_MI, dtype=np.int64),
            ring_all=np.empty((mon.RING, mon.N_RA)),
            ring_any=np.empty((mon.RING, 2)),
            rv=np.zeros((mon.REV_RING, mon.N_RV)) if revolutions else None,
            yrev=np.empty_like(y) if revolutions else None,
            out_i=np.zeros(driver.N_OUT_I, dtype=np.int64),
            out_f=np.zeros(en.N_OUT_F),
        )

    def args(self) -> tuple:
        """The 17 arrays in the positional order of `driver.run`."""
        return (
            self.p,
            self.pts,
            self.y,
            self.modes,
            self.iopt,
            self.fopt,
            self.rec_t,
            self.rec_y,
            self.rec_m,
            self.mf,
            self.mi,
            self.ring_all,
            self.ring_any,
            self.rv,
            self.yrev,
            self.out_i,
            self.out_f,
        )

    def run(self) -> KernelRun:
        """Integrate with the kernel (`driver.run`): y and modes end as the final state,
        status and t_end [s] are set. Returns self."""
        if self.p is None or self.pts is None or self.rv is None:
            raise ValueError("this KernelRun was allocated without the kernel's inputs")
        status, t_end = driver.run(*self.args())
        self.status, self.t_end = int(status), float(t_end)
        return self

    def finish(self, status: int, t_end: float, y_end: np.ndarray) -> None:
        """Set the outcome of a run integrated elsewhere: status, t_end [s], final state.
        `modes` keeps its initial values: such an integrator tracks its own modes."""
        self.status, self.t_end = int(status), float(t_end)
        self.y = np.asarray(y_end, dtype=np.float64)

    def set_counters(self, steps: int, rejected: int, refused: int) -> None:
        """Counters of a run integrated elsewhere (driver.C_STEPS, C_REJECTED, C_REFUSED)."""
        self.out_i[driver.C_STEPS] = steps
        self.out_i[driver.C_REJECTED] = rejected
        self.out_i[driver.C_REFUSED] = refused

    # --- read back -------------------------------------------------------------------

    def monitor(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(mf, mi, ring_all, ring_any): the monitor state, as kernel/monitor.py takes it."""
        return self.mf, self.mi, self.ring_all, self.ring_any

    @property
    def steps(self) -> int:
        """Accepted integrator steps."""
        return int(self.out_i[driver.C_STEPS])

    @property
    def rejected(self) -> int:
        """Rejected steps (0 = unknown for scipy-Radau)."""
        return int(self.out_i[driver.C_REJECTED])

    @property
    def refused(self) -> int:
        """Refused stick entries (docs/model.md section 3)."""
        return int(self.out_i[driver.C_REFUSED])

    @property
    def recorded(self) -> int:
        """Rows written to rec_t, rec_y, rec_m."""
        return int(self.out_i[recording.C_RECORDED])

    @property
    def truncated(self) -> bool:
        """Whether the recording ran out of rows."""
        return bool(self.out_i[recording.C_TRUNCATED])

    @property
    def budget_spent(self) -> bool:
        """Whether a run still settling hit the horizon budget (numerics.horizon_budget)."""
        return bool(self.out_i[driver.C_BUDGET_SPENT])

    @property
    def work_in(self) -> float:
        """Work put in by the master up to t_end [J]."""
        return float(self.out_f[en.E_W_IN])

    @property
    def work_dissipated(self) -> float:
        """Energy dissipated up to t_end [J]."""
        return float(self.out_f[en.E_W_DISS])

    @property
    def slip_total(self) -> float:
        """Net plastic slip of the mean contact up to t_end [m]; NaN without the ring."""
        return math.nan if self.rv is None else float(self.out_f[en.E_SLIP])

    def recorded_rows(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(t [s], y, modes) of the recorded rows (views into the buffers)."""
        k = self.recorded
        return self.rec_t[:k], self.rec_y[:k], self.rec_m[:k]
