"""What a bisection is asked to do, fixed for its whole search: a frozen record. Pure Python.

`BisectionSettings` holds every rule of one bisection that does not change while it runs
(tol, limits, retries, direction, parts per round, certification level, root finder, how
it reaches past a missed prediction, the two sides of its boundary, the reserve's learned
offset, the narrowest bracket its numerics resolve). The searches built on a bisection
(certify.py, trace) keep one record and derive the next search's from it
(`dataclasses.replace`) instead of copying the bisection's constructor.

A bracket is never split below `floor(mu)`: `resolution` (what the point's numerics can tell
apart, 0 where unknown) or `FLOOR_ULPS` floating-point steps of mu, whichever is wider. A
tol below it cannot be reached: the search ends `failed` there, with that reason
(bisection.py).
"""

from __future__ import annotations

import dataclasses
import math

from frictiondisk.model.search_settings import ROOT_FINDERS
from frictiondisk.tasks.jump_search.expanding import PLAIN, Expanding
from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK, Between

FLOOR_ULPS = 8  # floating-point steps of mu below which a bracket is not split again


@dataclasses.dataclass(frozen=True)
class BisectionSettings:
    """The fixed rules of one bisection (module docstring)."""

    tol: float  # [mu] converged at mu_hi - mu_lo <= tol
    limits: tuple[float, float]  # [mu] a bracket may be widened within these
    max_retries: int  # retries of an undetermined run, each with a longer horizon
    rising: bool = True  # not stick at mu_lo, stick at mu_hi (False: the other way round)
    split: int = 2  # parts per round: 2 = plain bisection
    strict: int = 0  # certification level of every run this bisection asks for
    root_finder: str = "itp"  # model.search_settings.ROOT_FINDERS
    expanding: Expanding = PLAIN  # how it reaches past a missed prediction (plain only)
    between: Between = NOT_STICK_STICK  # the two sides of the boundary (sides.py)
    reserve_offset: float = 0.0  # the reserve at the jump per unit mu (reserve_offset.py)
    resolution: float = 0.0  # [mu] the narrowest bracket the numerics resolve (0: unknown)
    watch: float = 0.0  # [s] every run watches this long (a re-search after a flip: certify.py)

    def __post_init__(self):
        if not (self.tol > 0 and math.isfinite(self.tol)):
            raise ValueError(f"tol must be a finite number > 0, got {self.tol}")
        if not (self.resolution >= 0 and math.isfinite(self.resolution)):
            raise ValueError(f"resolution must be a finite number >= 0, got {self.resolution}")
        if self.split < 2:
            raise ValueError(f"split must be >= 2 (parts per round), got {self.split}")
        if self.root_finder not in ROOT_FINDERS:
            raise ValueError(f"root_finder must be one of {ROOT_FINDERS}, got {self.root_finder!r}")
        if self.split != 2:  # multisection keeps its fixed schedule
            object.__setattr__(self, "expanding", PLAIN)

    @property
    def plain(self) -> bool:
        """Two parts a round (bisection, not multisection): undecided mu may be straddled."""
        return self.split == 2

    @property
    def interpolates(self) -> bool:
        """Each round's point is the friction reserve's root estimate (ITP)."""
        return self.split == 2 and self.root_finder == "itp"

    def corrected(self, mu: float, reserve) -> float | None:
        """A run's friction reserve less the learned offset x mu (its zero at the jump),
        or None where the reserve is absent, not finite, or guides no search here."""
        if not self.between.uses_reserve or reserve is None or not math.isfinite(reserve):
            return None
        return float(reserve) - self.reserve_offset * mu

    def floor(self, mu: float) -> float:
        """[mu] the narrowest bracket at `mu` that is split again (module docstring)."""
        return max(self.resolution, FLOOR_ULPS * math.ulp(abs(mu)))
