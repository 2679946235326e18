"""The figure of a map campaign: its results.nc in, a matplotlib Figure out.

Every cell coloured by its motion (the colours of frictiondisk.figures.outcome_colors:
the campaign figures' colours, then a fixed palette for any outcome they do
not know), one legend for all motions with the share of cells of each; the cells that ran
are marked with a dot (the others are inferred from a uniform block of the refinement), a
cross where a converge-mode run had not settled (sticking is settled by its own rule). A map over one key is one coloured strip.

Like every figure: no backend, no pyplot, no kernel.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
import xarray as xr
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from frictiondisk.figures.curves import curve_points
from frictiondisk.figures.outcome_colors import outcome_colors
from frictiondisk.figures.shared import (
    axis_label,
    cell_edges,
    check_vars,
    legend_above,
    new_figure,
)
from frictiondisk.figures.style import styled
from frictiondisk.tasks.map.table import settled_flags

_VARS = ("motion", "ran", "cycle_converged", "cell_fraction")
_TRACE_VARS = ("mu_star", "curve_first_point", "curve_points")  # what curve_points reads
# a traced boundary's line: (line style, marker); drawn in black over any cell colour
BOUNDARY_STYLES = (("-", "o"), ("--", "s"), (":", "^"), ("-.", "D"))


@styled
def plot_map(results: xr.Dataset, boundaries: tuple[xr.Dataset, ...] = ()) -> Figure:
    """The motion of every cell of a map results.nc (see the module docstring);
    `boundaries`: trace results.nc over the map's two keys, whose curves are drawn on top."""
    check_vars(results, _VARS, "results (map)")
    outcomes = [str(o) for o in results["outcome"].values]
    colors = outcome_colors(outcomes)
    motion = results["motion"]
    dims = list(motion.dims)
    # the caption names the map's own numerics.mode (the base scene's may differ)
    fig, main, _ = new_figure(results, 7.2, 5.2, 0, results.attrs.get("mode"))
    ax = main.add_subplot()
    code = {o: k for k, o in enumerate(outcomes)}
    values = np.vectorize(lambda o: code.get(str(o), -1), otypes=[float])(motion.values)
    values[values < 0] = np.nan  # pending: left blank
    cmap = ListedColormap([colors[o] for o in outcomes])
    norm = BoundaryNorm(np.arange(len(outcomes) + 1) - 0.5, len(outcomes))
    xs = np.asarray(results[dims[0]].values, float)
    ix = np.argsort(xs)
    if len(dims) == 1:
        ys, iy = np.array([0.5]), np.array([0])
        grid = values[ix][:, None]
        y_edges = np.array([0.0, 1.0])
        ax.set_yticks([])
    else:
        ys = np.asarray(results[dims[1]].values, float)
        iy = np.argsort(ys)
        grid = values[np.ix_(ix, iy)]
        y_edges = cell_edges(ys[iy])
        ax.set_ylabel(axis_label(results[dims[1]]))
    mesh = ax.pcolormesh(cell_edges(xs[ix]), y_edges, grid.T, cmap=cmap, norm=norm)
    mesh.set_gid("motion_map")
    ax.set_xlabel(axis_label(results[dims[0]]))
    handles = _legend_handles(results, outcomes, colors)
    handles += _mark_runs(ax, results, dims, xs, ys)
    for k, trace in enumerate(boundaries):
        handles += _draw_traced(
            ax,
            trace,
            dims,
            BOUNDARY_STYLES[k % len(BOUNDARY_STYLES)],
            results.attrs.get("param_mu"),
        )
    legend_above(ax, handles, min(3, len(handles)))
    ran = int((results["ran"] == 1).sum())
    main.suptitle(
        f"{results.attrs.get('campaign_name', '')}: motion map, {motion.size} cells "
        f"({ran} run), start: {str(results.attrs.get('start', '?')).split(':')[0]}",
        wrap=True,
    )
    return fig


def _legend_handles(results: xr.Dataset, outcomes: list[str], colors) -> list[Any]:
    """One patch per motion present, with its share of the known cells."""
    shares = dict(zip(outcomes, np.asarray(results["cell_fraction"].values, float), strict=True))
    return [
        Patch(facecolor=colors[o], edgecolor="0.3", label=f"{o} ({100 * shares[o]:.1f} %)")
        for o in outcomes
        if np.isfinite(shares[o]) and shares[o] > 0
    ]


def _mark_runs(ax, results: xr.Dataset, dims: list[str], xs, ys) -> list[Any]:
    """A dot on each cell that ran, a cross where its log says "not settled" (map/table.py
    settled_flags, in either mode); their legend handles. xs, ys: the cells' values in file
    order."""
    ran = np.asarray(results["ran"].values)
    settled = settled_flags(results)
    if len(dims) == 1:
        ran, settled = ran[:, None], settled[:, None]
    handles = []
    for flag, marker, label in ((1, ".", "cell run"), (0, "x", "run, not settled")):
        mask = (ran == 1) & ((settled != 0) if flag else (settled == 0))
        i, j = np.nonzero(mask)
        if not i.size:
            continue
        size = 3 if flag else 5
        points = ax.plot(xs[i], ys[j], marker, color="0.15", markersize=size, linestyle="none")
        points[0].set_gid("cells_run" if flag else "cells_unsettled")
        handles.append(Line2D([], [], marker=marker, color="0.15", linestyle="none", label=label))
    return handles


def _draw_traced(
    ax, trace: xr.Dataset, dims: list[str], style: tuple[str, str], map_mu: float | None
) -> list[Any]:
    """A boundary drawn on the map, from any results.nc with a mu_star: a trace's curves,
    or a find_jump's line mu*(key), where the map's two keys are that key and mu (either
    way round); a find_jump grid over the map's two keys as the contour mu* = the map's
    mu. Its legend entry; ValueError ("boundary ...") for results it cannot place."""
    name = trace.attrs.get("campaign_name", "?")
    task = trace.attrs.get("task")
    if "mu_star" not in trace.variables or task not in ("trace", "find_jump"):
        raise ValueError(f"boundary {name}: a {task!r} results.nc without mu_star")
    if "parameter" in trace.attrs:
        raise ValueError(
            f"boundary {name}: it bisects {trace.attrs['parameter']}, not mu; its values "
            "are no mu to draw on the map"
        )
    if task == "trace":
        check_vars(trace, _TRACE_VARS, f"boundary {name} (trace)")
        key = str(trace.attrs["trace_key_var"])
        curves = curve_points(trace, key)
    else:
        star = trace["mu_star"].where(trace["status"] == "converged")
        if star.ndim == 2 and set(star.dims) == set(dims):
            return _draw_contour(ax, trace, star, dims, style, map_mu)
        key = str(star.dims[0]) if star.ndim == 1 else "?"
        order = np.argsort(np.asarray(star[key].values, float)) if star.ndim == 1 else []
        ok = np.isfinite(np.asarray(star.values, float)[order]) if star.ndim == 1 else []
        curves = [(np.asarray(star[key].values, float)[order][ok], star.values[order][ok])]
    if len(dims) != 2 or set(dims) != {key, "mu"}:
        raise ValueError(
            f"boundary {name}: the {task} runs over ({key}, mu), the map over ({', '.join(dims)})"
        )
    line, marker = style
    for along, mu in curves:
        x, y = (along, mu) if dims[0] == key else (mu, along)
        ax.plot(x, y, line, color="black", linewidth=1.3, zorder=5)
        ax.plot(x, y, marker, color="black", markersize=2.6, zorder=6)
    what = "traced" if task == "trace" else "find_jump"
    label = f"{what} {_sides(trace)}, tol {float(trace.attrs['tol']):g}"
    return [
        Line2D([], [], linestyle=line, marker=marker, color="black", markersize=2.6, label=label)
    ]


def _draw_contour(ax, found: xr.Dataset, star, dims: list[str], style, mu) -> list[Any]:
    """The contour mu*(x, y) = `mu` (the map's) of a find_jump grid over the map's keys."""
    name = found.attrs.get("campaign_name", "?")
    if mu is None:
        raise ValueError(f"boundary {name}: a grid of mu* needs a map at one mu")
    z = np.asarray(star.transpose(*dims).values, float)
    xs, ys = (np.asarray(star[d].values, float) for d in dims)
    ix, iy = np.argsort(xs), np.argsort(ys)
    if not np.isfinite(z).any() or not (np.nanmin(z) <= float(mu) <= np.nanmax(z)):
        return []
    line, _ = style
    ax.contour(
        xs[ix],
        ys[iy],
        z[np.ix_(ix, iy)].T,
        levels=[float(mu)],
        colors="black",
        linestyles=line,
        linewidths=1.3,
    )
    label = f"find_jump {_sides(found)}: \u03bc* = {float(mu):g}"
    return [Line2D([], [], linestyle=line, color="black", label=label)]


def _sides(trace: xr.Dataset) -> str:
    """ "A | B" of a trace's `between` attribute ("[A, B]: each curve separates ..."); the
    stick jump's where it has none."""
    found = re.match(r"\[(\w+), (\w+)\]", str(trace.attrs.get("between", "")))
    return f"{found[1]} | {found[2]}" if found else "not_stick | stick"
