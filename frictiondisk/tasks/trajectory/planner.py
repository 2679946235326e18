"""Which run a `trajectory` campaign needs: its one recorded run, as one job beside other
campaigns' runs (`run A.yaml B.yaml`); run alone it is simulated in this process instead
(files.run_trajectory). The planner contract of frictiondisk.tasks.protocol, with nothing
for the journal: the files are the record."""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.tasks.jobs import RunRecorded, Sizing
from frictiondisk.tasks.protocol import Planner
from frictiondisk.tasks.trajectory.results import TrajectoryResults


@dataclasses.dataclass(frozen=True)
class FailedRecording:
    """The place of a recorded run whose job never came back (reads like a failed point)."""

    reason: str
    status: str = "failed"


class TrajectoryPlanner(Planner):
    """The one recorded run of a trajectory campaign."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.points = campaign.points()  # one: the base scene
        self.results: dict[int, Any] = {}
        self.result = None  # the SimulationResult made now, if any
        self._out = False

    def already_written(self) -> None:
        """Its files are there from an earlier run: nothing to do."""
        self.results[0] = "written"

    @property
    def done(self) -> bool:
        return bool(self.results)

    def progress(self) -> tuple[int, int]:
        return len(self.results), 1

    def config_for(self, i: int, request) -> Any:
        return self.campaign.base

    def requests(self) -> list:
        return []

    def feed(self, i: int, request, result: dict[str, Any]) -> None:
        """Never called: the planner asks the journal for nothing."""

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[int, RunRecorded]]:
        if self.done or self._out or (sizing is not None and sizing.max_jobs == 0):
            return []
        self._out = True
        return [(0, RunRecorded(self.campaign.base.canonical(), self.campaign.task.dt_out))]

    def complete(self, job: int, value) -> list[tuple[int, None, dict[str, Any]]]:
        """Take the recorded run back; returns it (point 0, no request: nothing to journal)."""
        self.result = self.results[0] = value
        return [(0, None, value.summary())]

    def fail(self, job: int, reason: str) -> None:
        self.results[0] = FailedRecording(reason)

    def snapshot(self) -> TrajectoryResults:
        """The run made now (None: none, its files are current or it failed)."""
        return TrajectoryResults(self.campaign, self.result)
