"""The figure of a find_jump campaign over two keys: `plot_jump_grid`.

mu* as a coloured map with a colour bar, each cell labelled with its value, failed cells
hatched, numbered and listed with their reasons, non-monotone cells ringed; optionally each
cell's run count.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.patches import Patch, Rectangle

from frictiondisk.figures.shared import (
    FAIL_COLOR,
    MAX_LISTED,
    NON_MONOTONE_COLOR,
    add_note,
    axis_label,
    boundary_sides,
    cell_edges,
    legend_above,
    new_figure,
    scene_title,
    searched_key,
)
from frictiondisk.figures.style import styled
from frictiondisk.tasks.find_jump.figure_kind import figure_kind
from frictiondisk.tasks.find_jump.figure_layers import (
    failed_and_without,
    failure_lines,
    no_jump_label,
    point_labels,
)

NO_JUMP_FACE = "#eeeeee"  # a cell without a jump on its grid (mu* above it)


@styled
def plot_jump_grid(
    results: xr.Dataset, runs: xr.Dataset | None = None, *, show_runs: bool = False
) -> Figure:
    """mu* over the two varied keys of a find_jump campaign, as a coloured map.

    The first key is the x axis, the second the y axis; each cell shows its mu*. Failed
    cells are hatched red, numbered and listed with their reasons; non-monotone cells are
    ringed. `show_runs` adds each cell's run count (a map has no axis for the mu of a run;
    the runs themselves are in runs.nc). `runs` is accepted for symmetry with
    `plot_jump_line`.
    """
    if figure_kind(results) != "jump_grid":
        raise ValueError("plot_jump_grid needs a find_jump result over two keys")
    dim_x, dim_y = results["mu_star"].dims
    cx, cy = results[dim_x], results[dim_y]
    ix, iy = np.argsort(cx.values), np.argsort(cy.values)
    xs, ys = np.asarray(cx.values, float)[ix], np.asarray(cy.values, float)[iy]
    cells = np.ix_(ix, iy)
    mu_star = np.asarray(results["mu_star"].values, float)[cells]
    failed_all, without_all = failed_and_without(results)
    failed, without = failed_all[cells], without_all[cells]

    failed_in_order = failed_all.reshape(-1)  # C order
    fail_lines = failure_lines(results, point_labels(results), failed_in_order)
    fig, main, note = new_figure(results, 7.2, 5.4, len(fail_lines) + 1 if fail_lines else 0)
    ax = main.add_subplot()
    ex, ey = cell_edges(xs), cell_edges(ys)
    shown = np.ma.masked_invalid(np.where(failed, np.nan, mu_star))
    mesh = ax.pcolormesh(ex, ey, shown.T, cmap="viridis", shading="flat", zorder=1)
    mesh.set_gid("mu_star")
    cbar = main.colorbar(mesh, ax=ax)
    key = searched_key(results)
    cbar.set_label(f"{key.star} [{key.unit}]: {grid_title(results)}")
    tol = results.attrs.get("tol")
    digits = max(2, math.ceil(-math.log10(float(tol))) + 1) if tol else 4

    # number failed cells in the order of the list (the Dataset's C order)
    flat_failed = np.flatnonzero(failed_in_order)
    number = {int(i): k for k, i in enumerate(flat_failed[:MAX_LISTED], start=1)}
    n_runs = np.asarray(results["n_runs"].values)[cells] if "n_runs" in results else None
    monotone = np.asarray(results["monotone"].values).astype(int)[cells]
    for a in range(xs.size):
        for b in range(ys.size):
            box = (ex[a], ey[b], ex[a + 1], ey[b + 1])  # the cell's edges
            if failed[a, b]:
                k = number.get(int(ix[a]) * cy.size + int(iy[b]))
                lines, color = [f"[{k}]" if k else "failed"], FAIL_COLOR
            else:
                lines, color = _cell_value(ax, box, without[a, b], mu_star[a, b], mesh.norm, digits)
            if show_runs and n_runs is not None:
                lines.append(f"{int(n_runs[a, b])} runs")
            _draw_cell(ax, box, lines, color, failed[a, b], xs.size * ys.size <= 150)
            if monotone[a, b] == 0 and not failed[a, b] and not without[a, b]:
                _ring(ax, box, NON_MONOTONE_COLOR, 2.0, "non_monotone", zorder=4)
    handles = _legend_entries(results, failed, without, monotone)
    if handles:
        legend_above(ax, handles, len(handles))
    ax.set_xlim(ex[0], ex[-1])
    ax.set_ylim(ey[0], ey[-1])
    ax.set_xlabel(axis_label(cx))
    ax.set_ylabel(axis_label(cy))
    tol_text = f" (bracket width <= {float(tol):g}{key.unit_suffix})" if tol else ""
    main.suptitle(f"{scene_title(results)}: {grid_title(results)}{tol_text}", wrap=True)
    if note is not None:
        add_note(note, fail_lines, f"failed points ({int(failed.sum())}):")
    return fig


def grid_title(results: xr.Dataset) -> str:
    """ "jump friction coefficient \u03bc*" (the stick jump), or "boundary \u03c9_m* from A
    below to B above" (`between`, the bisected key's symbol)."""
    key = searched_key(results)
    sides = boundary_sides(results)
    if sides is None:
        what = "friction coefficient " if key.key == "params.mu" else ""
        return f"jump {what}{key.star}"
    return f"boundary {key.star} from {sides[0]} below to {sides[1]} above"


def _ring(ax, box, edge: str, width: float, gid: str, zorder: int, **style: Any) -> None:
    """A rectangle over one cell `box` (x_lo, y_lo, x_hi, y_hi)."""
    x, y, x_hi, y_hi = box
    w, h = x_hi - x, y_hi - y
    face = style.pop("facecolor", "none")
    ax.add_patch(
        Rectangle(
            (x, y),
            w,
            h,
            facecolor=face,
            edgecolor=edge,
            linewidth=width,
            zorder=zorder,
            gid=gid,
            **style,
        )
    )


def _cell_value(ax, box, without: bool, mu: float, norm, digits: int) -> tuple[list[str], str]:
    """A converged cell's text (its mu*) and colour; a cell without a jump greyed."""
    if without:
        _ring(ax, box, "0.6", 0.6, "no_jump_cell", zorder=2, facecolor=NO_JUMP_FACE)
        return ["no jump"], "black"
    shade = norm(mu)
    return [f"{mu:.{digits}f}"], "black" if np.ma.is_masked(shade) or shade > 0.55 else "white"


def _draw_cell(ax, box, lines: list[str], color: str, failed: bool, labelled: bool) -> None:
    """A failed cell hatched red; the text of any cell at its centre (if `labelled`)."""
    x_lo, y_lo, x_hi, y_hi = box
    if failed:
        _ring(ax, box, FAIL_COLOR, 0.6, "failed_cell", zorder=2, facecolor="#fde0dd", hatch="xx")
    if labelled:
        ax.text(
            0.5 * (x_lo + x_hi),
            0.5 * (y_lo + y_hi),
            "\n".join(lines),
            ha="center",
            va="center",
            fontsize="x-small",
            color=color,
            zorder=3,
            bbox={"boxstyle": "round,pad=0.15", "facecolor": "white", "edgecolor": "none"}
            if failed
            else None,
        )


def _legend_entries(results, failed, without, monotone) -> list[Any]:
    """Legend entries of the kinds of cells the map shows."""
    handles: list[Any] = []
    if failed.any():
        handles.append(
            Patch(facecolor="#fde0dd", edgecolor=FAIL_COLOR, hatch="xx", label="failed (listed)")
        )
    if without.any():
        handles.append(Patch(facecolor=NO_JUMP_FACE, edgecolor="0.6", label=no_jump_label(results)))
    if (monotone == 0).any():
        handles.append(
            Patch(
                facecolor="none",
                edgecolor=NON_MONOTONE_COLOR,
                linewidth=2,
                label="non-monotone: a run contradicts a single jump",
            )
        )
    return handles
