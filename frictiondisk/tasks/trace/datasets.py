"""A trace campaign's results as xarray Datasets: results.nc (curves and folds) and runs.nc,
from its results snapshot (results.py).

results.nc holds every curve point (dim `point`, curve after curve, each in loop order:
the sticking side on the left): the key and mu of the point, its bracket in both
coordinates (the bisected one has width <= tol, the other is a single value), which was
bisected, which side sticks, its certification, its arclength along its curve (scaled by
the plane's ranges) and its runs; per curve (dim `curve`) its first point, count, whether
it is closed and why each end stopped; per fold (dim `fold`) the tip's key bracket, its mu
bracket, whether the region closing there sticks (a window) or not (a gap), status and
certification; per first-look key (dim `look`) the jumps found there. The key's variables
are named after the key's last part (e.g. `beta_b`, `beta_b_lo`), as in find_jump files.
No timing: the same campaign gives identical files whatever the worker count.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.model.search_settings import CERTIFICATION_FLAGS
from frictiondisk.store import cf
from frictiondisk.store.campaign_datasets import campaign_attrs, key_attrs, run_columns
from frictiondisk.store.partial import PENDING
from frictiondisk.tasks.trace.joins import tangent
from frictiondisk.tasks.trace.steps import norm, sub

RESERVED = {"mu", "point", "curve", "fold", "look", "run", "key", "level", "strict", "role"}
# CF attributes of this task's own variables (frictiondisk.store.cf.complete)
FLAGS: dict[str, cf.Flag] = {
    "certification": cf.CERTIFICATION,
    "bisected": ((0, 1), "mu key"),
    "stick_high": ((0, 1), "stick_at_low_end stick_at_high_end"),
    "rising": ((0, 1), "falling rising"),
    "curve_closed": ((0, 1), "open closed"),
    "fold_window": ((0, 1), "gap_closes sticking_window_closes"),
    "fold_certification": (tuple(range(len(CERTIFICATION_FLAGS))), " ".join(CERTIFICATION_FLAGS)),
}
TEXTS = {
    "purpose": ("what the run served", "first_look, curve or fold (trace)"),
    "fold_status": ("status of the fold", "located or not located"),
    "curve_first_end": ("why the curve's first end stopped", "edge, joined, closed, limit, failed"),
    "curve_last_end": ("why the curve's last end stopped", "edge, joined, closed, limit, failed"),
}


def key_name(key: str) -> str:
    """The variable name of the plane's key: its last part, unless that is taken."""
    short = key.split(".")[-1]
    return key.replace(".", "_") if short in RESERVED or short.startswith("mu") else short


def _flag(name: str) -> int:
    return CERTIFICATION_FLAGS.index(name) if name in CERTIFICATION_FLAGS else -1


def _point_rows(trace) -> dict[str, list]:
    rows: dict[str, list] = {
        name: []
        for name in (
            "curve",
            "key",
            "key_lo",
            "key_hi",
            "mu",
            "mu_lo",
            "mu_hi",
            "bisected",
            "stick_high",
            "rising",
            "certification",
            "arclength",
            "n_runs",
            "strict",
        )
    }
    for c, curve in enumerate(trace.curves):
        length, last = 0.0, None
        for j, point in enumerate(curve.points):
            b = point.bracket
            if last is not None:
                length += norm(sub(point.position, last))
            last = point.position
            along_mu = b.along == "mu"
            rising = b.stick_high if along_mu else tangent(curve, j)[0] > 0
            rows["curve"].append(c)
            rows["key"].append(b.key)
            rows["key_lo"].append(b.key if along_mu else b.lo)
            rows["key_hi"].append(b.key if along_mu else b.hi)
            rows["mu"].append(b.mu)
            rows["mu_lo"].append(b.lo if along_mu else b.mu)
            rows["mu_hi"].append(b.hi if along_mu else b.mu)
            rows["bisected"].append(0 if along_mu else 1)
            rows["stick_high"].append(int(b.stick_high))
            rows["rising"].append(int(rising))
            rows["certification"].append(_flag(b.certification))
            rows["arclength"].append(length)
            rows["n_runs"].append(len(b.result.runs))
            rows["strict"].append(b.result.strict)
    return rows


def results_dataset(snapshot) -> xr.Dataset:
    """results.nc of a trace campaign (see the module docstring)."""
    campaign, trace = snapshot.campaign, snapshot.trace
    task = campaign.task
    name = key_name(task.key)
    of_key = key_attrs(task.key)
    rows = _point_rows(trace)

    def point_var(column, dtype, attrs):
        return ("point", np.asarray(rows[column], dtype=dtype), attrs)

    def key_var(column, what):
        return point_var(column, float, {**of_key, "long_name": f"{of_key['long_name']}; {what}"})

    data = {
        "point_curve": point_var(
            "curve", np.int64, {"units": "1", "long_name": "curve of the point"}
        ),
        name: key_var("key", "key at the point (bracket midpoint where the key was bisected)"),
        f"{name}_lo": key_var("key_lo", "bracket low end in the key"),
        f"{name}_hi": key_var("key_hi", "bracket high end in the key"),
        "mu_star": point_var(
            "mu",
            float,
            {"units": "1", "long_name": "mu at the point (bracket midpoint where mu was bisected)"},
        ),
        "mu_lo": point_var("mu_lo", float, {"units": "1", "long_name": "bracket low end in mu"}),
        "mu_hi": point_var("mu_hi", float, {"units": "1", "long_name": "bracket high end in mu"}),
        "bisected": point_var("bisected", np.int8, {"long_name": "the coordinate bisected"}),
        "stick_high": point_var(
            "stick_high", np.int8, {"long_name": "which end of the bisected bracket sticks"}
        ),
        "rising": point_var(
            "rising",
            np.int8,
            {"long_name": "1: stick above the curve in mu (rising jump); 0: below"},
        ),
        "certification": point_var(
            "certification", np.int8, {"long_name": "certification of the point's bracket"}
        ),
        "arclength": point_var(
            "arclength",
            float,
            {
                "units": "1",
                "long_name": "arclength from the curve's first point, scaled by the plane's ranges",
            },
        ),
        "n_runs": point_var("n_runs", np.int64, {"long_name": "runs of the point's bisection"}),
        "strict": point_var(
            "strict",
            np.int64,
            {"long_name": "certification level of the numerics behind the bracket"},
        ),
    }
    data.update(_curve_vars(trace))
    data.update(_fold_vars(trace, name, of_key))
    data.update(_look_vars(trace, name, of_key))
    attrs = {
        **campaign_attrs(campaign),
        "tol": task.tol,
        "key_tol": task.tol * (task.range[1] - task.range[0]) / (task.mu[1] - task.mu[0]),
        "resolution": task.resolution,
        "trace_key": task.key,
        "trace_key_var": name,
        "key_range": np.asarray(task.range, float),
        "mu_range": np.asarray(task.mu, float),
        "status": trace.status,
        "reason": trace.reason,
    }
    if not task.sides.is_default:  # a boundary between two motions, not the stick jump
        sides = task.sides
        attrs["between"] = (
            f"[{sides.low}, {sides.high}]: each curve separates {sides.low} from {sides.high}; "
            "a fold is where the two coexist on both sides of a window's tip"
        )
    ds = xr.Dataset(data, attrs=attrs)
    return cf.complete(
        ds,
        title=f"frictiondisk trace campaign {campaign.name}: the jump curves of the plane "
        f"({task.key}, mu)",
        what=f"frictiondisk run: campaign {campaign.name}, task trace, rebuilt from its journal",
        flags=FLAGS,
        texts=TEXTS,
    )


def _curve_vars(trace) -> dict[str, Any]:
    first, count, closed, ends = [], [], [], ([], [])
    total = 0
    for curve in trace.curves:
        first.append(total)
        count.append(len(curve.points))
        total += len(curve.points)
        closed.append(int(curve.closed))
        ends[0].append(curve.ends[-1] or PENDING)
        ends[1].append(curve.ends[+1] or PENDING)
    return {
        "curve_first_point": (
            "curve",
            np.asarray(first, np.int64),
            {"units": "1", "long_name": "index of the curve's first point"},
        ),
        "curve_points": (
            "curve",
            np.asarray(count, np.int64),
            {"units": "1", "long_name": "points of the curve"},
        ),
        "curve_closed": (
            "curve",
            np.asarray(closed, np.int8),
            {"long_name": "whether the curve is closed"},
        ),
        "curve_first_end": (
            "curve",
            np.asarray(ends[0], str),
            {"long_name": "why the curve's first end stopped"},
        ),
        "curve_last_end": (
            "curve",
            np.asarray(ends[1], str),
            {"long_name": "why the curve's last end stopped"},
        ),
    }


def _fold_vars(trace, name: str, of_key: dict[str, str]) -> dict[str, Any]:
    ids = [curve.id for curve in trace.curves]
    folds = [(ids.index(i) if i in ids else -1, fold) for i, fold in trace.folds]

    def column(values, dtype=float):
        return np.asarray(values, dtype=dtype)

    def key_var(values, what):
        return (
            "fold",
            column(values),
            {**of_key, "long_name": f"{of_key['long_name']}; {what}"},
        )

    return {
        "fold_curve": (
            "fold",
            column([c for c, _ in folds], np.int64),
            {"units": "1", "long_name": "curve of the fold (-1: not on a curve kept)"},
        ),
        f"fold_{name}": key_var(
            [f.key for _, f in folds], "key of the fold's tip (midpoint of its bracket)"
        ),
        f"fold_{name}_in": key_var(
            [f.key_in for _, f in folds], "key where the region is present, next to the tip"
        ),
        f"fold_{name}_out": key_var(
            [f.key_out for _, f in folds], "key beyond the tip, where the region is absent"
        ),
        "fold_mu": (
            "fold",
            column([f.mu for _, f in folds]),
            {
                "units": "1",
                "long_name": "mu of the fold's tip (the region's centre at the key inside)",
            },
        ),
        "fold_mu_lo": (
            "fold",
            column([f.mu_lo for _, f in folds]),
            {"units": "1", "long_name": "lower end of the tip's bracket in mu"},
        ),
        "fold_mu_hi": (
            "fold",
            column([f.mu_hi for _, f in folds]),
            {"units": "1", "long_name": "upper end of the tip's bracket in mu"},
        ),
        "fold_window": (
            "fold",
            column([int(f.inner_sticks) for _, f in folds], np.int8),
            {"long_name": "what closes at the tip"},
        ),
        "fold_certification": (
            "fold",
            column([_flag(f.certification) for _, f in folds], np.int8),
            {"long_name": "certification of the fold"},
        ),
        "fold_status": (
            "fold",
            column([f.status for _, f in folds], str),
            {"long_name": "located or not located"},
        ),
        "fold_reason": (
            "fold",
            column([f.reason for _, f in folds], str),
            {"long_name": "why a fold was not located"},
        ),
    }


def _look_vars(trace, name: str, of_key: dict[str, str]) -> dict[str, Any]:
    keys = [key for key, _ in trace.look]
    jumps = [len(found.jumps) for _, found in trace.look]
    return {
        f"look_{name}": (
            "look",
            np.asarray(keys, float),
            {**of_key, "long_name": f"{of_key['long_name']}; a key of the first look"},
        ),
        "look_jumps": (
            "look",
            np.asarray(jumps, np.int64),
            {"units": "1", "long_name": "jumps the first look found at the key"},
        ),
    }


def runs_dataset(snapshot, key_of) -> xr.Dataset:
    """Every run of the trace, in schedule order: key, mu, levels, role, purpose, outcome,
    measures, journal key, wall time."""
    campaign, trace = snapshot.campaign, snapshot.trace
    runs = trace.runs
    name = key_name(campaign.task.key)
    base_mode = campaign.base.numerics.mode
    data: dict[str, Any] = {
        name: (
            "run",
            np.asarray([r.request.key for r in runs], float),
            key_attrs(campaign.task.key),
        ),
        "mu": (
            "run",
            np.asarray([r.request.mu for r in runs], float),
            {"units": "1", "long_name": "mu"},
        ),
        "level": (
            "run",
            np.asarray([r.request.level for r in runs], np.int64),
            {"long_name": "retry level (horizon x horizon_factor**level)"},
        ),
        "strict": (
            "run",
            np.asarray([r.request.strict for r in runs], np.int64),
            {
                "long_name": "certification level (horizon budget x certify.horizon**strict, rtol x certify.rtol**strict)"
            },
        ),
        "role": (
            "run",
            np.asarray([r.role for r in runs], str),
            {"long_name": "why the run was made: prescan, search or certification"},
        ),
        "purpose": (
            "run",
            np.asarray([r.purpose for r in runs], str),
            {"long_name": "what it served: first_look, curve or fold"},
        ),
        "mode": (
            "run",
            np.asarray([r.request.mode or base_mode for r in runs], str),
            {"long_name": "numerics.mode of the run (decide or converge)"},
        ),
    }
    keys = [key_of(0, r.request) for r in runs]
    results = [r.result for r in runs]
    data.update(run_columns(campaign, snapshot.points, [0] * len(runs), results, keys))
    return cf.complete(
        xr.Dataset(data, attrs=campaign_attrs(campaign)),
        title=f"frictiondisk trace campaign {campaign.name}: every run",
        what=f"frictiondisk run: campaign {campaign.name}, task trace, rebuilt from its journal",
        flags=FLAGS,
        texts=TEXTS,
    )
