"""A cell's runs: the request for run j of a cell and the runs a finished cell holds.

The outcome names are data: `outcome_order` lists frictiondisk.verdict.outcomes.OUTCOMES,
then any other name a run reported, so an outcome the verdict adds plugs in unchanged."""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.verdict.outcomes import OUTCOMES


@dataclasses.dataclass(frozen=True)
class SampleRequest:
    """Run `index` of a point (sample j of a basin point; 0, the one run of a map cell
    from the scene's own start)."""

    index: int


@dataclasses.dataclass(frozen=True)
class SampledRuns:
    """The runs of one point (a basin point, a map cell), in sample order, and its state."""

    status: str  # "converged" (every run came back) or "failed" (a job never came back)
    reason: str
    results: tuple[dict[str, Any], ...]

    @property
    def n(self) -> int:
        return len(self.results)

    def count(self, outcome: str) -> int:
        return sum(1 for r in self.results if r["outcome"] == outcome)


def outcome_order(seen) -> tuple[str, ...]:
    """OUTCOMES, then any other outcome in `seen` (sorted): nothing is dropped."""
    return (*OUTCOMES, *sorted(set(seen) - set(OUTCOMES)))


def reported_outcomes(results) -> set[str]:
    """Every outcome a run of `results` (SampledRuns or None, per point) reported."""
    return {r["outcome"] for res in results if res is not None for r in res.results}
