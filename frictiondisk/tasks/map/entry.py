"""The `map` task's plug-in (registry.py lists it)."""

from __future__ import annotations

from typing import Any

from frictiondisk.tasks.entry import TaskEntry
from frictiondisk.tasks.map.spec import MotionMap


class MapEntry(TaskEntry):
    spec = MotionMap
    summary = "the motion of every cell of a plane of one or two scene keys"
    boundary_tasks = ("trace", "find_jump")  # any results with a mu_star

    def size(self, task: MotionMap) -> tuple[int, str]:
        """Every cell is a point (at most; the refinement runs fewer) of runs_per_cell runs."""
        keys = [f"map.over.{dim}" for dim in task.over]
        return task.runs_per_cell, ", ".join(keys + (["map.samples"] if task.sampled else []))

    def planner(self, campaign: Any) -> Any:
        from frictiondisk.tasks.map.planner import MapPlanner

        return MapPlanner(campaign)

    def figure(self, results, runs=None, *, show_runs=False, boundary=(), files=None):
        from frictiondisk.tasks.map.figure import plot_map

        return plot_map(results, tuple(boundary))

    def run_lines(self, results) -> list[str]:
        from frictiondisk.tasks.map.table import summary_lines

        return summary_lines(results.load())

    def status_lines(self, results, complete: bool) -> list[str]:
        return self.run_lines(results)
