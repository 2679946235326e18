"""What one simulation run returns: outcome, measures and (optionally) the trajectory."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np


@dataclasses.dataclass(frozen=True)
class Trajectory:
    """Recorded samples of one run (SI units).

    t: time [s], shape (n,)
    x, y: slave (pin or disk centre) position [m], shape (n,)
    vx, vy: slave velocity [m/s], shape (n,)
    phi, phidot: disk rotation [rad], [rad/s], shape (n,); None for the pin
    Zx, Zy: elastic contact force of each contact in the fixed frame [N], shape (n, N)
    mode: contact mode, 1 = stick, 0 = slide, shape (n, N), int8
    """

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    phi: np.ndarray | None
    phidot: np.ndarray | None
    Zx: np.ndarray
    Zy: np.ndarray
    mode: np.ndarray
    truncated: bool = False

    @classmethod
    def from_states(
        cls, t: np.ndarray, y: np.ndarray, mode: np.ndarray, nq: int, truncated: bool = False
    ) -> Trajectory:
        """Split rows of the kernel state layout (kernel/model.py; nq = 2 pin, 3 disk)."""
        return cls(
            t=np.array(t, dtype=float),
            x=y[:, 0].copy(),
            y=y[:, 1].copy(),
            vx=y[:, nq].copy(),
            vy=y[:, nq + 1].copy(),
            phi=y[:, 2].copy() if nq == 3 else None,
            phidot=y[:, nq + 2].copy() if nq == 3 else None,
            Zx=y[:, 2 * nq :: 2].copy(),
            Zy=y[:, 2 * nq + 1 :: 2].copy(),
            mode=np.array(mode, dtype=np.int8),
            truncated=truncated,
        )

    @property
    def n_contacts(self) -> int:
        return int(self.mode.shape[1])

    @property
    def all_stick(self) -> np.ndarray:
        """True where every contact sticks (the slave moves rigidly with the master)."""
        return np.all(self.mode == 1, axis=1)


@dataclasses.dataclass(frozen=True)
class SimulationResult:
    """Outcome and measures of one run (docs/model.md section 6). Lengths in m, times in s."""

    outcome: str  # one of frictiondisk/verdict/outcomes.py OUTCOMES
    reason: str  # why this outcome; for `undetermined`, what went wrong
    R1: float  # first sticking radius |r| [m], NaN if the slave never stuck
    t_R1: float  # time of first sticking [s], NaN if never
    size: float  # sticking-circle radius (stick) or sticking-segment radius of the converged cycle [m]
    a: float  # largest excess |r| - R_stick while sliding on the converged cycle [m]
    n_transitions: int  # contact mode switches (stick<->slide), all contacts
    stick_fraction: float  # fraction of the final window with every contact sticking
    t_end: float  # simulated time reached [s]
    n_steps: int  # accepted integrator steps
    n_rejected: int  # rejected integrator steps
    n_refused: int  # refused slide->stick entries (docs/model.md section 3)
    cycle_converged: bool  # limit cycle converged (section-point test)
    wall_s: float  # wall time of the run [s]
    method: str  # numerics.method used
    trajectory: Trajectory | None = None
    # per-revolution measures of the last revolutions, oldest first (kernel/records.py
    # REVOLUTION rows: revolutions["slip"], ...)
    revolutions: np.ndarray | None = None
    # the last whole-body sticking phases, oldest first (kernel/records.py PHASE rows)
    sections: np.ndarray | None = None
    # the motion's own section, oldest first (kernel/records.py OWN_STEP rows; None for
    # integrators without the step loop)
    own_section: np.ndarray | None = None
    # Energy balance E(t_end) - E(0) = energy_in - energy_dissipated (kernel/energy.py);
    # NaN for integrators without the diagnostic (scipy-radau, coulomb).
    energy_in: float = math.nan  # work the driven master put in [J]
    energy_dissipated: float = math.nan  # work of the dampers and friction [J]
    energy_residual: float = math.nan  # (dE - in + dissipated) / largest term [1]
    # Co-rotation measures (verdict/corotation.py), over the last whole master revolution; NaN
    # before the first one and for integrators without them (scipy-radau, coulomb).
    n_revolutions: int = 0  # whole master revolutions completed
    slip_per_rev: float = (
        math.nan
    )  # net plastic slip of the mean contact, sum_i w_i int |w_i'| dt [m]
    drift_per_rev: float = math.nan  # drift of the slave centre in the master frame [m]
    spin_drift_per_rev: float = math.nan  # drift of the spin phase phi - omega_m t [rad]
    slip_decay: float = math.nan  # mean log ratio of successive revolutions' slips [1]
    slip_limit: float = math.nan  # extrapolated limit of slip_per_rev (Aitken) [m]
    slip_total: float = math.nan  # net plastic slip over the whole run [m]
    # mu - demand(R1) / F_n: > 0 where the first sticking circle holds (verdict/reserve.py)
    reserve: float = math.nan  # [1]
    # the rule that decided the outcome (verdict/deciding_rule.py DECIDING_RULES; "" where
    # the integrator has its own rules: the exact Coulomb pin)
    decided_by: str = ""
    # The pure-sliding motion's measures (verdict/motion_evidence.py), read from the own
    # section of runs that slide; NaN where they do not apply.
    own_period: float = math.nan  # the motion's own period (velocity phase turning 2 pi) [s]
    mean_radius: float = math.nan  # time mean of |r| over the newest own period [m]
    amplitude: float = math.nan  # (max |r| - min |r|) / 2 over it [m]
    spin_rate: float = math.nan  # mean phidot over it [rad/s] (NaN for the pin)
    floquet_ratio: float = math.nan  # contraction of the own section per own period [1]
    decay_rate: float = math.nan  # -ln(floquet_ratio) / own_period [1/s]
    r_eq_x: float = math.nan  # self-centring: the rest point x [m]
    r_eq_y: float = math.nan  # ... y [m]
    r_eq: float = math.nan  # ... its radius [m]
    r_eq_angle: float = math.nan  # ... its angle from +x, counter-clockwise [rad]
    envelope_period: float = math.nan  # modulated: the envelope's period [s]
    envelope_depth: float = math.nan  # ... half the range of the step-mean |r| [m]

    def summary(self) -> dict[str, Any]:
        """JSON-friendly dict of everything but the trajectory (NaN becomes None)."""
        out: dict[str, Any] = {}
        for name in SUMMARY_FIELDS:
            value = getattr(self, name)
            if isinstance(value, float) and not math.isfinite(value):
                value = None
            out[name] = value
        return out


# the fields of SimulationResult.summary, in order: all but the trajectory and the records
SUMMARY_FIELDS = tuple(
    field.name
    for field in dataclasses.fields(SimulationResult)
    if field.name not in ("trajectory", "revolutions", "sections", "own_section")
)
