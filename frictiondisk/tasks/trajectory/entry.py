"""The `trajectory` task's plug-in (registry.py lists it)."""

from __future__ import annotations

from typing import Any

from frictiondisk.store.layout import TRAJECTORY_FILE
from frictiondisk.tasks.entry import TaskEntry
from frictiondisk.tasks.trajectory.spec import Trajectory


class TrajectoryEntry(TaskEntry):
    spec = Trajectory
    summary = "one recorded run of the base scene"
    journaled = False  # its files are its record
    runs_alone = True  # one run: no Dask when it runs alone
    figure_files = (TRAJECTORY_FILE,)  # the orbit

    def planner(self, campaign: Any) -> Any:
        from frictiondisk.tasks.trajectory.planner import TrajectoryPlanner

        return TrajectoryPlanner(campaign)

    def files_current(self, out_dir: Any) -> bool:
        from frictiondisk.tasks.trajectory.files import outputs_valid

        return outputs_valid(out_dir)

    def run_alone(self, campaign: Any, out_dir: Any) -> tuple[int, Any]:
        from frictiondisk.tasks.trajectory.files import run_trajectory

        return run_trajectory(campaign, out_dir), out_dir / TRAJECTORY_FILE

    def figure(self, results, runs=None, *, show_runs=False, boundary=(), files=None):
        from frictiondisk.tasks.trajectory.figure import plot_trajectory

        return plot_trajectory(results, files[TRAJECTORY_FILE])
