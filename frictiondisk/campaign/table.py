"""The answer of a find_jump campaign as text: one line per point with mu*, its bracket,
the runs it took and its status (printed by `frictiondisk status`, hence by `make demo`)."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr


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
    stacked = results[["mu_star", "mu_lo", "mu_hi", "n_runs", "status"]]
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
        )
    heads += ["mu*", "bracket [mu_lo, mu_hi]", "runs", "status"]
    widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(heads)]
    tol = results.attrs.get("tol")
    title = f"mu* per point (bracket width <= tol {float(tol):g}):" if tol else "mu* per point:"
    lines = [
        "  " + "  ".join(f"{c:<{w}}" for c, w in zip(r, widths, strict=True))
        for r in [heads, *rows]
    ]
    return [title, *(line.rstrip() for line in lines)]
