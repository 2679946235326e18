"""What the label reads of a finished run (plain dataclasses, SI units): the machine's final
state and the loop's counters (`RunFacts`), the co-rotation rule's measures
(`Revolutions`) and the section evidence (`Evidence`, which words itself)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .motion_evidence import OwnScene
from .records import (
    EV_CANNOT,
    EV_CONTRACT,
    EV_DEPART,
    EV_GRAZE,
    EV_REPEAT,
    EV_RIM,
    EV_SHAKEDOWN,
    EV_SLIDING,
    SOURCE_CYCLES,
)


@dataclasses.dataclass(frozen=True)
class Revolutions:
    """The per-revolution measures behind the co-rotation verdict (kernel/monitor.py,
    verdict/corotation.py)."""

    count: int  # whole master revolutions completed
    slip: float  # net plastic slip over the last revolution [m]
    drift: float  # drift of the slave centre over it, in the master frame [m]
    spin_drift: float  # drift of the spin phase phi - omega_m t over it [rad] (NaN: pin)
    decay: float  # mean log ratio of successive slips over the verdict window [1/rev]
    decay_se: float  # its standard error [1/rev]
    remaining: float  # slip still to come under that decay [m]
    limit: float  # extrapolated limit of the slip per revolution [m] (NaN: none)
    limit_spread: float  # range of that estimate made 0 ... m revolutions back [m] (NaN: none)
    on_orbit: bool  # some contact stuck at every instant of the last revolution
    settling: bool  # still on its way to a decision when the horizon budget ran out
    tol: float  # slip per revolution that counts as none, eps T [m]


@dataclasses.dataclass(frozen=True)
class Evidence:
    """What the motion's own section showed at the last check (verdict/section_evidence.py)."""

    kind: int  # verdict/records.py EV_*
    source: int  # SOURCE_CYCLES or SOURCE_REVOLUTIONS (0: none)
    distance: float  # newest section distance [m]
    ratio: float  # its contraction ratio per step (distance / the one before)
    ratio_bound: float  # the extrapolated bound on that ratio (EV_CONTRACT)
    limit: float  # slip limit [m] (EV_SHAKEDOWN) or travel still to come [m] (EV_CONTRACT)
    lag: int  # sticking phases (revolutions) per period of a repeating cycle
    points: int  # section points read
    sliding_revs: int = 0  # revolutions slid as a whole at the last sliding check
    envelope_revs: int = 0  # H of its lowest-slip comparison (verdict/sliding.py)

    @property
    def step(self) -> str:
        return "cycle" if self.source == SOURCE_CYCLES else "revolution"

    @property
    def section(self) -> str:
        return (
            "the onsets of whole-body sticking"
            if self.source == SOURCE_CYCLES
            else "the state at every master revolution"
        )

    def describe(self) -> str:
        """The evidence in words, with its measures."""
        kind = self.kind
        if kind == EV_REPEAT:
            every = "" if self.lag == 1 else f" every {self.lag} {self.step}s"
            return (
                f"the section at {self.section} repeats{every} within "
                f"{self.distance:.3g} m: a cycle reached"
            )
        if kind == EV_CONTRACT:
            return (
                f"the section at {self.section} contracts geometrically by {self.ratio:.3g} "
                f"per {self.step} (bound {self.ratio_bound:.3g}), {self.limit:.3g} m still to "
                "travel, towards a cycle that still slips"
            )
        if kind == EV_DEPART:
            return (
                f"the section at {self.section} moves away from sticking: slip per {self.step} "
                f"growing, sticking time shrinking, steps of {self.distance:.3g} m (ratio "
                f"{self.ratio:.3g})"
            )
        if kind == EV_SLIDING:
            return (
                f"slides as a whole for {self.sliding_revs} revolutions, its slip per "
                "revolution not falling revolution after revolution and its lowest over the "
                f"newest {self.envelope_revs} revolutions not below the lowest of the "
                f"{self.envelope_revs} before (no approach to sticking)"
            )
        if kind == EV_GRAZE:
            return (
                f"it leaves sticking for a moment in each of its last {self.points} "
                f"revolutions (newest slip {self.distance:.3g} m), each slip carrying it "
                f"outward ({self.ratio:.3g} of the slip's direction, m_s omega_m^2 > c_s): "
                "onto a circle that demands more, so it cannot shake down (a grazing departure)"
            )
        if kind == EV_RIM:
            return (
                f"it leaves sticking for a moment in each of its last {self.points} "
                f"revolutions (newest slip {self.distance:.3g} m), each slip carrying it "
                f"inward ({-self.ratio:.3g} of the slip's direction, m_s omega_m^2 < c_s): onto "
                "circles that demand less, so it creeps onto the rim of its sticking disc"
            )
        if kind == EV_CANNOT:
            return (
                "no co-rotation can hold: mu F_n is below the spring's pull c_s |x_ms| (or the "
                "brake torque over the longest arm, or, with a brake, the least shakedown "
                "demand c_s |x_ms| + N beta_b omega_m / sum |a_i|) on every sticking circle"
            )
        if kind == EV_SHAKEDOWN:
            return (
                f"its slip per {self.step} falls at every {self.step} to an extrapolated limit "
                f"of {self.limit:.3g} m"
            )
        if math.isnan(self.ratio):
            return f"no evidence from its section yet ({self.points} section points){self._sliding}"
        return (
            f"no evidence from its section: contraction {self.ratio:.3g} per step "
            f"(bound {self.ratio_bound:.3g}), newest step {self.distance:.3g} m{self._sliding}"
        )

    @property
    def _sliding(self) -> str:
        """Why a slave sliding as a whole is no sliding state yet ("" if it is not one)."""
        if self.sliding_revs == 0:
            return ""
        return (
            f"; slides as a whole for {self.sliding_revs} revolutions, but its slip per "
            "revolution falls, or its lowest over the newest "
            f"{self.envelope_revs} revolutions is below the lowest of the "
            f"{self.envelope_revs} before (or fewer than {2 * self.envelope_revs} to compare)"
        )


@dataclasses.dataclass(frozen=True)
class RunFacts:
    """What a finished run reports to the label, in the units of the model (s, m)."""

    status: int  # the machine's final state, or the loop's failure (kernel/status.py)
    t_end: float
    stuck_for: float  # uninterrupted whole-body sticking at t_end [s]
    hold: float  # sticking time that decides `stick` [s]
    window: tuple[float, float]  # final window [s]
    frac_all: float  # window fraction with every contact sticking (decides the outcome)
    frac_any: float  # window fraction with some contact sticking (reported only)
    converge_mode: bool
    max_steps: int
    max_events: int
    stick_rule: str = "contacts"  # numerics.stick_rule
    revs: Revolutions | None = None
    evidence: Evidence | None = None
    steps: int = 1  # accepted integrator steps
    # the revolution log, oldest first (kernel/records.py REVOLUTION rows), for the bound
    revolution_log: np.ndarray | None = None
    floor: float = math.nan  # the bound's reserve against the least demand of any circle [1]
    radius_end: float = math.nan  # |r| at t_end [m]
    cycle_converged: bool = False  # the converge test's section points agreed
    cycle_size: float = math.nan  # radius of the last sticking segment [m]
    cycle_excess: float = math.nan  # excess of the last sliding phase over its onset [m]
    # the motion's own section, oldest first (kernel/records.py OWN_STEP rows; None for an
    # integrator without it) and what reading it needs (verdict/motion_evidence.py)
    own_rows: np.ndarray | None = None
    own_scene: OwnScene | None = None
