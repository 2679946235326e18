"""Which figure fits a find_jump campaign's results (`figure_kind`), read from results.nc
alone: a line along one key (jump_line), a map over two (jump_grid), or the sizes against
mu of a converge-mode prescan along one key (jump_sizes). Nothing here draws."""

from __future__ import annotations

import xarray as xr

from frictiondisk.figures.shared import check_vars

FIGURE_KINDS = ("jump_line", "jump_grid", "jump_sizes")
JUMP_VARS = ("mu_star", "mu_lo", "mu_hi", "status", "reason", "monotone")


def figure_kind(results: xr.Dataset) -> str:
    """One of FIGURE_KINDS; ValueError (saying what is wrong) for results it cannot draw."""
    check_vars(results, JUMP_VARS, "results (find_jump)")
    dims = list(results["mu_star"].dims)  # a prescan adds the dims jump and scan_mu
    if len(dims) == 1 and results.attrs.get("prescan_mode") == "converge":
        return "jump_sizes"
    if len(dims) == 1:
        return "jump_line"
    if len(dims) == 2:
        return "jump_grid"
    raise ValueError(f"a find_jump result varies 1 or 2 keys, this one {len(dims)}: {dims}")
