"""The answer of a find_jump campaign as text: one line per point with mu*, its bracket,
the runs it took, its status and certification (printed by `frictiondisk status`, hence
by `make demo`), and the one-line summary of uncertain points."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from frictiondisk.search.jumps import RUN_ROLES
from frictiondisk.store.cf import flag_meanings
from frictiondisk.store.trace_table import trace_closing


def _unit(coord: xr.DataArray) -> str:
    unit = str(coord.attrs.get("units", "")).strip()
    return "" if unit in ("", "1") else f" [{unit}]"


def mu_star_table(results: xr.Dataset) -> list[str]:
    """Lines of the mu* table of a find_jump results.nc; [] for any other task."""
    if results.attrs.get("task") != "find_jump" or "mu_star" not in results:
        return []
    dims = list(results["mu_star"].dims)
    heads = [f"{d}{_unit(results[d])}" for d in dims]
    rows = []
    names = ["mu_star", "mu_lo", "mu_hi", "n_runs", "status"]
    certified = "certification" in results
    stacked = results[names + (["certification"] if certified else [])]
    if len(dims) > 1:
        stacked = stacked.stack(point=dims)
    elif dims:
        stacked = stacked.rename({dims[0]: "point"}).assign_coords(point=results[dims[0]].values)
    jumps = results.get("jump_mu_star")
    for i in range(stacked.sizes.get("point", 1)):
        row = stacked.isel(point=i) if dims else stacked
        coords = row["point"].values.item() if dims else ()
        coords = coords if isinstance(coords, tuple) else (coords,)
        mu, lo, hi = (float(row[v]) for v in ("mu_star", "mu_lo", "mu_hi"))
        bracket = f"[{lo:.6f}, {hi:.6f}]" if math.isfinite(lo) and math.isfinite(hi) else "-"
        extra = ""
        if jumps is not None:
            n = int(np.isfinite(jumps.values.reshape(-1, jumps.shape[-1])[i]).sum())
            extra = f" ({n} jumps)" if n > 1 else ""
        rows.append(
            [f"{c:g}" for c in coords]
            + [f"{mu:.6f}" if math.isfinite(mu) else "-", bracket, str(int(row["n_runs"]))]
            + [f"{row['status'].values.item()}{extra}"]
            + ([_flag(results["certification"], row["certification"])] if certified else [])
        )
    heads += ["mu*", "bracket [mu_lo, mu_hi]", "runs", "status"]
    heads += ["certification"] if certified else []
    widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(heads)]
    tol = results.attrs.get("tol")
    title = f"mu* per point (bracket width <= tol {float(tol):g}):" if tol else "mu* per point:"
    lines = [
        "  " + "  ".join(f"{c:<{w}}" for c, w in zip(r, widths, strict=True))
        for r in [heads, *rows]
    ]
    return [title, *(line.rstrip() for line in lines)]


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
