"""The `find_jump` task's plug-in (registry.py lists it)."""

from __future__ import annotations

from typing import Any

from frictiondisk.tasks.entry import TaskEntry
from frictiondisk.tasks.find_jump.spec import FindJump


class FindJumpEntry(TaskEntry):
    spec = FindJump
    summary = "bisect mu to the jump mu* at every point"
    shows_runs = True
    mu_star_grid = True

    def size(self, task: FindJump) -> tuple[int, str]:
        from frictiondisk.tasks.jump_search.bisection import cold_run_count

        fields = ", ".join(f"find_jump.along.{dim}" for dim in task.along)
        per_point = cold_run_count(task.bracket, task.tol)
        if task.prescan is not None:
            per_point += len(task.prescan.mu)
            fields += ", find_jump.prescan.mu"
        return per_point, fields + ", find_jump.tol"

    def planner(self, campaign: Any) -> Any:
        from frictiondisk.tasks.find_jump.planner import JumpPlanner

        return JumpPlanner(campaign)

    def figure(self, results, runs=None, *, show_runs=False, boundary=(), files=None):
        from frictiondisk.tasks.find_jump.figure import plot_find_jump

        return plot_find_jump(results, runs, show_runs=show_runs)

    def run_lines(self, results) -> list[str]:
        from frictiondisk.tasks.find_jump.table import table_lines

        return table_lines(results)

    def status_lines(self, results, complete: bool) -> list[str]:
        return self.run_lines(results)
