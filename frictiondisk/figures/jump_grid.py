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

from frictiondisk.figures.kind import figure_kind
from frictiondisk.figures.shared import (
    FAIL_COLOR,
    MAX_LISTED,
    NON_MONOTONE_COLOR,
    _add_note,
    _failure_lines,
    _point_labels,
    axis_label,
    failed_and_without,
    fitted_legend,
    new_figure,
    no_jump_label,
    scene_title,
)
from frictiondisk.figures.style import styled

NO_JUMP_FACE = "#eeeeee"  # a cell without a jump on its grid (mu* above it)


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges around sorted centres: midpoints, half a step beyond the ends."""
    v = np.asarray(values, dtype=float)
    if v.size == 1:
        half = 0.5 * (abs(v[0]) or 1.0)
        return np.array([v[0] - half, v[0] + half])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])


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
    mu_star = np.asarray(results["mu_star"].values, float)[np.ix_(ix, iy)]
    monotone = np.asarray(results["monotone"].values).astype(int)[np.ix_(ix, iy)]
    n_runs = np.asarray(results["n_runs"].values)[np.ix_(ix, iy)] if "n_runs" in results else None
    failed_all, without_all = failed_and_without(results)
    failed, without = failed_all[np.ix_(ix, iy)], without_all[np.ix_(ix, iy)]

    labels = _point_labels(results)
    failed_in_order = failed_all.reshape(-1)  # C order
    fail_lines = _failure_lines(results, labels, failed_in_order)
    fig, main, note = new_figure(results, 7.2, 5.4, len(fail_lines) + 1 if fail_lines else 0)
    ax = main.add_subplot()
    ex, ey = _edges(xs), _edges(ys)
    shown = np.ma.masked_invalid(np.where(failed, np.nan, mu_star))
    mesh = ax.pcolormesh(ex, ey, shown.T, cmap="viridis", shading="flat", zorder=1)
    mesh.set_gid("mu_star")
    cbar = main.colorbar(mesh, ax=ax)
    cbar.set_label("jump friction coefficient \u03bc* [-]")
    tol = results.attrs.get("tol")
    digits = max(2, math.ceil(-math.log10(float(tol))) + 1) if tol else 4

    # number failed cells in the order of the list (the Dataset's C order)
    flat_failed = np.flatnonzero(failed_in_order)
    number = {int(i): k for k, i in enumerate(flat_failed[:MAX_LISTED], start=1)}
    norm = mesh.norm
    handles: list[Any] = []
    for a in range(xs.size):
        for b in range(ys.size):
            x_lo, x_hi, y_lo, y_hi = ex[a], ex[a + 1], ey[b], ey[b + 1]
            xc, yc = 0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi)
            lines = []
            if failed[a, b]:
                ax.add_patch(
                    Rectangle(
                        (x_lo, y_lo),
                        x_hi - x_lo,
                        y_hi - y_lo,
                        facecolor="#fde0dd",
                        edgecolor=FAIL_COLOR,
                        hatch="xx",
                        linewidth=0.6,
                        zorder=2,
                        gid="failed_cell",
                    )
                )
                original = int(ix[a]) * cy.size + int(iy[b])
                k = number.get(original)
                lines.append(f"[{k}]" if k else "failed")
                color = FAIL_COLOR
            elif without[a, b]:
                ax.add_patch(
                    Rectangle(
                        (x_lo, y_lo),
                        x_hi - x_lo,
                        y_hi - y_lo,
                        facecolor=NO_JUMP_FACE,
                        edgecolor="0.6",
                        linewidth=0.6,
                        zorder=2,
                        gid="no_jump_cell",
                    )
                )
                lines.append("no jump")
                color = "black"
            else:
                lines.append(f"{mu_star[a, b]:.{digits}f}")
                shade = norm(mu_star[a, b])
                color = "black" if np.ma.is_masked(shade) or shade > 0.55 else "white"
            if show_runs and n_runs is not None:
                lines.append(f"{int(n_runs[a, b])} runs")
            if xs.size * ys.size <= 150:
                ax.text(
                    xc,
                    yc,
                    "\n".join(lines),
                    ha="center",
                    va="center",
                    fontsize="x-small",
                    color=color,
                    zorder=3,
                    bbox={"boxstyle": "round,pad=0.15", "facecolor": "white", "edgecolor": "none"}
                    if failed[a, b]
                    else None,
                )
            if monotone[a, b] == 0 and not failed[a, b] and not without[a, b]:
                ax.add_patch(
                    Rectangle(
                        (x_lo, y_lo),
                        x_hi - x_lo,
                        y_hi - y_lo,
                        facecolor="none",
                        edgecolor=NON_MONOTONE_COLOR,
                        linewidth=2.0,
                        zorder=4,
                        gid="non_monotone",
                    )
                )
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
    if handles:
        fitted_legend(
            ax,
            len(handles),
            handles=handles,
            loc="lower left",
            bbox_to_anchor=(0.0, 1.01),
            fontsize="small",
            frameon=False,
        )
    ax.set_xlim(ex[0], ex[-1])
    ax.set_ylim(ey[0], ey[-1])
    ax.set_xlabel(axis_label(cx))
    ax.set_ylabel(axis_label(cy))
    tol_text = f" (bracket width <= {float(tol):g})" if tol else ""
    main.suptitle(f"{scene_title(results)}: jump coefficient \u03bc*{tol_text}")
    if note is not None:
        _add_note(note, fail_lines, f"failed points ({int(failed.sum())}):")
    return fig
