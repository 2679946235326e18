"""The answer of a basin campaign as text (`summary_lines`), printed by `run` and by
`status` of a stopped campaign: one line per point, or the shares of a map."""

from __future__ import annotations

import xarray as xr

from frictiondisk.store.tables import coordinate_specs
from frictiondisk.tasks.basin.sampling import STICK


def summary_lines(results: xr.Dataset) -> list[str]:
    """One line per point of a basin results.nc: the stick and not-stick fractions with
    their 95 % Wilson intervals and n (a map: the fraction of cells of each outcome)."""
    outcomes = [str(o) for o in results["outcome"].values]
    if results.attrs.get("basin_mode") == "map":
        shares = ", ".join(
            f"{o} {float(f):.3f}"
            for o, f in zip(outcomes, results["fraction"].values, strict=True)
            if f > 0
        )
        return [f"basin map, {int(results['n_samples'])} cells: {shares}"]
    dims = list(results["n_samples"].dims)
    specs = coordinate_specs(results, dims)  # neighbouring grid values print apart
    stacked = results.stack(point=dims) if dims else results.expand_dims("point")
    lines = []
    for k in range(stacked.sizes["point"]):
        row = stacked.isel(point=k)
        where = (
            ", ".join(f"{d} = {float(row[d]):{f}}" for d, f in zip(dims, specs, strict=True))
            or "basin"
        )
        if int(row.n_samples) == 0:  # partial results: this point has not finished
            lines.append(f"{where}: {row.status.values.item()}")
            continue
        stick = row.sel(outcome=STICK)
        lines.append(
            f"{where}: stick {float(stick.fraction):.4f} "
            f"[{float(stick.fraction_lo):.4f}, {float(stick.fraction_hi):.4f}], "
            f"not stick {float(row.not_stick_fraction):.4f} "
            f"[{float(row.not_stick_lo):.4f}, {float(row.not_stick_hi):.4f}] "
            f"(95 % Wilson), n = {int(row.n_samples)}"
        )
    return lines
