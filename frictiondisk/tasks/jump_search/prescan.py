"""Which prescan values to run: a coarse grid first, refined where something changes.

A dense prescan runs every value of its grid. `AdaptiveGrid` runs every `stride`-th value
(and the last), then runs a grid value inside an interval between two run values while

* its ends differ in stick / not stick (refined down to neighbouring grid values, so a
  jump gets the same bracket, and so the same bisection and mu*, as in the dense prescan),
* an end is undetermined after every retry, or
* an end's friction reserve (frictiondisk/verdict/reserve.py) contradicts its verdict: a run
  that sticks should have a positive reserve; one that does not, a negative one or none
  (never stuck). A contradiction means the reserve does not describe the verdicts there,
  so it cannot vouch for the interval.

Where the ends differ and their reserves agree with their verdicts, the grid value run
next is the one nearest the reserve's zero (secant, or unit slope from the one finite
reserve: the reserve is mu minus a demand that moves slowly with mu), else the middle.

An interval whose ends agree in verdict and whose reserves agree with those verdicts is
not run inside: the prescan takes it to hold no change. A change the dense prescan sees
is missed only there, as an island narrower than stride grid steps whose ends' reserves
both agree with their verdicts, and only above a headline: the search runs every grid
value below its headline, and the whole grid of a point where the prescan found no change
and nothing sticks (frictiondisk.tasks.jump_search.jumps). Measured against dense prescans
(docs/benchmarks.md): no miss on the figure campaigns and the well-posedness study's
scenes; under `stick_rule: contacts` one, which is why that rule keeps a dense prescan by
default.

Pure Python: grid indices in, grid indices out; the run summaries are fed by the caller.
"""

from __future__ import annotations

import math
from typing import Any

from frictiondisk.tasks.jump_search.bisection import zero_crossing
from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK, Between


def default_stride(
    n_values: int, mode: str, stick_rule: str, between: Between = NOT_STICK_STICK
) -> int:
    """The coarse stride a prescan of n_values gets unless its campaign sets one: about
    sqrt(n), so the coarse grid and one change's refinement stay small together. 1
    (dense) for a `converge` prescan, whose every value is data (size versus mu), for
    `stick_rule: contacts`, whose sticking islands the reserve does not show (a dense
    disk_xms_at_rest line has one that an adaptive prescan misses), for any boundary but
    the stick / not-stick jump (no friction reserve vouches for an interval), and below 6
    values."""
    dense = mode == "converge" or stick_rule == "contacts" or not between.uses_reserve
    if dense or n_values < 6:
        return 1
    return round(math.sqrt(n_values))


def stride_of(prescan, stick_rule: str, between: Between = NOT_STICK_STICK) -> int:
    """The stride a point with this stick rule runs its campaign's `prescan` with: the
    campaign's own, else `default_stride`."""
    if prescan.stride is not None:
        return prescan.stride
    return default_stride(len(prescan.mu), prescan.mode, stick_rule, between)


def needs_a_run_inside(
    a: dict[str, Any], b: dict[str, Any], between: Between = NOT_STICK_STICK
) -> bool:
    """Whether the interval between run summaries `a` and `b` needs a grid value run
    inside: its verdicts differ (a side undecided counts as different), or its ends do not
    explain it (for the stick / not-stick jump: their reserves; for another boundary
    ends on one side are taken to hold no change)."""
    sides = (between.side(a["outcome"]), between.side(b["outcome"]))
    if None in sides or sides[0] != sides[1]:
        return True
    if not between.uses_reserve:
        return False
    return not all(reserve_explains(run, between) for run in (a, b))


def reserve_explains(run: dict[str, Any], between: Between = NOT_STICK_STICK) -> bool:
    """A run whose friction reserve agrees with its verdict: positive if it sticks,
    negative or NaN (never stuck) if not."""
    reserve = _finite(run.get("reserve"))
    if between.is_high(run["outcome"]):
        return reserve is not None and reserve > 0
    return reserve is None or reserve <= 0


def _finite(value: Any) -> float | None:
    return float(value) if value is not None and math.isfinite(value) else None


class AdaptiveGrid:
    """The grid indices to run, grown as run summaries come back (`settle`)."""

    def __init__(self, mus: tuple[float, ...], stride: int, between: Between = NOT_STICK_STICK):
        n_values = len(mus)
        if n_values < 2 or stride < 1:
            raise ValueError(f"need 2 or more values and stride >= 1, got {n_values}, {stride}")
        self.mus = mus  # the grid, increasing
        self.between = between  # the boundary's two sides (sides.py)
        self.wanted: set[int] = set(range(0, n_values, stride)) | {n_values - 1}
        self._runs: dict[int, dict[str, Any]] = {}  # index -> its settled run's summary

    def settle(self, index: int, summary: dict[str, Any]) -> None:
        """Record the final run (last retry level) of grid value `index`."""
        if index not in self.wanted:
            raise ValueError(f"grid value {index} was not asked for")
        self._runs[index] = summary

    @property
    def waiting(self) -> set[int]:
        """Wanted indices without a settled run."""
        return self.wanted - self._runs.keys()

    def refine(self) -> set[int]:
        """Once nothing is waiting: one grid index inside every interval that needs a run
        (added to `wanted`); empty when the prescan is complete."""
        if self.waiting:
            return set()
        ran = sorted(self._runs)
        new = {
            self._split(i, j)
            for i, j in zip(ran, ran[1:], strict=False)
            if j - i >= 2 and needs_a_run_inside(self._runs[i], self._runs[j], self.between)
        }
        self.wanted |= new
        return new

    def _split(self, i: int, j: int) -> int:
        """The grid index to run inside (i, j): nearest the reserve's zero where both ends
        explain their verdicts, else the middle."""
        a, b = self._runs[i], self._runs[j]
        if not self.between.uses_reserve:
            return (i + j) // 2
        if not (reserve_explains(a) and reserve_explains(b)):
            return (i + j) // 2
        zero = _reserve_zero((self.mus[i], a), (self.mus[j], b))
        if zero is None:
            return (i + j) // 2
        return min(range(i + 1, j), key=lambda k: abs(self.mus[k] - zero))


def _reserve_zero(*ends: tuple[float, dict[str, Any]]) -> float | None:
    """mu where the reserve crosses zero: the secant through two finite reserves, or a
    unit slope from the one finite reserve; None without a finite reserve."""
    finite = [(mu, r) for mu, run in ends if (r := _finite(run.get("reserve"))) is not None]
    if len(finite) == 2 and finite[0][1] != finite[1][1]:
        return zero_crossing(*finite[0], *finite[1])
    if finite:
        mu, r = finite[0]
        return mu - r
    return None


# runs per prescan value that the refinement at motion boundaries may spend at one point
MOTION_REFINE_BUDGET = 1.0


def motions_differ(a: str, b: str, between: Between = NOT_STICK_STICK) -> bool:
    """Two outcomes on the low (not-stick) side that name different motions: a boundary
    between them where a sticking window can sit. `slide` (a motion not yet shown) next to
    a shown one counts as different; two runs of one name do not."""
    return between.is_low(a) and between.is_low(b) and a != b


def motion_boundaries(
    decided: dict[float, str],
    top: float,
    width: float,
    between: Between = NOT_STICK_STICK,
    undetermined=(),
) -> list[tuple[float, float]]:
    """The intervals below `top` that still need a run inside before the grid below `top`
    counts as decided, increasing in mu: between neighbouring decided values (mu ->
    outcome) whose motions differ, wider than `width` (the persistence width). Where
    values undetermined after every retry lie between them, the parts beside each such
    value, wider than width / 2: a window wider than `width` that holds an undetermined
    value then holds a decided one too."""
    below = sorted(mu for mu in decided if mu < top)
    open_parts = []
    for a, b in zip(below, below[1:], strict=False):
        if not motions_differ(decided[a], decided[b], between):
            continue
        inside = sorted(u for u in undetermined if a < u < b)
        limit = (0.5 * width if inside else width) * (1 + 1e-9)
        ends = [a, *inside, b]
        open_parts += [(x, y) for x, y in zip(ends, ends[1:], strict=False) if y - x > limit]
    return open_parts


class MotionRefinement:
    """Where two neighbouring decided values below the headline name different motions,
    a run at their middle, round after round, until they lie within the persistence width
    (a sticking window at least that wide sitting on the boundary covers more than half of
    the interval, so a middle lands in it; around a middle left undetermined, half that
    on either side), within a budget of runs per point. Which intervals are refined
    depends on the verdicts only: the lowest first."""

    def __init__(self, n_values: int, width: float, between: Between = NOT_STICK_STICK):
        self.budget = math.ceil(MOTION_REFINE_BUDGET * n_values)
        self.width = width  # [mu] the persistence width: persist x tol
        self.between = between
        self.asked: set[float] = set()  # every mu it asked for

    def wanted(self, decided: dict[float, str], top: float, undetermined=()) -> set[float]:
        """The middles of this round (none already asked for), lowest intervals first, at
        most the budget left. `undetermined`: values undetermined after every retry."""
        parts = motion_boundaries(decided, top, self.width, self.between, undetermined)
        middles = [0.5 * (a + b) for a, b in parts]
        fresh = [mu for mu in middles if mu not in self.asked]
        chosen = set(fresh[: max(0, self.budget - len(self.asked))])
        self.asked |= chosen
        return chosen


def motion_runs(
    scan: dict, checks: dict, prescan: set, between: Between
) -> tuple[dict[float, str], list[float]]:
    """What the refinement between motions reads of a point's runs (`scan`: mu -> its last
    prescan run; `checks`: mu -> its fill, persistence or refinement run): mu -> outcome of
    every decided run with the prescan's numerics (`prescan`: their mu), so that motions are
    compared as one numerics names them; and the mu of every run undetermined after every
    retry."""
    runs = {**scan, **checks}
    outcomes = {
        mu: run.outcome
        for mu, run in runs.items()
        if mu in prescan and between.side(run.outcome) is not None
    }
    undecided = [*scan.values(), *checks.values()]
    return outcomes, [run.request.mu for run in undecided if between.side(run.outcome) is None]
