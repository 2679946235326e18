"""Text tables of a campaign's results.nc, for `run` and `status` (each task's table
lines are in its package, table.py): the rows of a per-point variable, aligned columns,
the reasons under a table, numbers and CF flags as text."""

from __future__ import annotations

import math

import xarray as xr

from frictiondisk.store.cf import flag_meanings


def unit_text(coord: xr.DataArray) -> str:
    """' [unit]' of a variable with a unit other than 1; '' else."""
    unit = str(coord.attrs.get("units", "")).strip()
    return "" if unit in ("", "1") else f" [{unit}]"


def point_rows(results: xr.Dataset, names: list[str]) -> list[tuple[tuple, xr.Dataset]]:
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


def number(value: float, spec: str) -> str:
    """`value` formatted with `spec`; '-' if it is not finite."""
    return f"{value:{spec}}" if math.isfinite(value) else "-"


def columns(heads: list[str], rows: list[list[str]]) -> list[str]:
    """The lines of a table: heads and rows left-aligned in columns, indented two spaces."""
    widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(heads)]
    lines = [
        "  " + "  ".join(f"{c:<{w}}" for c, w in zip(r, widths, strict=True))
        for r in [heads, *rows]
    ]
    return [line.rstrip() for line in lines]


def reasons(title: str, dims: list[str], which: list[tuple[tuple, str]]) -> list[str]:
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


def flag_text(var: xr.DataArray, value) -> str:
    """The meaning of one CF flag value of `var`."""
    code = int(value)
    return flag_meanings(var).get(code, str(code))


def head_of(results: xr.Dataset, dim: str) -> str:
    """A column head: the dimension's name and unit."""
    return f"{dim}{unit_text(results[dim])}"
