"""Campaign results as xarray Datasets: results.nc (one row per point) and runs.nc.

results.nc holds no timing, so the same campaign gives identical files whatever the
worker count; wall times are in runs.nc.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from frictiondisk import __version__
from frictiondisk.campaign.journal import kernel_version
from frictiondisk.config import describe_key
from frictiondisk.yamlio import dump_yaml

RUN_MEASURES = {  # summary field -> (units, long name)
    "R1": ("m", "first sticking radius |r|"),
    "t_R1": ("s", "time of first sticking"),
    "size": ("m", "radius of the sticking circle or of the cycle's sticking segment"),
    "a": ("m", "largest excess |r| - R_stick while sliding on the cycle"),
    "n_transitions": ("1", "stick/slide switches, all contacts"),
    "stick_fraction": ("1", "fraction of the final window with every contact sticking"),
    "t_end": ("s", "simulated time reached"),
    "n_steps": ("1", "accepted integrator steps"),
    "n_refused": ("1", "refused slide->stick entries"),
}


def dim_names(campaign) -> dict[str, str]:
    """Dimension name of each varied scene key: its last part, unless two would clash."""
    short = {key: key.split(".")[-1] for key in campaign.dims}
    if len(set(short.values())) < len(short):
        return {key: key.replace(".", "_") for key in campaign.dims}
    return short


def _key_attrs(key: str) -> dict[str, str]:
    """units, long_name and scene_key of a varied scene key."""
    unit, description = describe_key(key)
    attrs = {"long_name": description, "scene_key": key}
    if unit:
        attrs["units"] = unit
    return attrs


def _coords(campaign) -> dict[str, Any]:
    names = dim_names(campaign)
    return {
        names[key]: (names[key], np.asarray(campaign.coords[key], dtype=float), _key_attrs(key))
        for key in campaign.dims
    }


def _attrs(campaign) -> dict[str, Any]:
    return {
        "campaign_name": campaign.name,
        "task": campaign.task.kind,
        "campaign_yaml": campaign.text,
        "numerics_yaml": dump_yaml(campaign.base.canonical()["numerics"]),
        "frictiondisk_version": __version__,
        "kernel_version": kernel_version(),
    }


def _num(value) -> float:
    return math.nan if value is None else float(value)


def results_dataset(campaign, planner) -> xr.Dataset:
    if campaign.task.kind == "find_jump":
        return _jump_results(campaign, planner)
    return _scan_results(campaign, planner)


def _jump_results(campaign, planner) -> xr.Dataset:
    shape = campaign.shape
    dims = tuple(dim_names(campaign)[k] for k in campaign.dims)
    n = len(planner.points)
    cols: dict[str, list] = {
        k: []
        for k in (
            "mu_lo",
            "mu_hi",
            "outcome_lo",
            "outcome_hi",
            "size_lo",
            "size_hi",
            "R1_hi",
            "n_runs",
            "status",
            "reason",
            "monotone",
            "warm_start",
        )
    }
    for i in range(n):
        res = planner.results[i]
        lo, hi = res.end_result("lo") or {}, res.end_result("hi") or {}
        cols["mu_lo"].append(res.mu_lo)
        cols["mu_hi"].append(res.mu_hi)
        cols["outcome_lo"].append(lo.get("outcome", ""))
        cols["outcome_hi"].append(hi.get("outcome", ""))
        cols["size_lo"].append(_num(lo.get("size")))
        cols["size_hi"].append(_num(hi.get("size")))
        cols["R1_hi"].append(_num(hi.get("R1")))
        cols["n_runs"].append(len(res.runs))
        cols["status"].append(res.status)
        cols["reason"].append(res.reason)
        cols["monotone"].append(np.int8(res.monotone))
        cols["warm_start"].append(np.int8(planner.warm.get(i, False)))

    def var(name, units, long_name, dtype=None):
        data = np.asarray(cols[name], dtype=dtype).reshape(shape)
        attrs = {"long_name": long_name}
        if units:
            attrs["units"] = units
        return (dims, data, attrs)

    mu_lo = np.asarray(cols["mu_lo"], dtype=float).reshape(shape)
    mu_hi = np.asarray(cols["mu_hi"], dtype=float).reshape(shape)
    ds = xr.Dataset(
        {
            "mu_star": (
                dims,
                0.5 * (mu_lo + mu_hi),
                {"units": "1", "long_name": "jump friction coefficient mu* (bracket midpoint)"},
            ),
            "mu_lo": var("mu_lo", "1", "largest mu found not to stick", float),
            "mu_hi": var("mu_hi", "1", "smallest mu found to stick", float),
            "outcome_lo": var("outcome_lo", None, "outcome at mu_lo", str),
            "outcome_hi": var("outcome_hi", None, "outcome at mu_hi", str),
            "size_lo": var(
                "size_lo", "m", "size at mu_lo: converged cycle only (NaN in decide mode)", float
            ),
            "size_hi": var("size_hi", "m", "size at mu_hi (the sticking circle)", float),
            "R1_hi": var("R1_hi", "m", "first sticking radius at mu_hi", float),
            "n_runs": var("n_runs", "1", "runs made for this point", np.int64),
            "status": var("status", None, "converged or failed", str),
            "reason": var("reason", None, "why the point converged or failed", str),
            "monotone": var("monotone", None, "1 if no run contradicts a single jump", np.int8),
            "warm_start": var("warm_start", None, "1 if the bracket was predicted", np.int8),
        },
        coords=_coords(campaign),
        attrs={
            **_attrs(campaign),
            "tol": campaign.task.tol,
            "runs_saved_by_warm_start": int(planner.runs_saved()),
        },
    )
    return ds


def _scan_results(campaign, planner) -> xr.Dataset:
    shape = campaign.shape
    dims = tuple(dim_names(campaign)[k] for k in campaign.dims)
    results = [planner.results[i] for i in range(len(planner.points))]
    data_vars = {
        "outcome": (
            dims,
            np.asarray([r["outcome"] for r in results], dtype=str).reshape(shape),
            {"long_name": "stick, stick_slip, slide or undetermined"},
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
    for name, (units, long_name) in RUN_MEASURES.items():
        values = np.asarray([_num(r.get(name)) for r in results]).reshape(shape)
        data_vars[name] = (dims, values, {"units": units, "long_name": long_name})
    return xr.Dataset(data_vars, coords=_coords(campaign), attrs=_attrs(campaign))


def _run_rows(campaign, planner):
    """(point index, mu, level, result) of every run the planner used, in point order."""
    if campaign.task.kind == "find_jump":
        for i in range(len(planner.points)):
            for run in planner.results[i].runs:
                yield i, run.request, run.result
    else:
        from frictiondisk.bisection import RunRequest

        for i, point in enumerate(planner.points):
            yield i, RunRequest(point.config.params.mu), planner.results[i]


def runs_dataset(campaign, planner, key_of) -> xr.Dataset:
    """Every run: its point, mu, retry level, outcome, measures and wall time."""
    rows = list(_run_rows(campaign, planner))
    names = dim_names(campaign)
    data_vars: dict[str, Any] = {
        "point": ("run", np.asarray([r[0] for r in rows], np.int64), {"long_name": "point index"}),
        "mu": ("run", np.asarray([r[1].mu for r in rows]), {"units": "1", "long_name": "mu"}),
        "level": (
            "run",
            np.asarray([r[1].level for r in rows], np.int64),
            {"long_name": "retry level (horizon x horizon_factor**level)"},
        ),
        "outcome": ("run", np.asarray([r[2]["outcome"] for r in rows], str), {}),
        "reason": ("run", np.asarray([r[2].get("reason", "") for r in rows], str), {}),
        "key": (
            "run",
            np.asarray([key_of(r[0], r[1]) for r in rows], str),
            {"long_name": "journal key (content hash of the run's inputs + kernel version)"},
        ),
        "wall_s": (
            "run",
            np.asarray([_num(r[2].get("wall_s")) for r in rows]),
            {"units": "s", "long_name": "wall time of the kernel run"},
        ),
    }
    for key in campaign.dims:
        if key == "params.mu":
            continue
        values = [planner.points[r[0]].coords[key] for r in rows]
        data_vars[names[key]] = ("run", np.asarray(values, float), _key_attrs(key))
    for name, (units, long_name) in RUN_MEASURES.items():
        values = np.asarray([_num(r[2].get(name)) for r in rows])
        data_vars[name] = ("run", values, {"units": units, "long_name": long_name})
    return xr.Dataset(data_vars, attrs=_attrs(campaign))
