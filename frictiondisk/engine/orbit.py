"""The `trajectory` task: one recorded run of a campaign's base scene (paper Figs 4-5).

A single run needs neither Dask nor a journal: it is simulated in the driver, and its
trajectory (DIR/trajectory.nc) and summary (DIR/results.nc, the same measures as a scan
point) are written atomically. Running it again recomputes it only if either file is
missing or damaged.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

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


def run_trajectory(campaign, out_dir: Path, results_file: str) -> dict:
    """Simulate the base scene with recording on and write trajectory.nc and results.nc,
    unless both are already there and readable.

    Returns {"computed": 0 or 1, "results", "trajectory"} (the two paths)."""
    results = out_dir / results_file
    trajectory = out_dir / TRAJECTORY_FILE
    computed = 0
    if not (netcdf_is_valid(results) and netcdf_is_valid(trajectory)):
        config = campaign.base
        result = simulate(config, record=True, dt_out=campaign.task.dt_out)
        write_trajectory(trajectory, result, config)
        atomic_write_netcdf(summary_dataset(campaign, result.summary()), results)
        computed = 1
    return {"computed": computed, "results": results, "trajectory": trajectory}
