"""A scan campaign's results.nc (each point's outcome, reason and measures) and runs.nc,
from its results snapshot (results.py). A point not run yet (partial results) has an
empty outcome and the pending reason."""

from __future__ import annotations

import numpy as np
import xarray as xr

from frictiondisk.store import cf
from frictiondisk.store.campaign_datasets import (
    campaign_attrs,
    coords,
    dim_names,
    request_runs_dataset,
)
from frictiondisk.store.measures import RUN_MEASURES, measure_columns
from frictiondisk.store.partial import PENDING_REASON
from frictiondisk.tasks.jump_search.runs import RunRequest
from frictiondisk.verdict.outcomes import OUTCOMES

PENDING_RUN = {"outcome": "", "reason": PENDING_REASON}
# CF attributes of this task's own variables (frictiondisk.store.cf.complete)
FLAGS: dict[str, cf.Flag] = {"cycle_converged": ((0, 1), "not_converged converged")}


def results_dataset(snapshot) -> xr.Dataset:
    """results.nc: one row per point, the run's outcome and measures."""
    campaign = snapshot.campaign
    return cf.complete(
        _scan_results(snapshot),
        title=f"frictiondisk scan campaign {campaign.name}: the outcome and measures per point",
        what=f"frictiondisk run: campaign {campaign.name}, task scan, rebuilt from its journal",
        flags=FLAGS,
    )


def _scan_results(snapshot) -> xr.Dataset:
    campaign = snapshot.campaign
    shape = campaign.shape
    dims = tuple(dim_names(campaign)[k] for k in campaign.dims)
    results = [PENDING_RUN if r is None else r for r in snapshot.results]
    data_vars = {
        "outcome": (
            dims,
            np.asarray([r["outcome"] for r in results], dtype=str).reshape(shape),
            {"long_name": "one of " + ", ".join(OUTCOMES)},
        ),
        "reason": (
            dims,
            np.asarray([r.get("reason", "") for r in results], dtype=str).reshape(shape),
            {"long_name": "why this outcome"},
        ),
        "cycle_converged": (
            dims,
            np.asarray([bool(r.get("cycle_converged")) for r in results], np.int8).reshape(shape),
            {"long_name": "1 if the limit cycle converged"},
        ),
    }
    measures = measure_columns(results)
    for name, (units, long_name) in RUN_MEASURES.items():
        values = measures[name].reshape(shape)
        data_vars[name] = (dims, values, {"units": units, "long_name": long_name})
    return xr.Dataset(data_vars, coords=coords(campaign), attrs=campaign_attrs(campaign))


def runs_dataset(snapshot, key_of) -> xr.Dataset:
    """runs.nc: the run of every point, in point order."""
    rows = [
        (i, RunRequest(point.config.params.mu), snapshot.results[i], "scan")
        for i, point in enumerate(snapshot.points)
    ]
    return request_runs_dataset(snapshot.campaign, snapshot.points, rows, key_of)
