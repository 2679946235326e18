"""Campaign figures: results.nc / runs.nc Datasets in, matplotlib Figures out.

Which figure a campaign gets follows from its results alone (`figure_kind`):

- ``jump_line``: `find_jump` along one scene key, the paper's Figs 9-11: mu* against the key,
  every point with its bracket [mu_lo, mu_hi] as an error bar, the regions "pure sticking"
  (above the line) and "outer limit cycle" (below) labelled, failed points marked at the
  bottom of the axes and listed with their reasons, non-monotone points ringed.
- ``jump_grid``: `find_jump` over two scene keys: mu* as a coloured map with a colour bar,
  failed cells hatched and listed.
- ``scan_mu``: `scan` of mu alone, the paper's Figs 6-7: `size` against mu coloured by outcome
  (top) and the deviation `a` of the converged stick-slip cycles with its least-squares line
  (bottom; the paper finds a linear in mu).
- ``scan_family``: `scan` of mu and one more key: one `size` curve per value of that key.
- ``trace``: the jump curves of a (key, mu) plane, their sticking sides shaded, folds marked
  (trace.py).

For find_jump figures `show_runs=True` overlays every run of runs.nc (paper Fig 7, middle
panel: how the jump was iterated): dots at (coordinate, mu), stick dark, not stick light,
undetermined red. A grid has no room for the mu of each run; its cells show their run count.

Every figure carries a caption line (campaign, task, tolerance, numerics, versions).

This module dispatches (`plot_campaign`) and names the public figure API (`__all__`); each family is
drawn in its own module: kind.py (`figure_kind`), jump_line.py, jump_grid.py, scan.py,
size.py (``jump_sizes``) and trace.py, with what they share in shared.py. Like
`frictiondisk.figures.plotting`, none of them selects a backend, touches pyplot, imports
the kernel or simulates: figures are `matplotlib.figure.Figure` objects, saved with
`frictiondisk.figures.plotting.save_figure`.
"""

from __future__ import annotations

import xarray as xr
from matplotlib.figure import Figure

from frictiondisk.figures.jump_grid import plot_jump_grid
from frictiondisk.figures.jump_line import plot_jump_line
from frictiondisk.figures.kind import FIGURE_KINDS, figure_kind
from frictiondisk.figures.scan import plot_scan_family, plot_scan_mu
from frictiondisk.figures.shared import MU_LABEL, axis_label, caption_text
from frictiondisk.figures.style import styled

__all__ = [
    "FIGURE_KINDS",
    "MU_LABEL",
    "axis_label",
    "caption_text",
    "figure_kind",
    "plot_campaign",
    "plot_jump_grid",
    "plot_jump_line",
    "plot_scan_family",
    "plot_scan_mu",
]


# ---- dispatch ---------------------------------------------------------------------------
@styled
def plot_campaign(
    results: xr.Dataset, runs: xr.Dataset | None = None, *, show_runs: bool = False
) -> Figure:
    """The figure that fits a campaign's results (see `figure_kind`).

    `results` is results.nc, `runs` runs.nc (needed only for `show_runs`). `show_runs`
    overlays every run on a find_jump figure; a scan's runs are its points already, so
    there it changes nothing.
    """
    kind = figure_kind(results)
    if kind == "trace":
        from frictiondisk.figures.trace import plot_trace

        return plot_trace(results, runs, show_runs=show_runs)
    if kind == "jump_sizes":
        from frictiondisk.figures.size import plot_jump_sizes

        return plot_jump_sizes(results, runs if show_runs else None)
    if kind == "jump_line":
        return plot_jump_line(results, runs, show_runs=show_runs)
    if kind == "jump_grid":
        return plot_jump_grid(results, runs, show_runs=show_runs)
    if kind == "scan_mu":
        return plot_scan_mu(results)
    return plot_scan_family(results)
