"""Which figure fits a campaign's results (`figure_kind`), read from results.nc alone.

The figure modules (jump_line.py, jump_grid.py, scan.py) check their input with it and
campaign.py dispatches on it; it also checks that a Dataset holds the variables a figure
reads. Nothing here draws.
"""

from __future__ import annotations

import xarray as xr

FIGURE_KINDS = (
    "jump_line",
    "jump_grid",
    "jump_sizes",
    "scan_mu",
    "scan_family",
    "trajectory",
    "trace",
)

_JUMP_VARS = ("mu_star", "mu_lo", "mu_hi", "status", "reason", "monotone")
_SCAN_VARS = ("outcome", "reason", "size", "a")


# ---- what the Dataset holds -------------------------------------------------------------
def _check_vars(ds: xr.Dataset, names: tuple[str, ...], what: str) -> None:
    missing = [name for name in names if name not in ds.variables]
    if missing:
        raise ValueError(
            f"{what} lacks the variable(s) {', '.join(missing)}: "
            "not written by this version of frictiondisk?"
        )


def _mu_dim(ds: xr.Dataset) -> str | None:
    """The dimension of a scan that varies mu (scene key params.mu), or None."""
    for dim in ds.dims:
        if dim in ds.coords and ds[dim].attrs.get("scene_key") == "params.mu":
            return str(dim)
    return "mu" if "mu" in ds.dims else None


def figure_kind(results: xr.Dataset) -> str:
    """Which figure fits these results: one of `FIGURE_KINDS`.

    ValueError (with what is wrong) for a Dataset that is not a campaign's results.nc.
    """
    task = results.attrs.get("task")
    dims = list(results.dims)
    if task == "find_jump":
        _check_vars(results, _JUMP_VARS, "results (find_jump)")
        dims = list(results["mu_star"].dims)  # a prescan adds the dims jump and scan_mu
        if len(dims) == 1 and results.attrs.get("prescan_mode") == "converge":
            return "jump_sizes"
        if len(dims) == 1:
            return "jump_line"
        if len(dims) == 2:
            return "jump_grid"
        raise ValueError(f"a find_jump result varies 1 or 2 keys, this one {len(dims)}: {dims}")
    if task == "scan":
        _check_vars(results, _SCAN_VARS, "results (scan)")
        mu_dim = _mu_dim(results)
        if mu_dim is None:
            raise ValueError(f"a scan result varies mu, this one varies only {dims}")
        if len(dims) == 1:
            return "scan_mu"
        if len(dims) == 2:
            return "scan_family"
        raise ValueError(f"a scan varies mu and at most one more key, this one {dims}")
    if task == "trajectory":
        return "trajectory"
    if task == "trace":
        return "trace"
    raise ValueError(
        f"results attribute 'task' is {task!r}; expected 'find_jump', 'scan', 'trajectory' "
        "or 'trace' (not a frictiondisk campaign result?)"
    )
