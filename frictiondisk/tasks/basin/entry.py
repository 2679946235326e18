"""The `basin` task's plug-in (registry.py lists it)."""

from __future__ import annotations

from typing import Any

from frictiondisk.tasks.basin.spec import Basin
from frictiondisk.tasks.entry import TaskEntry
from frictiondisk.tasks.sampling.distribution import Distribution


class BasinEntry(TaskEntry):
    spec = Basin
    summary = "basin stability or a basin map"
    boundary_tasks = ("find_jump",)

    def size(self, task: Basin) -> tuple[int, str]:
        """Every grid cell of a map is a point; a sampled point takes up to sample_limit runs."""
        keys = [f"basin.grid.{dim}" for dim in task.grid] or [
            f"basin.along.{dim}" for dim in task.along
        ]
        return task.sample_limit, ", ".join(
            keys + ([] if task.is_map else ["basin.samples / max_samples"])
        )

    reference_tables = (
        ("A sampled initial-state key (`basin.sample.<key>`)", "Exactly one of:", Distribution),
    )

    def planner(self, campaign: Any) -> Any:
        from frictiondisk.tasks.basin.planner import BasinPlanner

        return BasinPlanner(campaign)

    def figure(self, results, runs=None, *, show_runs=False, boundary=(), files=None):
        from frictiondisk.tasks.basin.figure import plot_basin

        if len(boundary) > 1:
            raise ValueError("boundary: a basin map draws one find_jump contour")
        return plot_basin(results, boundary[0] if boundary else None)

    def run_lines(self, results) -> list[str]:
        from frictiondisk.tasks.basin.table import summary_lines

        return summary_lines(results.load())

    def status_lines(self, results, complete: bool) -> list[str]:
        """A stopped or running campaign's fractions so far (a complete one: none)."""
        return [] if complete else self.run_lines(results)
