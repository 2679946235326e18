"""The base of every task's results snapshot (`TaskResults`): what a planner has found, as
a public frozen record (`Planner.snapshot()`), with the netCDF files it makes. The shared
machinery (engine/campaign_run.py) writes a campaign's files through it and never reads a
task's fields."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from frictiondisk.store.files import atomic_write_netcdf
from frictiondisk.store.layout import RESULTS_FILE, RUNS_FILE


class TaskResults:
    """A planner's snapshot. Subclasses (frozen dataclasses) hold the results and build the
    Datasets; `write` writes results.nc and runs.nc."""

    def to_dataset(self) -> Any:
        """results.nc as an xarray Dataset (points not finished marked pending); None if
        there is nothing to write."""
        raise NotImplementedError

    def runs_dataset(self, key_of) -> Any:
        """runs.nc of a finished campaign (dim `run`); key_of(point, request) is the
        journal key of a run."""
        raise NotImplementedError

    def write(self, out_dir: Path, key_of) -> tuple[Path, Path, int]:
        """Write the finished campaign's results.nc and runs.nc into out_dir, atomically.
        Returns (results.nc, runs.nc, runs in runs.nc)."""
        results = atomic_write_netcdf(self.to_dataset(), out_dir / RESULTS_FILE)
        runs_ds = self.runs_dataset(key_of)
        runs = atomic_write_netcdf(runs_ds, out_dir / RUNS_FILE)
        return Path(results), Path(runs), int(runs_ds.sizes["run"])
