"""The files of a `trajectory` campaign: its recorded run as DIR/trajectory.nc
(frictiondisk.store.trajectory) and the run's outcome and measures as DIR/results.nc
(`summary_dataset`), written atomically. Running it again recomputes it only if either
file is missing or damaged (`outputs_valid`); run alone it is simulated in this process
(`run_trajectory`, no Dask, no journal)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.simulation.simulate import simulate
from frictiondisk.store import cf
from frictiondisk.store.campaign_datasets import campaign_attrs
from frictiondisk.store.files import atomic_write_netcdf, netcdf_is_valid
from frictiondisk.store.layout import RESULTS_FILE, TRAJECTORY_FILE
from frictiondisk.store.measures import RUN_MEASURES
from frictiondisk.store.trajectory import write_trajectory


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


def outputs_valid(out_dir: Path) -> bool:
    """Whether trajectory.nc and results.nc are both there and readable (then the run
    is not made again)."""
    return netcdf_is_valid(out_dir / RESULTS_FILE) and netcdf_is_valid(out_dir / TRAJECTORY_FILE)


def write_outputs(campaign, out_dir: Path, result) -> None:
    """Write the recorded run `result` as trajectory.nc and its summary as results.nc."""
    write_trajectory(out_dir / TRAJECTORY_FILE, result, campaign.base)
    atomic_write_netcdf(summary_dataset(campaign, result.summary()), out_dir / RESULTS_FILE)


def run_trajectory(campaign, out_dir: Path) -> int:
    """Simulate the base scene with recording on and write trajectory.nc and results.nc,
    unless both are already there and readable. Returns the runs computed (0 or 1)."""
    if outputs_valid(out_dir):
        return 0
    result = simulate(campaign.base, record=True, dt_out=campaign.task.dt_out)
    write_outputs(campaign, out_dir, result)
    return 1
