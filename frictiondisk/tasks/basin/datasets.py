"""A basin campaign's results as xarray Datasets: results.nc (fractions) and runs.nc, from
its results snapshot (results.py).

results.nc of a sampled basin: over the varied dims and the coordinate `outcome`
(frictiondisk.verdict.outcomes.OUTCOMES, plus any other outcome a run reported), `fraction`,
`fraction_se`, `fraction_lo`, `fraction_hi` (95 % Wilson interval); per point `n_samples`,
the not-stick ("large limit cycle") fraction `not_stick_fraction` with its `_se`, `_lo`,
`_hi`, `status` and `reason` (why sampling stopped). results.nc of a map: the `outcome` of
every cell with its reason and measures (like a scan), and over `outcome` the fraction of
cells. runs.nc: every run with its point, sample index and initial state. No timing in
results.nc: the same campaign gives identical files whatever the worker count.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.store import cf
from frictiondisk.store.campaign_datasets import campaign_attrs, coords, dim_names
from frictiondisk.store.measures import RUN_MEASURES, measure_columns
from frictiondisk.store.partial import PENDING, PENDING_REASON
from frictiondisk.tasks.basin import stats as basin_stats
from frictiondisk.tasks.basin.sampling import BasinPointResult, not_stick_outcomes
from frictiondisk.tasks.sampling.columns import sample_yaml, sampled_run_columns
from frictiondisk.tasks.sampling.runs import outcome_order, reported_outcomes

NOT_STICK_TEXT = "every determined outcome but stick"
DIMENSIONLESS = ("sample", "n_samples")  # CF: this task's counters (store.cf.complete)
# a point not finished yet (partial results): no samples
PENDING_POINT = BasinPointResult(status=PENDING, reason=PENDING_REASON, results=())


def _results(snapshot) -> list[BasinPointResult]:
    """Every point's result, PENDING_POINT for one not finished."""
    return [PENDING_POINT if r is None else r for r in snapshot.results]


def outcome_list(snapshot) -> tuple[str, ...]:
    """OUTCOMES, then any other outcome a run reported (sorted): nothing is dropped."""
    return outcome_order(reported_outcomes(snapshot.results))


def _basin_attrs(campaign, outcomes: tuple[str, ...]) -> dict[str, Any]:
    task = campaign.task
    attrs = {**campaign_attrs(campaign), "basin_mode": "map" if task.is_map else "sample"}
    if task.is_map:
        return attrs | {"mu": campaign.base.params.mu}  # the map's (fixed) friction coefficient
    large = ", ".join(not_stick_outcomes(outcomes))
    attrs |= {
        "seed": task.seed,
        "sample_yaml": sample_yaml(task),
        "confidence": basin_stats.CONFIDENCE,
        "interval": "Wilson score interval (scipy.stats.binomtest, method wilson)",
        "large_cycle": f"not stick = {NOT_STICK_TEXT} ({large}); undetermined counts in neither",
    }
    if task.target_se is not None:
        attrs |= {"target_se": task.target_se, "max_samples": task.max_samples}
        attrs["batch"] = task.batch
    else:
        attrs["samples"] = task.samples
    return attrs


def results_dataset(snapshot) -> xr.Dataset:
    """results.nc of a basin campaign (CF-1.10): fractions per point, or the outcome map."""
    campaign = snapshot.campaign
    outcomes = outcome_list(snapshot)
    build = _map_results if campaign.task.is_map else _fraction_results
    what = "the outcome of each initial state" if campaign.task.is_map else "outcome fractions"
    return cf.complete(
        build(campaign, _results(snapshot), outcomes),
        title=f"frictiondisk basin campaign {campaign.name}: {what}",
        what=f"frictiondisk run: campaign {campaign.name}, task basin, rebuilt from its journal",
        dimensionless=DIMENSIONLESS,
    )


def _fraction_results(campaign, results, outcomes: tuple[str, ...]) -> xr.Dataset:
    shape = campaign.shape
    dims = tuple(dim_names(campaign)[k] for k in campaign.dims)
    n_points = len(results)
    stats = {name: np.full((n_points, len(outcomes)), np.nan) for name in ("p", "se", "lo", "hi")}
    large = {name: np.full(n_points, np.nan) for name in ("p", "se", "lo", "hi")}
    n = np.zeros(n_points, np.int64)
    for i, res in enumerate(results):
        n[i] = res.n
        for k, outcome in enumerate(outcomes):
            _fill(stats, (i, k), res.count(outcome), res.n)
        _fill(large, i, res.not_stick, res.n)
    odims = (*dims, "outcome")

    def shaped(values):
        return values.reshape((*shape, *values.shape[1:]))

    def attrs(long_name):
        return {"units": "1", "long_name": long_name}

    level = f"{basin_stats.CONFIDENCE:.0%}"
    data_vars = {
        "fraction": (odims, shaped(stats["p"]), attrs("fraction of samples with this outcome")),
        "fraction_se": (odims, shaped(stats["se"]), attrs("binomial standard error of fraction")),
        "fraction_lo": (odims, shaped(stats["lo"]), attrs(f"{level} Wilson interval, low")),
        "fraction_hi": (odims, shaped(stats["hi"]), attrs(f"{level} Wilson interval, high")),
        "n_samples": (dims, shaped(n), {"long_name": "samples drawn at this point"}),
        "not_stick_fraction": (
            dims,
            shaped(large["p"]),
            attrs(f"fraction on the large limit cycle: not stick ({NOT_STICK_TEXT})"),
        ),
        "not_stick_se": (dims, shaped(large["se"]), attrs("standard error of not_stick_fraction")),
        "not_stick_lo": (dims, shaped(large["lo"]), attrs(f"{level} Wilson interval, low")),
        "not_stick_hi": (dims, shaped(large["hi"]), attrs(f"{level} Wilson interval, high")),
        "status": (dims, _strings(results, "status", shape), {"long_name": "converged or failed"}),
        "reason": (dims, _strings(results, "reason", shape), {"long_name": "why sampling stopped"}),
    }
    grid = {**coords(campaign), "outcome": ("outcome", np.asarray(outcomes, dtype=str))}
    return xr.Dataset(data_vars, coords=grid, attrs=_basin_attrs(campaign, outcomes))


def _fill(arrays: dict[str, np.ndarray], where, k: int, n: int) -> None:
    arrays["p"][where] = basin_stats.fraction(k, n)
    arrays["se"][where] = basin_stats.standard_error(k, n)
    arrays["lo"][where], arrays["hi"][where] = basin_stats.wilson_interval(k, n)


def _strings(results, name: str, shape) -> np.ndarray:
    return np.asarray([getattr(res, name) for res in results], dtype=str).reshape(shape)


def _map_results(campaign, results, outcomes: tuple[str, ...]) -> xr.Dataset:
    shape = campaign.shape
    dims = tuple(dim_names(campaign)[k] for k in campaign.dims)
    # a point still pending (partial results) has no run yet: its cell stays empty
    runs = [(res.results or ({"outcome": "", "reason": res.reason},))[0] for res in results]
    cells = np.asarray([r["outcome"] for r in runs], dtype=str)
    data_vars: dict[str, Any] = {
        "outcome_map": (
            dims,
            cells.reshape(shape),
            {"long_name": f"outcome of the run from this initial state: {', '.join(outcomes)}"},
        ),
        "reason": (
            dims,
            np.asarray([r.get("reason", "") for r in runs], dtype=str).reshape(shape),
            {"long_name": "why this outcome"},
        ),
        "fraction": (
            ("outcome",),
            np.asarray([np.mean(cells == o) for o in outcomes]),
            {"units": "1", "long_name": "fraction of grid cells with this outcome"},
        ),
        "n_samples": ((), np.int64(cells.size), {"long_name": "grid cells (one run each)"}),
    }
    measures = measure_columns(runs)
    for name, (units, long_name) in RUN_MEASURES.items():
        values = measures[name].reshape(shape)
        data_vars[name] = (dims, values, {"units": units, "long_name": long_name})
    grid = {**coords(campaign), "outcome": ("outcome", np.asarray(outcomes, dtype=str))}
    return xr.Dataset(data_vars, coords=grid, attrs=_basin_attrs(campaign, outcomes))


def runs_dataset(snapshot, key_of) -> xr.Dataset:
    """Every run: point, sample index, initial state, outcome, measures, key, wall time
    (CF-1.10)."""
    campaign = snapshot.campaign
    return cf.complete(
        _runs(snapshot, key_of),
        title=f"frictiondisk basin campaign {campaign.name}: every sampled run",
        what=f"frictiondisk run: campaign {campaign.name}, task basin, rebuilt from its journal",
        dimensionless=DIMENSIONLESS,
    )


def _runs(snapshot, key_of) -> xr.Dataset:
    campaign, points = snapshot.campaign, snapshot.points
    rows = [
        (i, j, result)
        for i, res in enumerate(snapshot.results)
        for j, result in enumerate(res.results)
    ]
    data_vars = sampled_run_columns(
        campaign,
        points,
        rows,
        key_of,
        "point index",
        "sample index at its point (fixed by seed, point and index)",
    )
    return xr.Dataset(data_vars, attrs=_basin_attrs(campaign, outcome_list(snapshot)))
