"""What a basin planner has found, as a public snapshot (`BasinResults`): each point's
samples (a BasinPointResult, None while not finished); with the netCDF files it makes
(datasets.py)."""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.tasks.results import TaskResults


@dataclasses.dataclass(frozen=True)
class BasinResults(TaskResults):
    campaign: Any
    points: tuple[Any, ...]  # the campaign's Points
    results: tuple[Any, ...]  # per point: its BasinPointResult, None while not finished

    def to_dataset(self):
        """results.nc (pending points marked; see datasets.py)."""
        from frictiondisk.tasks.basin.datasets import results_dataset

        return results_dataset(self)

    def runs_dataset(self, key_of):
        """runs.nc of a finished campaign; key_of(point, request) is a run's journal key."""
        from frictiondisk.tasks.basin.datasets import runs_dataset

        return runs_dataset(self, key_of)
