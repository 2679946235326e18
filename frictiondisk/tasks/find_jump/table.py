"""The answer of a find_jump campaign as text, printed by `run` and `status`: mu* per point
with its bracket, runs, status and certification (the points without a jump and the
failed points listed with their reasons), then the runs per point and the uncertain
points."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from frictiondisk.figures.searched import boundary_sides, searched_key
from frictiondisk.store.tables import (
    columns,
    coordinate_specs,
    flag_text,
    head_of,
    mu_decimals,
    number,
    point_rows,
    reasons,
)
from frictiondisk.tasks.find_jump.coexistence import coexistence_lines
from frictiondisk.tasks.jump_search.jump_result import NO_JUMP, RUN_ROLES


def table_lines(results: xr.Dataset) -> list[str]:
    """The mu* table (named after the bisected key) and the closing lines."""
    lines = [runs_summary(results), uncertain_summary(results)]
    key = searched_key(results)
    head = []
    if "parameter" in results.attrs:
        head.append(f"bisected parameter: {key.key} [{key.unit}]")
    sides = boundary_sides(results)
    if sides is not None:
        head.append(
            f"boundary between {sides[0]} (below {key.name}*) and {sides[1]} (above {key.name}*)"
        )
    tail = [line for line in lines if line] + coexistence_lines(results)
    return head + mu_star_table(results) + tail


def mu_star_table(results: xr.Dataset) -> list[str]:
    """Lines of the mu* table ([] without mu*). A point that did not converge shows no mu*
    and no bracket (its last bracket is no answer); the points without a jump on their grid
    (NO_JUMP) and the failed points are listed under the table with their reasons."""
    if "mu_star" not in results:
        return []
    dims = list(results["mu_star"].dims)
    certified = "certification" in results
    names = ["mu_star", "mu_lo", "mu_hi", "n_runs", "status"]
    names += [name for name in ("certification", "reason") if name in results]
    below = _grid_below_column(results)
    tol = results.attrs.get("tol")
    places = mu_decimals(None if tol is None else float(tol))  # two below the tol's place
    specs = coordinate_specs(results, dims)
    rows, failed, without = [], [], []
    for i, (coords, row) in enumerate(point_rows(results, names)):
        status = str(row["status"].values.item())
        mu, lo, hi = (float(row[v]) for v in ("mu_star", "mu_lo", "mu_hi"))
        if status != "converged":
            mu = lo = hi = math.nan
        finite = math.isfinite(lo) and math.isfinite(hi)
        bracket = f"[{lo:.{places}f}, {hi:.{places}f}]" if finite else "-"
        rows.append(
            [f"{c:{f}}" for c, f in zip(coords, specs, strict=True)]
            + [number(mu, f".{places}f"), bracket, str(int(row["n_runs"]))]
            + [f"{status}{_jumps_note(results, i)}"]
            + ([flag_text(results["certification"], row["certification"])] if certified else [])
            + ([below[i]] if below else [])
        )
        if status in ("failed", NO_JUMP) and "reason" in row:
            which = failed if status == "failed" else without
            which.append((coords, str(row["reason"].values.item())))
    key = searched_key(results)
    unit = f" [{key.unit}]" if key.key != "params.mu" else ""
    heads = [head_of(results, d) for d in dims]
    heads += [f"{key.name}*{unit}", f"bracket [{key.name}_lo, {key.name}_hi]", "runs", "status"]
    heads += ["certification"] if certified else []
    heads += ["grid below mu* decided"] if below else []
    width = f" (bracket width <= tol {float(tol):g}{key.unit_suffix})" if tol else ""
    title = f"{key.name}* per point{width}:"
    return [
        title,
        *columns(heads, rows),
        *reasons(f"points without a jump on their grid ({len(without)}):", dims, without, specs),
        *reasons(f"failed points ({len(failed)}), why:", dims, failed, specs),
    ]


def _jumps_note(results: xr.Dataset, i: int) -> str:
    """' (3 jumps, 1 window)' of point i of a prescanned find_jump; '' else."""
    jumps, windows = results.get("jump_mu_star"), results.get("n_windows")
    if jumps is None:
        return ""
    n = int(np.isfinite(jumps.values.reshape(-1, jumps.shape[-1])[i]).sum())
    k = int(windows.values.reshape(-1)[i]) if windows is not None else 0
    parts = ([f"{n} jumps"] if n > 1 else []) + ([f"{k} window{'s' if k > 1 else ''}"] if k else [])
    return f" ({', '.join(parts)})" if parts else ""


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


def uncertain_summary(results: xr.Dataset) -> str | None:
    """'k of n points uncertain: x = ..., ...' for results with uncertain points (mu* not
    confirmed at the strictest certification level); None otherwise."""
    if "certification" not in results:
        return None
    var = results["certification"]
    flat = var.stack(point=var.dims) if var.dims else var.expand_dims("point")
    uncertain = [i for i in range(flat.sizes["point"]) if flag_text(var, flat[i]) == "uncertain"]
    if not uncertain:
        return None
    where = []
    for i in uncertain:
        coords = flat["point"].values[i] if var.dims else ()
        coords = coords if isinstance(coords, tuple) else (coords,)
        where.append(", ".join(f"{d} = {c:g}" for d, c in zip(var.dims, coords, strict=True)))
    return f"{len(uncertain)} of {flat.sizes['point']} points uncertain: " + "; ".join(where)


def runs_summary(results: xr.Dataset) -> str | None:
    """'runs per point: 5.8 (search 3.4, prescan 0, certification 2.4)' (per finished
    point); None without the counts."""
    if "runs_search" not in results or "n_runs" not in results:
        return None
    # a pending point of a partial results.nc has made no runs that count yet
    finished = int((results["status"] != "pending").sum()) if "status" in results else 0
    points = max(1, finished or int(results["n_runs"].size))
    parts = ", ".join(
        f"{role} {float(results[f'runs_{role}'].sum()) / points:.3g}" for role in RUN_ROLES
    )
    return f"runs per point: {float(results['n_runs'].sum()) / points:.3g} ({parts})"
