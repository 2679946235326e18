"""What a scan planner has found, as a public snapshot (`ScanResults`): each point's run
summary (None while not run); with the netCDF files it makes (datasets.py)."""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.tasks.results import TaskResults


@dataclasses.dataclass(frozen=True)
class ScanResults(TaskResults):
    campaign: Any
    points: tuple[Any, ...]  # the campaign's Points
    results: tuple[dict[str, Any] | None, ...]  # per point: its run's summary

    def to_dataset(self):
        """results.nc (pending points marked; see datasets.py)."""
        from frictiondisk.tasks.scan.datasets import results_dataset

        return results_dataset(self)

    def runs_dataset(self, key_of):
        """runs.nc of a finished campaign; key_of(point, request) is a run's journal key."""
        from frictiondisk.tasks.scan.datasets import runs_dataset

        return runs_dataset(self, key_of)
