"""What a trajectory planner has made, as a public snapshot (`TrajectoryResults`): the
recorded run (a SimulationResult, None if nothing was run now); with its files
(files.py: trajectory.nc and results.nc)."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

from frictiondisk.store.layout import RESULTS_FILE, TRAJECTORY_FILE
from frictiondisk.tasks.results import TaskResults


@dataclasses.dataclass(frozen=True)
class TrajectoryResults(TaskResults):
    campaign: Any
    result: Any  # the SimulationResult recorded now; None: nothing new to write

    def to_dataset(self):
        """results.nc: the run's outcome and measures (None without a run made now)."""
        if self.result is None:
            return None
        from frictiondisk.tasks.trajectory.files import summary_dataset

        return summary_dataset(self.campaign, self.result.summary())

    def write(self, out_dir: Path, key_of) -> tuple[Path, Path, int]:
        """Write trajectory.nc and results.nc of the run made now (if any); returns their
        paths and 1, the campaign's one run."""
        if self.result is not None:
            from frictiondisk.tasks.trajectory.files import write_outputs

            write_outputs(self.campaign, out_dir, self.result)
        return out_dir / RESULTS_FILE, out_dir / TRAJECTORY_FILE, 1
