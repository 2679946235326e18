"""Campaign results as xarray Datasets: results.nc (one row per point) and runs.nc.

results.nc holds no timing, so the same campaign gives identical files whatever the
worker count; wall times are in runs.nc.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.model.scene import describe_key
from frictiondisk.model.yamlio import dump_yaml
from frictiondisk.search.bisection import RunRequest
from frictiondisk.search.certify import CERTIFICATION_FLAGS
from frictiondisk.search.jumps import RUN_ROLES, run_role
from frictiondisk.search.requests import run_config
from frictiondisk.store import cf
from frictiondisk.store.journal import kernel_version
from frictiondisk.store.jump_datasets import all_jumps
from frictiondisk.store.measures import RUN_MEASURES, num
from frictiondisk.store.partial import PENDING
from frictiondisk.verdict.horizon import horizon_of
from frictiondisk.version import __version__


def dim_names(campaign) -> dict[str, str]:
    """Dimension name of each varied scene key: its last part, unless two would clash."""
    short = {key: key.split(".")[-1] for key in campaign.dims}
    if len(set(short.values())) < len(short):
        return {key: key.replace(".", "_") for key in campaign.dims}
    return short


def _key_attrs(key: str) -> dict[str, str]:
    """units, long_name and scene_key of a varied scene key."""
    unit, description = describe_key(key)
    # the scene schema's descriptions end in "[unit]"; CF keeps the unit in `units` alone
    description = description.removesuffix(f" [{unit}]") if unit else description
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


def campaign_attrs(campaign) -> dict[str, Any]:
    return {
        "campaign_name": campaign.name,
        "task": campaign.task.kind,
        "campaign_yaml": campaign.text,
        "numerics_yaml": dump_yaml(campaign.base.canonical()["numerics"]),
        "frictiondisk_version": __version__,
        "kernel_version": kernel_version(),
        **cf.scene_attrs(campaign.base, unfixed_keys(campaign)),
        **(campaign.numerics_choice.attrs() if campaign.numerics_choice else {}),
    }


def unfixed_keys(campaign) -> set[str]:
    """The scene keys without one value in the files: varied (the coordinates), sampled
    (a basin) and params.mu where a find_jump searches it."""
    keys = set(campaign.dims) | set(getattr(campaign.task, "sample", {}))
    return keys | ({"params.mu"} if campaign.kind == "find_jump" else set())


def results_dataset(campaign, planner) -> xr.Dataset:
    """results.nc: one row per point (find_jump: mu* and its bracket; scan: the run)."""
    kind = campaign.task.kind
    if kind == "find_jump":
        ds, what = _jump_results(campaign, planner), "the jump mu* per point"
    else:
        ds, what = _scan_results(campaign, planner), "the outcome and measures per point"
    return cf.complete(
        ds,
        title=f"frictiondisk {kind} campaign {campaign.name}: {what}",
        what=f"frictiondisk run: campaign {campaign.name}, task {kind}, rebuilt from its journal",
    )


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
            "certification",
            "verdict_horizon",
            "verdict_rtol",
            *(f"runs_{role}" for role in RUN_ROLES),
        )
    }
    task = campaign.task
    for i in range(n):
        res = planner.results[i]
        lo, hi = res.end_result("lo") or {}, res.end_result("hi") or {}
        cols["mu_lo"].append(res.mu_lo)
        cols["mu_hi"].append(res.mu_hi)
        cols["outcome_lo"].append(lo.get("outcome", ""))
        cols["outcome_hi"].append(hi.get("outcome", ""))
        cols["size_lo"].append(num(lo.get("size")))
        cols["size_hi"].append(num(hi.get("size")))
        cols["R1_hi"].append(num(hi.get("R1")))
        cols["n_runs"].append(len(res.runs))
        roles = [_role_of(res, run.request) for run in res.runs]
        for role in RUN_ROLES:
            cols[f"runs_{role}"].append(roles.count(role))
        cols["status"].append(res.status)
        cols["reason"].append(res.reason)
        cols["monotone"].append(np.int8(res.monotone))
        cols["warm_start"].append(np.int8(planner.warm.get(i, False)))
        cols["certification"].append(
            CERTIFICATION_PENDING
            if res.status == PENDING
            else CERTIFICATION_FLAGS.index(res.certification)
        )
        horizon, rtol = verdict_numerics(planner.points[i].config, task, _strict_of(res))
        cols["verdict_horizon"].append(horizon)
        cols["verdict_rtol"].append(rtol)

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
            **{
                f"runs_{role}": var(f"runs_{role}", "1", f"{role} runs of this point", np.int64)
                for role in RUN_ROLES
            },
            "status": var("status", None, "converged or failed", str),
            "reason": var("reason", None, "why the point converged or failed", str),
            "monotone": var("monotone", None, "1 if no run contradicts a single jump", np.int8),
            "warm_start": var("warm_start", None, "1 if the bracket was predicted", np.int8),
            "certification": (
                dims,
                np.asarray(cols["certification"], np.int8).reshape(shape),
                {"long_name": "certification of mu* (the weakest of the point's jumps)"},
            ),
            "verdict_horizon": var(
                "verdict_horizon", "s", "decision horizon of the runs behind mu_lo and mu_hi", float
            ),
            "verdict_rtol": var(
                "verdict_rtol", "1", "rtol of the runs behind mu_lo and mu_hi", float
            ),
        },
        coords=_coords(campaign),
        attrs={
            **campaign_attrs(campaign),
            "tol": campaign.task.tol,
            "runs_saved_by_warm_start": int(planner.runs_saved()),
        },
    )
    if campaign.task.prescan is not None:
        ds = ds.assign(all_jumps(campaign, planner, dims))
        ds = ds.assign_coords(
            scan_mu=(
                "scan_mu",
                np.asarray(campaign.task.prescan.mu, float),
                {"units": "1", "long_name": "prescan friction coefficient mu"},
            )
        )
        ds.attrs["prescan_mode"] = campaign.task.prescan.mode
    return ds


CERTIFICATION_PENDING = -1  # a point not finished yet (partial results)


def _role_of(res, request) -> str:
    """search, prescan or certification (jumps.RUN_ROLES) of one run of a point's result."""
    return res.role(request) if hasattr(res, "role") else run_role(request)


def _strict_of(res) -> int:
    """Certification level of the numerics behind a point's (primary) bracket."""
    primary = getattr(res, "primary", res)
    return 0 if primary is None else primary.strict


def verdict_numerics(point_config, task, strict: int) -> tuple[float, float]:
    """(decision horizon [s], rtol) of a run at certification level `strict`, as
    requests.run_config builds it (the one place that scales them)."""
    request = RunRequest(point_config.params.mu, strict=strict)
    config = run_config(point_config, request, task.horizon_factor, task.certify)
    return horizon_of(config), config.numerics.rtol


def _scan_results(campaign, planner) -> xr.Dataset:
    shape = campaign.shape
    dims = tuple(dim_names(campaign)[k] for k in campaign.dims)
    results = [planner.results[i] for i in range(len(planner.points))]
    data_vars = {
        "outcome": (
            dims,
            np.asarray([r["outcome"] for r in results], dtype=str).reshape(shape),
            {"long_name": "stick, creep, stick_slip, slide or undetermined"},
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
        values = np.asarray([num(r.get(name)) for r in results]).reshape(shape)
        data_vars[name] = (dims, values, {"units": units, "long_name": long_name})
    return xr.Dataset(data_vars, coords=_coords(campaign), attrs=campaign_attrs(campaign))


def _run_rows(campaign, planner):
    """(point index, mu, level, result) of every run the planner used, in point order."""
    if campaign.task.kind == "find_jump":
        for i in range(len(planner.points)):
            for run in planner.results[i].runs:
                yield i, run.request, run.result
    else:
        from frictiondisk.search.bisection import RunRequest

        for i, point in enumerate(planner.points):
            yield i, RunRequest(point.config.params.mu), planner.results[i]


def run_columns(campaign, planner, points, results, keys) -> dict[str, Any]:
    """The columns every runs.nc has, one row per run: outcome, reason, journal key, wall
    time, the point's coordinates (but mu) and the run measures. points: each run's point
    index; results: its result summary; keys: its journal key."""
    names = dim_names(campaign)
    columns: dict[str, Any] = {
        "outcome": ("run", np.asarray([r["outcome"] for r in results], str), {}),
        "reason": ("run", np.asarray([r.get("reason", "") for r in results], str), {}),
        "key": (
            "run",
            np.asarray(keys, str),
            {"long_name": "journal key (content hash of the run's inputs + kernel version)"},
        ),
        "wall_s": (
            "run",
            np.asarray([num(r.get("wall_s")) for r in results]),
            {"units": "s", "long_name": "wall time of the kernel run"},
        ),
    }
    for key in campaign.dims:
        if key == "params.mu":
            continue
        values = [planner.points[i].coords[key] for i in points]
        columns[names[key]] = ("run", np.asarray(values, float), _key_attrs(key))
    for name, (units, long_name) in RUN_MEASURES.items():
        values = np.asarray([num(r.get(name)) for r in results])
        columns[name] = ("run", values, {"units": units, "long_name": long_name})
    return columns


def runs_dataset(campaign, planner, key_of) -> xr.Dataset:
    """Every run: its point, mu, retry level, outcome, measures and wall time."""
    rows = list(_run_rows(campaign, planner))
    data_vars: dict[str, Any] = {
        "point": ("run", np.asarray([r[0] for r in rows], np.int64), {"long_name": "point index"}),
        "mu": ("run", np.asarray([r[1].mu for r in rows]), {"units": "1", "long_name": "mu"}),
        "level": (
            "run",
            np.asarray([r[1].level for r in rows], np.int64),
            {"long_name": "retry level (horizon x horizon_factor**level)"},
        ),
        "strict": (
            "run",
            np.asarray([r[1].strict for r in rows], np.int64),
            {
                "long_name": "certification level (horizon budget x certify.horizon**strict, "
                "rtol and atol x certify.rtol**strict)"
            },
        ),
        "role": (
            "run",
            np.asarray(
                [
                    _role_of(planner.results[r[0]], r[1])
                    if campaign.task.kind == "find_jump"
                    else "scan"
                    for r in rows
                ],
                str,
            ),
            {
                "long_name": "why the run was made: search, prescan or certification (find_jump); scan"
            },
        ),
        "mode": (
            "run",
            np.asarray([r[1].mode or planner.points[r[0]].config.numerics.mode for r in rows], str),
            {"long_name": "numerics.mode of the run (decide or converge)"},
        ),
    }
    points = [r[0] for r in rows]
    keys = [key_of(r[0], r[1]) for r in rows]
    data_vars.update(run_columns(campaign, planner, points, [r[2] for r in rows], keys))
    return cf.complete(
        xr.Dataset(data_vars, attrs=campaign_attrs(campaign)),
        title=f"frictiondisk campaign {campaign.name}: every run",
        what=f"frictiondisk run: campaign {campaign.name}, rebuilt from its journal",
    )
