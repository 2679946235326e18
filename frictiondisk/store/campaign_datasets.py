"""What every campaign's netCDF files share, whatever its task: the dimension names and CF
attributes of its varied scene keys, the campaign's own attributes, the columns every
runs.nc has, and runs.nc of a task whose runs are requests in mu (find_jump, scan).

The task's own variables are built in its package (frictiondisk/tasks/<task>/datasets.py).
results.nc holds no timing, so the same campaign gives identical files whatever the worker
count; wall times are in runs.nc.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.model.scene import describe_key
from frictiondisk.model.yamlio import dump_yaml
from frictiondisk.store import cf
from frictiondisk.store.journal_entry import kernel_version
from frictiondisk.store.measures import RUN_MEASURES, measure_columns, num
from frictiondisk.version import __version__


def dim_names(campaign) -> dict[str, str]:
    """Dimension name of each varied scene key: its last part, unless two would clash."""
    short = {key: key.split(".")[-1] for key in campaign.dims}
    if len(set(short.values())) < len(short):
        return {key: key.replace(".", "_") for key in campaign.dims}
    return short


def key_attrs(key: str) -> dict[str, str]:
    """units, long_name and scene_key of a varied scene key."""
    unit, description = describe_key(key)
    # the scene schema's descriptions end in "[unit]"; CF keeps the unit in `units` alone
    description = description.removesuffix(f" [{unit}]") if unit else description
    attrs = {"long_name": description, "scene_key": key}
    if unit:
        attrs["units"] = unit
    return attrs


def coords(campaign) -> dict[str, Any]:
    """The campaign's varied keys as coordinates, named by dim_names."""
    names = dim_names(campaign)
    return {
        names[key]: (names[key], np.asarray(campaign.coords[key], dtype=float), key_attrs(key))
        for key in campaign.dims
    }


def campaign_attrs(campaign) -> dict[str, Any]:
    """The attributes of every file of a campaign: its name, task, text, numerics, versions
    and the scene values it fixes."""
    return {
        "campaign_name": campaign.name,
        "task": campaign.kind,
        "campaign_yaml": campaign.text,
        "numerics_yaml": dump_yaml(campaign.base.canonical()["numerics"]),
        "frictiondisk_version": __version__,
        "kernel_version": kernel_version(),
        **cf.scene_attrs(campaign.base, unfixed_keys(campaign)),
        **(campaign.numerics_choice.attrs() if campaign.numerics_choice else {}),
    }


def unfixed_keys(campaign) -> set[str]:
    """The scene keys without one value in the files: varied (the coordinates), and those
    the task searches or samples (TaskSpec.unfixed_keys)."""
    return set(campaign.dims) | campaign.task.unfixed_keys()


def run_columns(campaign, points, run_points, results, keys) -> dict[str, Any]:
    """The columns every runs.nc has, one row per run: outcome, reason, journal key, wall
    time, the point's coordinates (but mu) and the run measures. points: the campaign's
    points; run_points: each run's point index; results: its result summary; keys: its
    journal key."""
    names = dim_names(campaign)
    columns: dict[str, Any] = {
        "outcome": ("run", np.asarray([r["outcome"] for r in results], str), {}),
        "reason": ("run", np.asarray([r.get("reason", "") for r in results], str), {}),
        "decided_by": ("run", np.asarray([r.get("decided_by", "") for r in results], str), {}),
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
        values = [points[i].coords[key] for i in run_points]
        columns[names[key]] = ("run", np.asarray(values, float), key_attrs(key))
    measures = measure_columns(results)
    for name, (units, long_name) in RUN_MEASURES.items():
        columns[name] = ("run", measures[name], {"units": units, "long_name": long_name})
    return columns


# the roles of the runs of a request_runs_dataset (the text is part of the files)
REQUEST_ROLES = "search, prescan or certification (find_jump); scan"


def request_runs_dataset(campaign, points, rows, key_of) -> xr.Dataset:
    """runs.nc of a task whose runs are requests in mu (`rows`: (point index, request,
    result summary, role) in order; a request has mu, level, strict and mode): every run
    with its point, mu, retry and certification level, role (REQUEST_ROLES), mode,
    outcome, measures and wall time."""
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
            np.asarray([r[3] for r in rows], str),
            {"long_name": f"why the run was made: {REQUEST_ROLES}"},
        ),
        "mode": (
            "run",
            np.asarray([r[1].mode or points[r[0]].config.numerics.mode for r in rows], str),
            {"long_name": "numerics.mode of the run (decide or converge)"},
        ),
    }
    run_points = [r[0] for r in rows]
    keys = [key_of(r[0], r[1]) for r in rows]
    data_vars.update(run_columns(campaign, points, run_points, [r[2] for r in rows], keys))
    return cf.complete(
        xr.Dataset(data_vars, attrs=campaign_attrs(campaign)),
        title=f"frictiondisk campaign {campaign.name}: every run",
        what=f"frictiondisk run: campaign {campaign.name}, rebuilt from its journal",
    )
