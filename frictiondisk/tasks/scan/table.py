"""The answer of a scan campaign as text, printed by `run` and `status`: the outcome, size
and a per point, then the reason of each undetermined point."""

from __future__ import annotations

import xarray as xr

from frictiondisk.store.partial import PENDING
from frictiondisk.store.tables import (
    columns,
    coordinate_specs,
    head_of,
    number,
    point_rows,
    reasons,
)
from frictiondisk.verdict.outcomes import UNDETERMINED


def scan_table(results: xr.Dataset) -> list[str]:
    """Lines of the table (a pending point of a partial file: `pending`); [] without
    outcomes."""
    if "outcome" not in results:
        return []
    dims = list(results["outcome"].dims)
    names = [name for name in ("outcome", "size", "a", "reason") if name in results]
    specs = coordinate_specs(results, dims)  # a grid step of 1e-8 in mu shows
    rows, undetermined = [], []
    for coords, row in point_rows(results, names):
        outcome = str(row["outcome"].values.item()) or PENDING
        # one column per measure the file has (as the heads below)
        measures = [number(float(row[m]), ".4g") for m in ("size", "a") if m in results]
        rows.append([f"{c:{f}}" for c, f in zip(coords, specs, strict=True)] + [outcome, *measures])
        if outcome == UNDETERMINED and "reason" in row:
            undetermined.append((coords, str(row["reason"].values.item())))
    heads = [head_of(results, d) for d in dims]
    heads += ["outcome", *(head_of(results, m) for m in ("size", "a") if m in results)]
    return [
        "outcome per point:",
        *columns(heads, rows),
        *reasons(f"undetermined points ({len(undetermined)}), why:", dims, undetermined, specs),
    ]
