"""The `scan` task's plug-in (registry.py lists it)."""

from __future__ import annotations

from typing import Any

from frictiondisk.tasks.entry import TaskEntry
from frictiondisk.tasks.scan.spec import Scan


class ScanEntry(TaskEntry):
    spec = Scan
    summary = "run every point of a grid of mu"

    def size(self, task: Scan) -> tuple[int, str]:
        return 1, ", ".join(("scan.mu", *(f"scan.along.{dim}" for dim in task.along)))

    def planner(self, campaign: Any) -> Any:
        from frictiondisk.tasks.scan.planner import ScanPlanner

        return ScanPlanner(campaign)

    def figure(self, results, runs=None, *, show_runs=False, boundary=(), files=None):
        from frictiondisk.tasks.scan.figure import plot_scan

        return plot_scan(results)

    def run_lines(self, results) -> list[str]:
        from frictiondisk.tasks.scan.table import scan_table

        return scan_table(results)

    def status_lines(self, results, complete: bool) -> list[str]:
        return self.run_lines(results)
