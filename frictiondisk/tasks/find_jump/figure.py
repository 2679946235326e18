"""The figure of a find_jump campaign (`plot_find_jump`), read from results.nc (and
runs.nc to show the runs): mu* along one key (figure_line.py, paper Figs 9-11), a map of
mu* over two (figure_grid.py), or the sizes against mu of a converge-mode prescan
(figure_sizes.py, paper Figs 7-8); `figure_kind` says which."""

from __future__ import annotations

import xarray as xr
from matplotlib.figure import Figure

from frictiondisk.tasks.find_jump.figure_grid import plot_jump_grid
from frictiondisk.tasks.find_jump.figure_kind import figure_kind
from frictiondisk.tasks.find_jump.figure_line import plot_jump_line
from frictiondisk.tasks.find_jump.figure_sizes import plot_jump_sizes


def plot_find_jump(
    results: xr.Dataset, runs: xr.Dataset | None = None, *, show_runs: bool = False
) -> Figure:
    """The figure that fits a find_jump's results; `show_runs` overlays every run of `runs`
    (a grid shows each cell's run count instead)."""
    kind = figure_kind(results)
    if kind == "jump_sizes":
        return plot_jump_sizes(results, runs if show_runs else None)
    if kind == "jump_line":
        return plot_jump_line(results, runs, show_runs=show_runs)
    return plot_jump_grid(results, runs, show_runs=show_runs)
