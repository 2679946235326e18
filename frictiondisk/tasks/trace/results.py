"""What a trace planner has found, as a public snapshot (`TraceResults`): the tracer's
result (final, or what is known so far: its curves, folds and first look); with the netCDF
files it makes (datasets.py)."""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.tasks.results import TaskResults


@dataclasses.dataclass(frozen=True)
class TraceResults(TaskResults):
    campaign: Any
    points: tuple[Any, ...]  # the campaign's one Point: its base scene
    trace: Any  # the tracer's TraceResult (status "pending" while it runs)

    def to_dataset(self):
        """results.nc (curves and folds; see datasets.py)."""
        from frictiondisk.tasks.trace.datasets import results_dataset

        return results_dataset(self)

    def runs_dataset(self, key_of):
        """runs.nc of a finished trace; key_of(point, request) is a run's journal key."""
        from frictiondisk.tasks.trace.datasets import runs_dataset

        return runs_dataset(self, key_of)
