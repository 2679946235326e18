"""The answer of a campaign as text, printed by `frictiondisk run` and `status`: a
find_jump's mu* per point with its bracket, runs, status and certification (failed points
with their reasons), a scan's outcome and size per point, and the one-line summaries of
runs per point and of uncertain points."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from frictiondisk.search.jump_result import NO_JUMP
from frictiondisk.search.jumps import RUN_ROLES
from frictiondisk.store.cf import flag_meanings
from frictiondisk.store.partial import PENDING
from frictiondisk.store.trace_table import trace_closing


def _unit(coord: xr.DataArray) -> str:
    unit = str(coord.attrs.get("units", "")).strip()
    return "" if unit in ("", "1") else f" [{unit}]"


def _points(results: xr.Dataset, names: list[str]) -> list[tuple[tuple, xr.Dataset]]:
    """(coordinates, row) of every point of the variables `names`, in C order."""
    dims = list(results[names[0]].dims)
    stacked = results[names]
    if len(dims) > 1:
        stacked = stacked.stack(point=dims)
    elif dims:
        stacked = stacked.rename({dims[0]: "point"}).assign_coords(point=results[dims[0]].values)
    rows = []
    for i in range(stacked.sizes.get("point", 1)):
        row = stacked.isel(point=i) if dims else stacked
        coords = row["point"].values.item() if dims else ()
        rows.append((coords if isinstance(coords, tuple) else (coords,), row))
    return rows


def _number(value: float, spec: str) -> str:
    return f"{value:{spec}}" if math.isfinite(value) else "-"


def _columns(heads: list[str], rows: list[list[str]]) -> list[str]:
    widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(heads)]
    lines = [
        "  " + "  ".join(f"{c:<{w}}" for c, w in zip(r, widths, strict=True))
        for r in [heads, *rows]
    ]
    return [line.rstrip() for line in lines]


def _why(title: str, dims: list[str], which: list[tuple[tuple, str]]) -> list[str]:
    """`title`, then one line `  dim = value, ...: reason` per point of `which`."""
    if not which:
        return []
    where = [
        ", ".join(f"{d} = {c:g}" for d, c in zip(dims, coords, strict=True)) for coords, _ in which
    ]
    return [
        title,
        *(f"  {w or 'the point'}: {reason}" for w, (_, reason) in zip(where, which, strict=True)),
    ]


def mu_star_table(results: xr.Dataset) -> list[str]:
    """Lines of the mu* table of a find_jump results.nc; [] for any other task. A point
    that did not converge shows no mu* and no bracket (its last bracket is no answer); the
    points without a jump on their grid (NO_JUMP) and the failed points are listed under
    the table with their reasons."""
    if results.attrs.get("task") != "find_jump" or "mu_star" not in results:
        return []
    dims = list(results["mu_star"].dims)
    certified = "certification" in results
    names = ["mu_star", "mu_lo", "mu_hi", "n_runs", "status"]
    names += [name for name in ("certification", "reason") if name in results]
    jumps = results.get("jump_mu_star")
    windows = results.get("n_windows")
    below = _grid_below_column(results)
    rows, failed, without = [], [], []
    for i, (coords, row) in enumerate(_points(results, names)):
        status = str(row["status"].values.item())
        mu, lo, hi = (float(row[v]) for v in ("mu_star", "mu_lo", "mu_hi"))
        if status != "converged":
            mu = lo = hi = math.nan
        bracket = f"[{lo:.6f}, {hi:.6f}]" if math.isfinite(lo) and math.isfinite(hi) else "-"
        extra = ""
        if jumps is not None:
            n = int(np.isfinite(jumps.values.reshape(-1, jumps.shape[-1])[i]).sum())
            k = int(windows.values.reshape(-1)[i]) if windows is not None else 0
            parts = ([f"{n} jumps"] if n > 1 else []) + (
                [f"{k} window{'s' if k > 1 else ''}"] if k else []
            )
            extra = f" ({', '.join(parts)})" if parts else ""
        rows.append(
            [f"{c:g}" for c in coords]
            + [_number(mu, ".6f"), bracket, str(int(row["n_runs"]))]
            + [f"{status}{extra}"]
            + ([_flag(results["certification"], row["certification"])] if certified else [])
            + ([below[i]] if below else [])
        )
        if status in ("failed", NO_JUMP) and "reason" in row:
            which = failed if status == "failed" else without
            which.append((coords, str(row["reason"].values.item())))
    heads = [f"{d}{_unit(results[d])}" for d in dims]
    heads += ["mu*", "bracket [mu_lo, mu_hi]", "runs", "status"]
    heads += ["certification"] if certified else []
    heads += ["grid below mu* decided"] if below else []
    tol = results.attrs.get("tol")
    title = f"mu* per point (bracket width <= tol {float(tol):g}):" if tol else "mu* per point:"
    return [
        title,
        *_columns(heads, rows),
        *_why(f"points without a jump on their grid ({len(without)}):", dims, without),
        *_why(f"failed points ({len(failed)}), why:", dims, failed),
    ]


def scan_table(results: xr.Dataset) -> list[str]:
    """Lines of the table of a scan results.nc: outcome, size and a per point (a pending
    point of a partial file: `pending`), then the reason of each undetermined point; []
    for any other task."""
    if results.attrs.get("task") != "scan" or "outcome" not in results:
        return []
    dims = list(results["outcome"].dims)
    names = [name for name in ("outcome", "size", "a", "reason") if name in results]
    rows, undetermined = [], []
    for coords, row in _points(results, names):
        outcome = str(row["outcome"].values.item()) or PENDING
        measures = [_number(float(row[m]), ".4g") if m in row else "-" for m in ("size", "a")]
        rows.append([f"{c:g}" for c in coords] + [outcome, *measures])
        if outcome == "undetermined" and "reason" in row:
            undetermined.append((coords, str(row["reason"].values.item())))
    heads = [f"{d}{_unit(results[d])}" for d in dims]
    heads += ["outcome", *(f"{m}{_unit(results[m])}" for m in ("size", "a") if m in results)]
    return [
        "outcome per point:",
        *_columns(heads, rows),
        *_why(f"undetermined points ({len(undetermined)}), why:", dims, undetermined),
    ]


def results_table(results: xr.Dataset) -> list[str]:
    """The answer of a find_jump or scan results.nc as a table ([] for other tasks)."""
    return mu_star_table(results) or scan_table(results)


def _grid_below_column(results: xr.Dataset) -> list[str]:
    """'12/12 (0.01)' per point: prescan values below mu* with a decided verdict, of all,
    and the resolution below which a window could still hide; [] without a prescan."""
    if "grid_below_total" not in results:
        return []
    decided = results["grid_below_decided"].values.reshape(-1)
    total = results["grid_below_total"].values.reshape(-1)
    step = results["window_resolution"].values.reshape(-1)
    return [
        f"{int(d)}/{int(t)} ({r:.3g})" if math.isfinite(t) else "-"
        for d, t, r in zip(decided, total, step, strict=True)
    ]


def _flag(var: xr.DataArray, value) -> str:
    """The meaning of one CF flag value."""
    code = int(value)
    return flag_meanings(var).get(code, str(code))


def uncertain_summary(results: xr.Dataset) -> str | None:
    """'k of n points uncertain: x = ..., ...' for a find_jump results.nc with uncertain
    points (mu* not confirmed at the strictest certification level); None otherwise."""
    if "certification" not in results:
        return None
    var = results["certification"]
    flat = var.stack(point=var.dims) if var.dims else var.expand_dims("point")
    uncertain = [i for i in range(flat.sizes["point"]) if _flag(var, flat[i]) == "uncertain"]
    if not uncertain:
        return None
    where = []
    for i in uncertain:
        coords = flat["point"].values[i] if var.dims else ()
        coords = coords if isinstance(coords, tuple) else (coords,)
        where.append(", ".join(f"{d} = {c:g}" for d, c in zip(var.dims, coords, strict=True)))
    return f"{len(uncertain)} of {flat.sizes['point']} points uncertain: " + "; ".join(where)


def runs_summary(results: xr.Dataset) -> str | None:
    """'runs per point: 5.8 (search 3.4, prescan 0, certification 2.4)' for a find_jump
    results.nc (per finished point); None for other tasks."""
    if "runs_search" not in results or "n_runs" not in results:
        return None
    # a pending point of a partial results.nc has made no runs that count yet
    finished = int((results["status"] != "pending").sum()) if "status" in results else 0
    points = max(1, finished or int(results["n_runs"].size))
    parts = ", ".join(
        f"{role} {float(results[f'runs_{role}'].sum()) / points:.3g}" for role in RUN_ROLES
    )
    return f"runs per point: {float(results['n_runs'].sum()) / points:.3g} ({parts})"


def closing_lines(results: xr.Dataset) -> list[str]:
    """What `run` and `status` print under a find_jump's results: runs per point, and the
    uncertain points if any; under a trace's, its uncertain points and what failed ([] for
    other tasks)."""
    if results.attrs.get("task") == "trace":
        return trace_closing(results)
    return [line for line in (runs_summary(results), uncertain_summary(results)) if line]
