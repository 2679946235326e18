"""Where two motions coexist: a boundary that depends on the start. Pure xarray.

A find_jump over a boundary between two motions (`between`, not the default stick jump)
whose `along` holds an initial-state key locates the boundary once per start. Where the
starts' mu* differ by more than the tolerance, both motions are reached between them
(hysteresis: a fold of one of the branches lies inside the band), and results.nc says so:
`coexist_lo` and `coexist_hi` over the other keys (NaN: no band found), and the
`coexistence` attribute in words. Where a point's own search found several jumps (a
window of B inside A, or A inside B), its reason lists them.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from frictiondisk.model.varied import INITIAL_STATE_KEYS


def coexistence_vars(ds: xr.Dataset, between: str, tol: float) -> dict:
    """`coexist_lo`, `coexist_hi` over the dims that are not initial-state keys, and the
    `coexistence` text ({} without an initial-state dim)."""
    starts = [d for d in ds["mu_star"].dims if ds[d].attrs.get("scene_key") in INITIAL_STATE_KEYS]
    if not starts:
        return {}
    star = ds["mu_star"].where(ds["status"] == "converged")
    lo, hi = star.min(starts), star.max(starts)
    band = (hi - lo) > tol
    attrs = {"units": "1"}
    out = {
        "coexist_lo": lo.where(band).assign_attrs(
            attrs, long_name=f"lowest mu* over the starts ({between}): both reached above"
        ),
        "coexist_hi": hi.where(band).assign_attrs(
            attrs, long_name=f"highest mu* over the starts ({between}): both reached below"
        ),
    }
    names = ", ".join(starts)
    if not bool(band.any()):
        text = f"{between}: one boundary for every start ({names}) within tol {tol:g}"
    else:
        text = (
            f"{between}: the boundary depends on the start ({names}); both motions are "
            f"reached between coexist_lo and coexist_hi at {int(band.sum())} of "
            f"{band.size} points (hysteresis)"
        )
    return {"vars": out, "text": text}


def with_coexistence(ds: xr.Dataset, between: str, tol: float) -> xr.Dataset:
    """ds with the coexistence variables and attribute (unchanged without a start dim)."""
    found = coexistence_vars(ds, between, tol)
    if not found:
        return ds
    ds = ds.assign(found["vars"])
    ds.attrs["coexistence"] = found["text"]
    return ds


def coexistence_lines(ds: xr.Dataset) -> list[str]:
    """What `run` prints of it: the attribute, then each band."""
    if "coexistence" not in ds.attrs:
        return []
    lines = [f"coexistence: {ds.attrs['coexistence']}"]
    if "coexist_lo" in ds:
        lo, hi = ds["coexist_lo"], ds["coexist_hi"]
        stacked = lo.expand_dims("_").stack(point=[*lo.dims, "_"]) if lo.dims else None
        if stacked is None:
            if np.isfinite(float(lo)):
                lines.append(f"  both reached for mu in [{float(lo):.6g}, {float(hi):.6g}]")
            return lines
        for k in range(stacked.sizes["point"]):
            row_lo = stacked.isel(point=k)
            if not np.isfinite(float(row_lo)):
                continue
            where = ", ".join(f"{d} = {float(row_lo[d]):.6g}" for d in lo.dims)
            row_hi = hi.sel({d: row_lo[d] for d in lo.dims})
            lines.append(
                f"  {where}: both reached for mu in [{float(row_lo):.6g}, {float(row_hi):.6g}]"
            )
    return lines
