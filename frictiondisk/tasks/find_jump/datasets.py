"""A find_jump campaign's results.nc (mu* and its bracket per point; with a prescan, every
jump, window and the prescan grid: jump_datasets.py) and runs.nc, from its results
snapshot (results.py). A point not finished yet (partial results) is `pending`: NaN mu*,
no runs, certification -1."""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.model.search_settings import CERTIFICATION_FLAGS
from frictiondisk.store import cf
from frictiondisk.store.campaign_datasets import (
    campaign_attrs,
    coords,
    dim_names,
    key_attrs,
    request_runs_dataset,
)
from frictiondisk.store.measures import num
from frictiondisk.store.partial import PENDING, PENDING_REASON
from frictiondisk.tasks.find_jump.coexistence import with_coexistence
from frictiondisk.tasks.find_jump.jump_datasets import all_jumps
from frictiondisk.tasks.jump_search.jump_result import RUN_ROLES, run_role
from frictiondisk.tasks.jump_search.requests import run_config
from frictiondisk.tasks.jump_search.runs import RunRequest
from frictiondisk.verdict.horizon import horizon_of

CERTIFICATION_PENDING = -1  # a point not finished yet (partial results)
OUTCOMES = cf.OUTCOMES
# CF attributes of this task's own variables (frictiondisk.store.cf.complete)
FLAGS: dict[str, cf.Flag] = {
    "monotone": ((0, 1), "contradicts_a_single_jump single_jump"),
    "warm_start": ((0, 1), "bracket_from_campaign bracket_predicted"),
    "certification": cf.CERTIFICATION,
    "jump_rising": ((-1, 0, 1), "no_jump falling rising"),
    "window_narrow": ((-1, 0, 1), "no_window wider_than_persistence narrower_than_persistence"),
    "jump_certification": (
        tuple(range(-1, len(CERTIFICATION_FLAGS))),
        " ".join(("no_jump", *CERTIFICATION_FLAGS)),
    ),
}
TEXTS = {
    "outcome_lo": ("outcome at mu_lo", f"one of: {OUTCOMES}"),
    "outcome_hi": ("outcome at mu_hi", f"one of: {OUTCOMES}"),
    "scan_outcome": (
        "outcome of the prescan run",
        f"one of: {OUTCOMES}; empty: a value the adaptive prescan did not need to run",
    ),
    "jump_status": ("status of the jump", "converged or failed; empty: no jump"),
}
DIMENSIONLESS = ("n_jumps", "n_windows")

# (name, units, long_name, dtype) of the per-point variables, in file order
POINT_VARIABLES = (
    ("mu_lo", "1", "largest mu found not to stick", float),
    ("mu_hi", "1", "smallest mu found to stick", float),
    ("outcome_lo", None, "outcome at mu_lo", str),
    ("outcome_hi", None, "outcome at mu_hi", str),
    ("size_lo", "m", "size at mu_lo: converged cycle only (NaN in decide mode)", float),
    ("size_hi", "m", "size at mu_hi (the sticking circle)", float),
    ("R1_hi", "m", "first sticking radius at mu_hi", float),
    ("n_runs", "1", "runs made for this point", np.int64),
    *((f"runs_{role}", "1", f"{role} runs of this point", np.int64) for role in RUN_ROLES),
    ("status", None, "converged or failed", str),
    ("reason", None, "why the point converged or failed", str),
    ("monotone", None, "1 if no run contradicts a single jump", np.int8),
    ("warm_start", None, "1 if the bracket was predicted", np.int8),
    ("certification", None, "certification of mu* (the weakest of the point's jumps)", np.int8),
    ("verdict_horizon", "s", "decision horizon of the runs behind mu_lo and mu_hi", float),
    ("verdict_rtol", "1", "rtol of the runs behind mu_lo and mu_hi", float),
)


def role_of(result, request) -> str:
    """search, prescan or certification (RUN_ROLES) of one run of a point's result."""
    return result.role(request) if hasattr(result, "role") else run_role(request)


def strict_of(result) -> int:
    """Certification level of the numerics behind a point's (primary) bracket."""
    primary = getattr(result, "primary", result)
    return 0 if primary is None else primary.strict


def verdict_numerics(point_config, task, strict: int) -> tuple[float, float]:
    """(decision horizon [s], rtol) of a run at certification level `strict`, as
    requests.run_config builds it (the one place that scales them)."""
    request = RunRequest(point_config.params.mu, strict=strict)
    config = run_config(point_config, request, task.horizon_factor, task.certify)
    return horizon_of(config), config.numerics.rtol


def point_row(result, warm: bool) -> dict[str, Any]:
    """The per-point values of a finished point's result (a BisectionResult or a
    JumpSearchResult), but its verdict numerics."""
    lo, hi = result.end_result("lo") or {}, result.end_result("hi") or {}
    roles = [role_of(result, run.request) for run in result.runs]
    return {
        "mu_lo": result.mu_lo,
        "mu_hi": result.mu_hi,
        "outcome_lo": lo.get("outcome", ""),
        "outcome_hi": hi.get("outcome", ""),
        "size_lo": num(lo.get("size")),
        "size_hi": num(hi.get("size")),
        "R1_hi": num(hi.get("R1")),
        "n_runs": len(result.runs),
        **{f"runs_{role}": roles.count(role) for role in RUN_ROLES},
        "status": result.status,
        "reason": result.reason,
        "monotone": np.int8(result.monotone),
        "warm_start": np.int8(warm),
        "certification": CERTIFICATION_FLAGS.index(result.certification),
    }


def pending_row(warm: bool) -> dict[str, Any]:
    """The per-point values of a point not finished yet."""
    return {
        "mu_lo": np.nan,
        "mu_hi": np.nan,
        "outcome_lo": "",
        "outcome_hi": "",
        "size_lo": np.nan,
        "size_hi": np.nan,
        "R1_hi": np.nan,
        "n_runs": 0,
        **{f"runs_{role}": 0 for role in RUN_ROLES},
        "status": PENDING,
        "reason": PENDING_REASON,
        "monotone": np.int8(False),
        "warm_start": np.int8(warm),
        "certification": CERTIFICATION_PENDING,
    }


def results_dataset(snapshot) -> xr.Dataset:
    """results.nc: mu* and its bracket per point (see the module docstring)."""
    campaign = snapshot.campaign
    return cf.complete(
        _jump_results(snapshot),
        title=f"frictiondisk find_jump campaign {campaign.name}: the jump mu* per point",
        what=f"frictiondisk run: campaign {campaign.name}, task find_jump, rebuilt from its "
        "journal",
        flags=FLAGS,
        texts=TEXTS,
        dimensionless=DIMENSIONLESS,
    )


def _columns(snapshot) -> dict[str, list]:
    """Every per-point variable's values, in point order."""
    task = snapshot.campaign.task
    columns: dict[str, list] = {name: [] for name, *_ in POINT_VARIABLES}
    for i, result in enumerate(snapshot.results):
        warm = snapshot.warm[i]
        row = pending_row(warm) if result is None else point_row(result, warm)
        strict = 0 if result is None else strict_of(result)
        config = snapshot.points[i].config
        row["verdict_horizon"], row["verdict_rtol"] = verdict_numerics(config, task, strict)
        for name, value in row.items():
            columns[name].append(value)
    return columns


def _jump_results(snapshot) -> xr.Dataset:
    campaign = snapshot.campaign
    shape = campaign.shape
    dims = tuple(dim_names(campaign)[k] for k in campaign.dims)
    columns = _columns(snapshot)

    def var(name, units, long_name, dtype):
        attrs = {"long_name": long_name} | ({"units": units} if units else {})
        return (dims, np.asarray(columns[name], dtype=dtype).reshape(shape), attrs)

    mu_lo = np.asarray(columns["mu_lo"], dtype=float).reshape(shape)
    mu_hi = np.asarray(columns["mu_hi"], dtype=float).reshape(shape)
    mu_star = {"units": "1", "long_name": "jump friction coefficient mu* (bracket midpoint)"}
    data_vars = {"mu_star": (dims, 0.5 * (mu_lo + mu_hi), mu_star)}
    data_vars |= {spec[0]: var(*spec) for spec in POINT_VARIABLES}
    task = campaign.task
    ds = xr.Dataset(
        data_vars,
        coords=coords(campaign),
        attrs={
            **campaign_attrs(campaign),
            "tol": task.tol,
            "runs_saved_by_warm_start": int(snapshot.runs_saved),
        },
    )
    if task.prescan is not None:
        ds = ds.assign(all_jumps(campaign, snapshot.results, dims))
        ds = ds.assign_coords(
            scan_mu=(
                "scan_mu",
                np.asarray(task.prescan.mu, float),
                {"units": "1", "long_name": "prescan friction coefficient mu"},
            )
        )
        ds.attrs["prescan_mode"] = task.prescan.mode
    if not task.sides.is_default:
        ds = _between(ds, task.sides, task.tol)
    if task.parameter != "mu":
        ds = _parameter(ds, task.parameter_key)
    return ds


# the variables that hold values of the bisected parameter (named after mu in every file)
PARAMETER_VARS = (
    "mu_star",
    "mu_lo",
    "mu_hi",
    "scan_mu",
    "jump_mu_lo",
    "jump_mu_hi",
    "jump_mu_star",
)


def _parameter(ds: xr.Dataset, key: str) -> xr.Dataset:
    """A find_jump that bisects another scene key than mu: its variables keep mu's names
    (mu_star, mu_lo, ...), with the key's units and a long name that says what they hold."""
    attrs = key_attrs(key)
    ds.attrs["parameter"] = key
    for name in PARAMETER_VARS:
        if name in ds.variables:
            var = ds[name]
            old = str(var.attrs.get("long_name", name))
            var.attrs.update(
                units=attrs.get("units", "1"),
                long_name=f"{old.replace('friction coefficient ', '')} [values of {key}]",
            )
    return ds


def _between(ds: xr.Dataset, sides, tol: float) -> xr.Dataset:
    """A boundary other than the stick jump: its sides named in the attributes and long
    names, and where the two motions coexist (coexistence.py)."""
    ds.attrs["between"] = f"[{sides.low}, {sides.high}]: {sides.low} below mu*, {sides.high} above"
    ds["mu_star"].attrs["long_name"] = f"boundary {sides.label()} in mu (bracket midpoint)"
    ds["mu_lo"].attrs["long_name"] = f"largest mu found {sides.low} (side A)"
    ds["mu_hi"].attrs["long_name"] = f"smallest mu found {sides.high} (side B)"
    return with_coexistence(ds, sides.label(), tol)


def runs_dataset(snapshot, key_of) -> xr.Dataset:
    """runs.nc: every run of every point, in point order, each point's in its own order."""
    rows = [
        (i, run.request, run.result, role_of(result, run.request))
        for i, result in enumerate(snapshot.results)
        for run in result.runs
    ]
    ds = request_runs_dataset(snapshot.campaign, snapshot.points, rows, key_of)
    task = snapshot.campaign.task
    if task.parameter != "mu":  # the column `mu` holds the bisected key's values
        ds["mu"].attrs.update(
            units=key_attrs(task.parameter_key).get("units", "1"),
            long_name=f"value of {task.parameter_key}, the bisected parameter",
        )
        # mu itself, where it varies along the points, gets a column of its own
        if "params.mu" in snapshot.campaign.dims:
            points = snapshot.points
            ds["point_mu"] = (
                "run",
                np.asarray([points[i].coords["params.mu"] for i in ds["point"].values], float),
                {
                    "units": "1",
                    "long_name": "mu of the run's point (the column mu holds "
                    f"{task.parameter_key})",
                },
            )
    return ds
