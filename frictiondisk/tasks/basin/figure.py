"""Basin figures: a basin campaign's results.nc in, a matplotlib Figure out.

- a map (`basin.grid`, two keys): the outcome of every initial state as an image, one colour
  per outcome (like Attractors.jl's basin heatmaps), with the fraction of cells of each
  outcome in the legend; optionally the boundary mu*(x, y) = mu of a find_jump campaign
  over the same two keys drawn on top (`boundary`);
- a map over one key: the outcome along it, one coloured strip;
- sampled fractions along one key: the fraction of each outcome against it, with its 95 %
  Wilson interval as a band (and the not-stick curve when several outcomes make it up);
- at a single point: one bar per outcome with its interval; over two keys: a map of the
  stick fraction.

Like every figure: no backend, no pyplot, no kernel.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from frictiondisk.figures.outcome_colors import outcome_colors
from frictiondisk.figures.shared import (
    axis_label,
    cell_edges,
    check_vars,
    legend_above,
    new_figure,
    sample_spec,
)
from frictiondisk.figures.style import styled
from frictiondisk.model.scene import describe_key
from frictiondisk.verdict.outcomes import OUTCOMES, STICK, is_not_stick

__all__ = ["plot_basin", "plot_basin_fractions", "plot_basin_map"]

FRACTION_LABEL = "basin fraction [-]"
BAND_ALPHA = 0.25
_MAP_VARS = ("outcome_map", "fraction")
_FRACTION_VARS = ("fraction", "fraction_lo", "fraction_hi", "n_samples", "not_stick_fraction")


def _sample_text(results: xr.Dataset) -> str:
    """ "x0 ~ U[-0.05, 0.05]" for each sampled key (from the sample_yaml attribute)."""
    parts = []
    for key, dist in sample_spec(results).items():
        name = str(key).split(".")[-1]
        for kind, (a, b) in dist.items():
            unit = describe_key(str(key))[0]
            unit = f" {unit}" if unit and unit != "1" else ""
            parts.append(f"{name} ~ {'U' if kind == 'uniform' else 'N'}[{a:g}, {b:g}]{unit}")
    return ", ".join(parts)


@styled
def plot_basin(results: xr.Dataset, boundary: xr.Dataset | None = None) -> Figure:
    """The figure that fits a basin results.nc (see the module docstring)."""
    if results.attrs.get("basin_mode") == "map":
        return plot_basin_map(results, boundary)
    if boundary is not None:
        raise ValueError("boundary: applies to a basin map (basin.grid), not to fractions")
    return plot_basin_fractions(results)


# ---- maps ----------------------------------------------------------------------------------
@styled
def plot_basin_map(results: xr.Dataset, boundary: xr.Dataset | None = None) -> Figure:
    """The outcome of each initial state of a basin map, one colour per outcome.

    `boundary`: a find_jump results.nc over the same two keys; its contour mu* = the map's
    mu is drawn on top (where the map's stick region should end)."""
    check_vars(results, _MAP_VARS, "results (basin)")
    outcomes = [str(o) for o in results["outcome"].values]
    colors = outcome_colors(outcomes)
    cells = results["outcome_map"]
    dims = list(cells.dims)
    fig, main, _ = new_figure(results, 7.2, 5.2, 0)
    ax = main.add_subplot()
    code = {o: k for k, o in enumerate(outcomes)}
    values = np.vectorize(lambda o: code.get(str(o), -1))(cells.values)
    cmap = ListedColormap([colors[o] for o in outcomes])
    norm = BoundaryNorm(np.arange(len(outcomes) + 1) - 0.5, len(outcomes))
    fractions = dict(zip(outcomes, np.asarray(results["fraction"].values, float), strict=True))
    present = [o for o in outcomes if fractions[o] > 0]
    handles: list[Any] = [
        Patch(facecolor=colors[o], edgecolor="0.3", label=f"{o} ({100 * fractions[o]:.1f} %)")
        for o in present
    ]
    mu = results.attrs.get("mu")
    mu_text = f" at mu = {float(mu):g}" if mu is not None else ""
    if len(dims) == 1:
        if boundary is not None:
            raise ValueError("boundary: applies to a basin map over two keys")
        cx = results[dims[0]]
        order = np.argsort(cx.values)
        xs = np.asarray(cx.values, float)[order]
        mesh = ax.pcolormesh(
            cell_edges(xs), [0.0, 1.0], values[order][None, :], cmap=cmap, norm=norm
        )
        ax.set_yticks([])
        ax.set_xlabel(axis_label(cx))
    else:
        cx, cy = results[dims[0]], results[dims[1]]
        ix, iy = np.argsort(cx.values), np.argsort(cy.values)
        xs, ys = np.asarray(cx.values, float)[ix], np.asarray(cy.values, float)[iy]
        grid = values[np.ix_(ix, iy)]
        mesh = ax.pcolormesh(cell_edges(xs), cell_edges(ys), grid.T, cmap=cmap, norm=norm)
        ax.set_xlabel(axis_label(cx))
        ax.set_ylabel(axis_label(cy))
        if boundary is not None and mu is not None:
            handles += _draw_boundary(ax, boundary, dims, float(mu))
    mesh.set_gid("basin_map")
    legend_above(ax, handles, min(3, len(handles)))
    n = int(results["n_samples"])
    main.suptitle(
        f"{results.attrs.get('campaign_name', '')}: basin map{mu_text}, {n} initial states",
        wrap=True,
    )
    return fig


def _draw_boundary(ax, boundary: xr.Dataset, dims: list[str], mu: float) -> list[Any]:
    """Contour mu*(x, y) = mu of a find_jump grid over the map's keys (frictiondisk.tasks.
    plot checks that its task has one); its legend handle."""
    if "mu_star" not in boundary:
        raise ValueError("boundary: expected a find_jump results.nc (with mu_star)")
    if list(boundary["mu_star"].dims) != dims:
        raise ValueError(
            f"boundary: mu_star varies {list(boundary['mu_star'].dims)}, the map {dims}"
        )
    star = boundary["mu_star"].where(boundary["status"] == "converged")
    xs, ys = np.asarray(star[dims[0]].values, float), np.asarray(star[dims[1]].values, float)
    ix, iy = np.argsort(xs), np.argsort(ys)
    z = np.asarray(star.values, float)[np.ix_(ix, iy)].T
    if not (np.nanmin(z) <= mu <= np.nanmax(z)):
        return []
    contour = ax.contour(xs[ix], ys[iy], z, levels=[mu], colors="black", linewidths=1.4)
    contour.set_gid("boundary")
    return [Line2D([], [], color="black", linewidth=1.4, label=f"find_jump: mu* = {mu:g}")]


# ---- fractions -------------------------------------------------------------------------------
@styled
def plot_basin_fractions(results: xr.Dataset) -> Figure:
    """Sampled basin fractions with 95 % Wilson intervals (see the module docstring)."""
    check_vars(results, _FRACTION_VARS, "results (basin)")
    outcomes = [str(o) for o in results["outcome"].values]
    colors = outcome_colors(outcomes)
    frac = results["fraction"]
    present = [o for o in outcomes if float(frac.sel(outcome=o).max()) > 0]
    dims = list(results["n_samples"].dims)
    fig, main, _ = new_figure(results, 7.2, 4.6, 0)
    ax = main.add_subplot()
    sample = _sample_text(results)
    title = f"{results.attrs.get('campaign_name', '')}: basin fractions"
    title += f", {sample}" if sample else ""
    if len(dims) == 0:
        _bars(ax, results, present, colors)
    elif len(dims) == 1:
        _curves(ax, results, dims[0], present, colors)
    elif len(dims) == 2:
        _stick_map(main, ax, results, dims)
    else:
        raise ValueError(f"a basin varies at most 2 keys, this one {dims}")
    # wrapped to the figure's width: several sampled keys make a long title
    main.suptitle(title + " (bands: 95 % Wilson)" if len(dims) < 2 else title, wrap=True)
    return fig


def _bars(ax, results: xr.Dataset, present: list[str], colors: dict[str, str]) -> None:
    p = [float(results["fraction"].sel(outcome=o)) for o in present]
    lo = [float(results["fraction_lo"].sel(outcome=o)) for o in present]
    hi = [float(results["fraction_hi"].sel(outcome=o)) for o in present]
    yerr = np.array([np.subtract(p, lo), np.subtract(hi, p)])
    ax.bar(present, p, yerr=yerr, capsize=6, color=[colors[o] for o in present], gid="fractions")
    for k, value in enumerate(p):
        ax.text(k, hi[k] + 0.02, f"{value:.3f}\n[{lo[k]:.3f}, {hi[k]:.3f}]", ha="center")
    ax.set_ylim(0, 1.15)
    ax.set_ylabel(FRACTION_LABEL)
    ax.set_xlabel(f"outcome (n = {int(results['n_samples'])} samples)")


def _curves(ax, results: xr.Dataset, dim: str, present: list[str], colors) -> None:
    sorted_ = results.sortby(dim)
    x = np.asarray(sorted_[dim].values, float)
    for o in present:
        row = sorted_.sel(outcome=o)
        ax.fill_between(
            x, row["fraction_lo"], row["fraction_hi"], color=colors[o], alpha=BAND_ALPHA, lw=0
        )
        ax.plot(x, row["fraction"], marker="o", color=colors[o], label=o, gid=f"fraction_{o}")
    large = [o for o in present if o in OUTCOMES and is_not_stick(o)]
    if len(large) > 1:
        ax.fill_between(
            x, sorted_["not_stick_lo"], sorted_["not_stick_hi"], color="0.5", alpha=BAND_ALPHA
        )
        ax.plot(x, sorted_["not_stick_fraction"], "k--", marker=".", label="not stick (all)")
    for xi, n in zip(x, np.asarray(sorted_["n_samples"].values), strict=True):
        ax.annotate(
            f"n={int(n)}",
            (xi, 1.0),
            xytext=(0, 3),
            textcoords="offset points",
            ha="center",
            fontsize="x-small",
            color="0.35",
        )
    ax.set_ylim(-0.02, 1.08)
    ax.set_xlabel(axis_label(results[dim]))
    ax.set_ylabel(FRACTION_LABEL)
    ax.legend(fontsize="small", loc="center right")


def _stick_map(main, ax, results: xr.Dataset, dims: list[str]) -> None:
    cx, cy = results[dims[0]], results[dims[1]]
    ix, iy = np.argsort(cx.values), np.argsort(cy.values)
    xs, ys = np.asarray(cx.values, float)[ix], np.asarray(cy.values, float)[iy]
    stick = np.asarray(results["fraction"].sel(outcome=STICK).values, float)[np.ix_(ix, iy)]
    mesh = ax.pcolormesh(cell_edges(xs), cell_edges(ys), stick.T, vmin=0, vmax=1, cmap="Blues")
    mesh.set_gid("stick_fraction")
    main.colorbar(mesh, ax=ax).set_label("stick fraction [-]")
    ax.set_xlabel(axis_label(cx))
    ax.set_ylabel(axis_label(cy))
