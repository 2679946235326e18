"""Size against mu around the jump for a few points (paper Figs 7-8), from results.nc.

For a find_jump line with a `converge` prescan: one size curve per point (prescan runs,
coloured by point, marker by outcome) and every located jump as a vertical line with a
triangle on top (its bracket [mu_lo, mu_hi] is far narrower than a pixel at this scale);
the legend sits beside the axes, so it hides no jump. For the middle point, a zoom on its
jump shows every bisection run (the paper's middle panel) at its mu, in the order the runs
were made: a decide run that does not stick has no size, so the zoom's height is the run
number, not a size. Nothing here simulates.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator
from matplotlib.transforms import blended_transform_factory

from frictiondisk.figures.shared import (
    MU_LABEL,
    SIZE_LABEL,
    boundary_sides,
    fitted_legend,
    new_figure,
    outcome_style,
    scene_title,
    value_text,
)
from frictiondisk.figures.style import styled
from frictiondisk.tasks.find_jump.figure_line import line_title
from frictiondisk.verdict.outcomes import OUTCOMES, STICK

JUMP_MARK_Y = 1.0  # axes fraction of the triangle marking a located jump


@styled
def plot_jump_sizes(results: xr.Dataset, runs: xr.Dataset | None = None) -> Figure:
    """Size curves and jumps of a prescanned find_jump line (module docstring); `runs`
    (runs.nc) adds the zoom on the middle point's jump with its bisection runs."""
    (dim,) = results["mu_star"].dims
    x = np.asarray(results[dim].values, dtype=float)
    scan_mu = np.asarray(results["scan_mu"].values, dtype=float)
    colors = colormaps["viridis"](np.linspace(0.0, 0.85, max(len(x), 2)))
    middle = len(x) // 2
    zoom = runs is not None and "jump_mu_lo" in results.variables

    fig, main, _ = new_figure(results, 10.5 if zoom else 7.2, 5.2, 0)
    axes = main.subplots(1, 2, width_ratios=[3, 2]) if zoom else [main.subplots()]
    ax = axes[0]
    handles = []
    for i, value in enumerate(x):
        sizes = np.asarray(results["scan_size"].isel({dim: i}).values, dtype=float)
        outcomes = np.asarray(results["scan_outcome"].isel({dim: i}).values).astype(str)
        label = value_text(results[dim], value)
        ax.plot(scan_mu, sizes, "-", color=colors[i], lw=1.0, zorder=2)
        for outcome in np.unique(outcomes):
            sel = outcomes == outcome
            style = outcome_style(outcome)
            ax.plot(
                scan_mu[sel],
                sizes[sel],
                linestyle="none",
                marker=style["marker"],
                markersize=5,
                markerfacecolor=colors[i] if outcome == STICK else "white",
                markeredgecolor=colors[i],
                zorder=3,
            )
        top = blended_transform_factory(ax.transData, ax.transAxes)
        for lo, hi in _jumps(results, dim, i):
            ax.axvspan(lo, hi, color=colors[i], alpha=0.35, lw=0, zorder=1)
            ax.axvline(0.5 * (lo + hi), color=colors[i], lw=1.2, ls="--", zorder=1)
            ax.plot(
                0.5 * (lo + hi),
                JUMP_MARK_Y,
                "v",
                color=colors[i],
                ms=8,
                transform=top,
                clip_on=False,
                zorder=4,
            )
        text = ", ".join(f"\u03bc* = {0.5 * (lo + hi):.5f}" for lo, hi in _jumps(results, dim, i))
        handles.append(Line2D([], [], color=colors[i], marker="o", label=f"{label}: {text}"))
    present = set(np.asarray(results["scan_outcome"].values).astype(str).ravel())
    for outcome in [o for o in OUTCOMES if o in present] + sorted(present - set(OUTCOMES)):
        face = "0.3" if outcome == STICK else "white"
        marker = outcome_style(outcome)["marker"]
        fill = "filled" if outcome == STICK else "open"
        handles.append(
            Line2D(
                [], [], ls="none", marker=marker, mfc=face, mec="0.3", label=f"{outcome} ({fill})"
            )
        )
    ax.set_xlabel(MU_LABEL)
    ax.set_ylabel(SIZE_LABEL)
    ax.grid(True, lw=0.4, alpha=0.5)
    fitted_legend(
        ax,
        2,
        handles=handles,
        fontsize="small",
        loc="upper center",
        bbox_to_anchor=(0.5, -0.14),
        frameon=False,
    )
    ax.set_title("size against \u03bc; dashed line and \u25bc: located jump \u03bc*", fontsize=10)
    if zoom:
        _zoom(axes[1], results, runs, dim, middle, colors[middle])
    title = "from the limit cycle to permanent sticking"
    if boundary_sides(results) is not None:
        title = line_title(results)
    main.suptitle(f"{scene_title(results)}: {title}", wrap=True)
    return fig


def _jumps(results: xr.Dataset, dim: str, i: int) -> list[tuple[float, float]]:
    lo = np.asarray(results["jump_mu_lo"].isel({dim: i}).values, dtype=float)
    hi = np.asarray(results["jump_mu_hi"].isel({dim: i}).values, dtype=float)
    return [(a, b) for a, b in zip(lo, hi, strict=True) if np.isfinite(a) and np.isfinite(b)]


def _zoom(ax, results: xr.Dataset, runs: xr.Dataset, dim: str, i: int, color) -> None:
    """The middle point's first jump: every bisection run of it as a dot."""
    x_value = float(results[dim].values[i])
    jumps = _jumps(results, dim, i)
    ax.set_xlabel(MU_LABEL)
    ax.set_ylabel("bisection run (in order)")
    ax.grid(True, lw=0.4, alpha=0.5)
    if not jumps:
        ax.text(0.5, 0.5, "no jump located", transform=ax.transAxes, ha="center")
        return
    scan_mu = np.asarray(results["scan_mu"].values, dtype=float)
    primary = (float(results["mu_lo"].values[i]), float(results["mu_hi"].values[i]))
    lo, hi = primary if primary in jumps else jumps[0]
    below, above = scan_mu[scan_mu <= lo], scan_mu[scan_mu >= hi]
    left = float(below.max()) if below.size else lo  # the prescan values around the jump
    right = float(above.min()) if above.size else hi
    sel = (np.asarray(runs[dim].values) == x_value) & (np.asarray(runs["mode"].values) == "decide")
    sel &= (np.asarray(runs["mu"].values) >= left) & (np.asarray(runs["mu"].values) <= right)
    mu = np.asarray(runs["mu"].values, dtype=float)[sel]  # in run order (runs.nc order)
    stick = np.asarray(runs["outcome"].values).astype(str)[sel] == STICK
    number = np.arange(1, mu.size + 1)
    ax.plot(mu, number, "-", color="0.75", lw=0.8, zorder=1)
    ax.plot(mu[stick], number[stick], "o", color=color, ms=6, label="bisection run: stick")
    ax.plot(
        mu[~stick],
        number[~stick],
        "o",
        mfc="white",
        mec=color,
        ms=6,
        label="bisection run: not stick",
    )
    ax.axvspan(lo, hi, color=color, alpha=0.35, lw=0)
    ax.set_xlim(left - 0.05 * (right - left), right + 0.05 * (right - left))
    ax.set_ylim(0.5, max(mu.size, 1) + 0.5)
    ax.invert_yaxis()  # the first run at the top: read downwards as the bracket closes
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.ticklabel_format(axis="x", useOffset=False)
    ax.tick_params(axis="x", labelrotation=30)
    ax.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.22), frameon=False)
    ax.set_title(
        f"{value_text(results[dim], x_value)}: the bisection's runs, in order\n"
        f"\u03bc* in [{lo:.5f}, {hi:.5f}]",
        fontsize=10,
    )
