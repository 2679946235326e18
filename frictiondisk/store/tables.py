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


MU_DECIMALS = 6  # decimals of a mu in a table at least (tol 1e-4 and coarser: today's look)


def mu_decimals(tol: float | None) -> int:
    """Decimals that show a mu to two places below the tol's (tol 1e-8 -> 10, 2e-5 -> 7,
    1e-4 -> 6), never fewer than MU_DECIMALS; MU_DECIMALS without a finite tol."""
    if tol is None or not math.isfinite(tol) or tol <= 0:
        return MU_DECIMALS
    place = -math.floor(math.log10(tol) + 1e-9)  # 1e-8 -> 8 (log10 may round below)
    return max(MU_DECIMALS, place + 2)


def distinct_spec(values) -> str:
    """The shortest `.Ng` (N >= 6, i.e. `g`'s own) that prints distinct values
    distinctly: a grid step of 1e-8 in mu shows, a step of 0.025 keeps `g`'s look."""
    finite = {float(v) for v in values if math.isfinite(float(v))}
    for digits in range(6, 18):
        if len({f"{v:.{digits}g}" for v in finite}) == len(finite):
            return f".{digits}g"
    return ".17g"


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


def reasons(
    title: str, dims: list[str], which: list[tuple[tuple, str]], specs: list[str] | None = None
) -> list[str]:
    """`title`, then one line `  dim = value, ...: reason` per point of `which` (each
    coordinate in its spec of `specs`, `g` by default)."""
    if not which:
        return []
    specs = specs or ["g"] * len(dims)
    where = [
        ", ".join(f"{d} = {c:{f}}" for d, c, f in zip(dims, coords, specs, strict=True))
        for coords, _ in which
    ]
    return [
        title,
        *(f"  {w or 'the point'}: {reason}" for w, (_, reason) in zip(where, which, strict=True)),
    ]


def flag_text(var: xr.DataArray, value) -> str:
    """The meaning of one CF flag value of `var`."""
    code = int(value)
    return flag_meanings(var).get(code, str(code))


def coordinate_specs(results: xr.Dataset, dims: list[str]) -> list[str]:
    """The spec of each dimension's coordinate in a table (distinct_spec of its values)."""
    return [distinct_spec(results[d].values.ravel()) for d in dims]


def head_of(results: xr.Dataset, dim: str) -> str:
    """A column head: the dimension's name and unit."""
    return f"{dim}{unit_text(results[dim])}"
