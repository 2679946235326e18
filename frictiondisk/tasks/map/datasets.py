"""A map campaign's results as xarray Datasets: results.nc (the motion of every cell) and
runs.nc, from its results snapshot (results.py).

results.nc, over the map's one or two keys (coordinates with units) and `outcome` (every
outcome name, frictiondisk.tasks.sampling.runs.outcome_order): per cell its `motion`, how it
is known (`ran`: 1 run, 0 inferred from a uniform block of the refinement, -1 pending),
`reason`, `n_runs`, `cycle_converged` (-1 where not run or mixed over sampled starts),
`fraction` of its runs per outcome, and every run measure of frictiondisk.store.measures
(a sampled cell: the mean over its runs of its motion); over `outcome` the fraction of
cells with each motion (`cell_fraction`, run and inferred cells alike). runs.nc: every
run with its cell, sample index, initial state, outcome and measures. No timing in
results.nc: the same campaign gives identical files whatever the worker count.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.model.varied import INITIAL_STATE_KEYS
from frictiondisk.store import cf
from frictiondisk.store.campaign_datasets import campaign_attrs, coords, dim_names
from frictiondisk.store.measures import RUN_MEASURES, num
from frictiondisk.store.partial import PENDING, PENDING_REASON
from frictiondisk.tasks.map.motions import MapCellResult
from frictiondisk.tasks.sampling.columns import sample_yaml, sampled_run_columns
from frictiondisk.tasks.sampling.runs import outcome_order, reported_outcomes

DIMENSIONLESS = ("sample", "n_runs")
RAN: cf.Flag = ((-1, 0, 1), "pending inferred run")
CONVERGED: cf.Flag = ((-1, 0, 1), "unknown no yes")
FLAGS = {"ran": RAN, "cycle_converged": CONVERGED}
INFERRED_REASON = "not run: inside a block whose run cells all show this motion"


def outcome_list(snapshot) -> tuple[str, ...]:
    return outcome_order(reported_outcomes(snapshot.results) | set(snapshot.inferred.values()))


def start_text(campaign) -> str:
    """How every run starts: the scene's initial state (rest where all are 0), or sampled."""
    task = campaign.task
    if task.sampled:
        return f"sampled: {task.samples} starts per cell, seed {task.seed}"
    params = campaign.base.canonical()["params"]
    values = {k: params.get(k.split(".")[-1]) for k in INITIAL_STATE_KEYS}
    given = {k: v for k, v in values.items() if v}
    if not given:
        return "rest: the scene's initial state, every initial-state key 0"
    return "given: " + ", ".join(f"{k.split('.')[-1]} = {v:g}" for k, v in given.items())


def _map_attrs(campaign) -> dict[str, Any]:
    task = campaign.task
    attrs = {
        **campaign_attrs(campaign),
        "start": start_text(campaign),
        "mode": task.mode,
        "strides": ", ".join(str(s) for s in task.strides()),
        "refinement": "coarse lattice at `strides`, blocks split where their run cells "
        "differ in motion (frictiondisk/tasks/map/cells.py); ran = 0: inferred",
    }
    if task.sampled:
        attrs["sample_yaml"] = sample_yaml(task)
    return attrs


def results_dataset(snapshot) -> xr.Dataset:
    """results.nc of a map campaign (CF-1.10)."""
    campaign = snapshot.campaign
    return cf.complete(
        _results(snapshot),
        title=f"frictiondisk map campaign {campaign.name}: the motion of every cell",
        what=f"frictiondisk run: campaign {campaign.name}, task map, rebuilt from its journal",
        flags=FLAGS,
        dimensionless=DIMENSIONLESS,
    )


def _cell(snapshot, i: int) -> tuple[str, int, str, MapCellResult | None]:
    """(motion, ran flag, reason, runs) of cell i."""
    res = snapshot.results[i]
    if res is not None:
        return res.motion, 1, res.reason, res
    if i in snapshot.inferred:
        return snapshot.inferred[i], 0, INFERRED_REASON, None
    return "", -1, PENDING_REASON, None


def _converged(res: MapCellResult | None) -> int:
    if res is None:
        return -1
    flags = {bool(r.get("cycle_converged")) for r in res.results}
    return int(flags.pop()) if len(flags) == 1 else -1


def _measure(res: MapCellResult | None, name: str) -> float:
    """The cell's value of a measure: its run's (a sampled cell: the mean over the runs of
    its motion, NaN where none has it)."""
    if res is None:
        return np.nan
    values = [num(r.get(name)) for r in res.results if r["outcome"] == res.motion]
    finite = [v for v in values if np.isfinite(v)]
    return float(np.mean(finite)) if finite else np.nan


def _results(snapshot) -> xr.Dataset:
    campaign = snapshot.campaign
    shape = campaign.shape
    dims = tuple(dim_names(campaign)[k] for k in campaign.dims)
    outcomes = outcome_list(snapshot)
    cells = [_cell(snapshot, i) for i in range(len(snapshot.points))]
    motions = np.asarray([c[0] for c in cells], dtype=str)
    fraction = np.full((len(cells), len(outcomes)), np.nan)
    for i, (_, _, _, res) in enumerate(cells):
        if res is not None and res.n:
            fraction[i] = [res.count(o) / res.n for o in outcomes]
    known = motions[motions != ""]
    odims = (*dims, "outcome")
    data_vars: dict[str, Any] = {
        "motion": (
            dims,
            motions.reshape(shape),
            {"long_name": f"motion of the cell: one of {', '.join(outcomes)}"},
        ),
        "ran": (dims, np.asarray([c[1] for c in cells], np.int8).reshape(shape), {}),
        "reason": (dims, np.asarray([c[2] for c in cells], dtype=str).reshape(shape), {}),
        "n_runs": (
            dims,
            np.asarray([0 if c[3] is None else c[3].n for c in cells], np.int64).reshape(shape),
            {"long_name": "runs of the cell (0: inferred or pending)"},
        ),
        "cycle_converged": (
            dims,
            np.asarray([_converged(c[3]) for c in cells], np.int8).reshape(shape),
            {"long_name": "the motion settled (every run of the cell)"},
        ),
        "fraction": (
            odims,
            fraction.reshape((*shape, len(outcomes))),
            {"units": "1", "long_name": "fraction of the cell's runs with this outcome"},
        ),
        "cell_fraction": (
            ("outcome",),
            np.asarray([np.mean(known == o) if known.size else np.nan for o in outcomes]),
            {
                "units": "1",
                "long_name": "fraction of known cells (run or inferred) with this motion",
            },
        ),
    }
    for name, (units, long_name) in RUN_MEASURES.items():
        values = np.asarray([_measure(c[3], name) for c in cells]).reshape(shape)
        data_vars[name] = (dims, values, {"units": units, "long_name": long_name})
    grid = {**coords(campaign), "outcome": ("outcome", np.asarray(outcomes, dtype=str))}
    ds = xr.Dataset(data_vars, coords=grid, attrs=_map_attrs(campaign))
    ds["status"] = (dims, np.asarray([_status(c) for c in cells], dtype=str).reshape(shape), {})
    return ds


def _status(cell) -> str:
    motion, ran, _, res = cell
    if ran < 0:
        return PENDING
    return res.status if res is not None else "inferred"


def runs_dataset(snapshot, key_of) -> xr.Dataset:
    """Every run: cell, sample index, initial state, outcome, measures, key, wall time."""
    campaign = snapshot.campaign
    return cf.complete(
        _runs(snapshot, key_of),
        title=f"frictiondisk map campaign {campaign.name}: every run",
        what=f"frictiondisk run: campaign {campaign.name}, task map, rebuilt from its journal",
        dimensionless=DIMENSIONLESS,
    )


def _runs(snapshot, key_of) -> xr.Dataset:
    campaign, points = snapshot.campaign, snapshot.points
    rows = [
        (i, j, result)
        for i, res in enumerate(snapshot.results)
        if res is not None
        for j, result in enumerate(res.results)
    ]
    data_vars = sampled_run_columns(
        campaign,
        points,
        rows,
        key_of,
        "cell index",
        "run index in its cell (a sampled start: fixed by seed, cell, index)",
    )
    return xr.Dataset(data_vars, attrs=_map_attrs(campaign))
