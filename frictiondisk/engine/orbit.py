"""The `trajectory` task: one recorded run of a campaign's base scene (paper Figs 4-5).

A single run needs neither Dask nor a journal: run on its own, it is simulated in the
driver process; run with other campaigns (`run A.yaml B.yaml`), it is one job on their
workers (TrajectoryPlanner). Its trajectory (DIR/trajectory.nc) and summary (DIR/results.nc,
the same measures as a scan point) are written atomically. Running it again recomputes it
only if either file is missing or damaged.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.engine.tasks import run_recorded
from frictiondisk.simulation.simulate import simulate
from frictiondisk.store import cf
from frictiondisk.store.datasets import campaign_attrs
from frictiondisk.store.files import atomic_write_netcdf, netcdf_is_valid
from frictiondisk.store.measures import RUN_MEASURES
from frictiondisk.store.trajectory import write_trajectory

TRAJECTORY_FILE = "trajectory.nc"


def summary_dataset(campaign, summary: dict[str, Any]) -> xr.Dataset:
    """results.nc of a trajectory campaign: the run's outcome, reason and measures as
    scalars (units and long names as in runs.nc), the campaign and how to show it."""
    data = {
        "outcome": xr.Variable((), str(summary["outcome"]), {"long_name": "outcome of the run"}),
        "reason": xr.Variable((), str(summary["reason"]), {"long_name": "why this outcome"}),
    }
    for name, (units, long_name) in RUN_MEASURES.items():
        value = summary.get(name)
        data[name] = xr.Variable(
            (), np.nan if value is None else float(value), {"units": units, "long_name": long_name}
        )
    attrs = {
        **campaign_attrs(campaign),
        "show": campaign.task.show,
        "dt_out": campaign.task.dt_out,
        "mu": campaign.base.params.mu,
    }
    return cf.complete(
        xr.Dataset(data, attrs=attrs),
        title=f"frictiondisk trajectory campaign {campaign.name}: the run's outcome and measures",
        what=f"frictiondisk run: campaign {campaign.name}, task trajectory",
    )


def outputs_valid(out_dir: Path, results_file: str) -> bool:
    """Whether trajectory.nc and results.nc are both there and readable (then the run
    is not made again)."""
    return netcdf_is_valid(out_dir / results_file) and netcdf_is_valid(out_dir / TRAJECTORY_FILE)


def write_outputs(campaign, out_dir: Path, result, results_file: str) -> None:
    """Write the recorded run `result` as trajectory.nc and its summary as results.nc."""
    write_trajectory(out_dir / TRAJECTORY_FILE, result, campaign.base)
    atomic_write_netcdf(summary_dataset(campaign, result.summary()), out_dir / results_file)


def run_trajectory(campaign, out_dir: Path, results_file: str) -> dict:
    """Simulate the base scene with recording on and write trajectory.nc and results.nc,
    unless both are already there and readable.

    Returns {"computed": 0 or 1, "results", "trajectory"} (the two paths)."""
    computed = 0
    if not outputs_valid(out_dir, results_file):
        result = simulate(campaign.base, record=True, dt_out=campaign.task.dt_out)
        write_outputs(campaign, out_dir, result, results_file)
        computed = 1
    return {
        "computed": computed,
        "results": out_dir / results_file,
        "trajectory": out_dir / TRAJECTORY_FILE,
    }


@dataclasses.dataclass(frozen=True)
class FailedRecording:
    """The place of a recorded run whose job never came back (reads like a failed point)."""

    reason: str
    status: str = "failed"


class TrajectoryPlanner:
    """A trajectory campaign among others in one loop (runner.run_campaigns): its one
    recorded run is one job on the workers, beside the other campaigns' runs. The same
    planner contract as engine/plan.py, with nothing for the journal: its files are its
    record (written by the driver when it is done)."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.points = [campaign.base]
        self.results: dict[int, Any] = {}
        self.result = None  # the SimulationResult made now, if any
        self._out = False

    def already_written(self) -> None:
        """Its files are there from an earlier run: nothing to do."""
        self.results[0] = "written"

    @property
    def done(self) -> bool:
        return bool(self.results)

    def requests(self) -> list:
        return []

    def jobs(self, campaign_dir: str, sizing=None) -> list[tuple[int, Any, tuple]]:
        if self.done or self._out or (sizing is not None and sizing.max_jobs == 0):
            return []
        self._out = True
        task = self.campaign.task
        return [(0, run_recorded, (self.campaign.base.canonical(), task.dt_out))]

    def complete(self, job: int, value) -> list:
        self.result = self.results[0] = value
        return []

    def fail(self, job: int, reason: str) -> None:
        self.results[0] = FailedRecording(reason)
