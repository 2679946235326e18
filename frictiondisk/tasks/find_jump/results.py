"""What a find_jump planner has found, as a public snapshot (`FindJumpResults`): each
point's result (a BisectionResult, a JumpSearchResult with a prescan, or None while it is
not finished), which points started warm, and the runs the warm starts saved; with the
netCDF files it makes (datasets.py)."""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.tasks.results import TaskResults


@dataclasses.dataclass(frozen=True)
class FindJumpResults(TaskResults):
    campaign: Any
    points: tuple[Any, ...]  # the campaign's Points
    results: tuple[Any, ...]  # per point: its result, None while not finished
    warm: tuple[bool, ...]  # per point: its bracket was predicted (a warm start)
    runs_saved: int  # search runs the warm starts saved (JumpPlanner.runs_saved)

    def to_dataset(self):
        """results.nc (pending points marked; see datasets.py)."""
        from frictiondisk.tasks.find_jump.datasets import results_dataset

        return results_dataset(self)

    def runs_dataset(self, key_of):
        """runs.nc of a finished campaign; key_of(point, request) is a run's journal key."""
        from frictiondisk.tasks.find_jump.datasets import runs_dataset

        return runs_dataset(self, key_of)
