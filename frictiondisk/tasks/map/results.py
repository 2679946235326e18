"""What a map planner has found, as a public snapshot (`MapResults`): each cell's runs (a
MapCellResult, None while not run or not run at all) and the cells inferred from uniform
blocks (cells.py); with the netCDF files it makes (datasets.py)."""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.tasks.results import TaskResults


@dataclasses.dataclass(frozen=True)
class MapResults(TaskResults):
    campaign: Any
    points: tuple[Any, ...]  # the campaign's Points (the cells)
    results: tuple[Any, ...]  # per cell: its MapCellResult, None if not run (yet)
    inferred: dict[int, str]  # cell -> motion of the uniform block it lies in (not run)

    def to_dataset(self):
        """results.nc (cells not known yet marked pending; see datasets.py)."""
        from frictiondisk.tasks.map.datasets import results_dataset

        return results_dataset(self)

    def runs_dataset(self, key_of):
        """runs.nc of a finished campaign; key_of(point, request) is a run's journal key."""
        from frictiondisk.tasks.map.datasets import runs_dataset

        return runs_dataset(self, key_of)
