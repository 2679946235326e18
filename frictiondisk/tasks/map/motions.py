"""A map cell's runs and its motion: the outcome of its one run, or the leading outcome of
its sampled starts. The outcome names are data (`outcome_order` of
frictiondisk.tasks.sampling.runs), so a motion the verdict adds plugs in unchanged."""

from __future__ import annotations

from collections import Counter

from frictiondisk.tasks.sampling.runs import SampledRuns, outcome_order
from frictiondisk.verdict.outcomes import UNDETERMINED


class MapCellResult(SampledRuns):
    """The runs of one cell, in sample order (one from the scene's start)."""

    @property
    def motion(self) -> str:
        return leading_motion(self.results)


def leading_motion(results) -> str:
    """The most frequent decided outcome of `results` (ties: the first in the listing
    order); `undetermined` when no run decided."""
    counts = Counter(r["outcome"] for r in results if r["outcome"] != UNDETERMINED)
    if not counts:
        return UNDETERMINED
    order = {o: k for k, o in enumerate(outcome_order(counts))}
    return max(counts, key=lambda o: (counts[o], -order[o]))
