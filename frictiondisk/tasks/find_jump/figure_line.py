"""The figure of a find_jump campaign along one key (paper Figs 9-11): `plot_jump_line`.

mu* (or the bisected key's value) against the key, every point with its bracket
[mu_lo, mu_hi] as an error bar, the two sides labelled: "pure sticking" (above the line)
and "outer limit cycle" (below) for the stick jump, the two motions of `between` in their
outcome colours for any other boundary; failed
points marked at the bottom of the axes and listed with their reasons, non-monotone points
ringed; further jumps of a prescan as triangles, and optionally every run of runs.nc.
What it shows is read by figure_line_data.py; figure_regions.py places the side labels.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.transforms import blended_transform_factory

from frictiondisk.figures.shared import (
    FAIL_COLOR,
    LINE_COLOR,
    MAX_LISTED,
    NON_MONOTONE_COLOR,
    RUG_Y,
    SearchedKey,
    add_note,
    axis_label,
    boundary_sides,
    legend_above,
    make_rug_room,
    new_figure,
    padded,
    run_dots,
    scene_title,
    searched_key,
)
from frictiondisk.figures.style import STICK_COLOR, styled
from frictiondisk.tasks.find_jump.figure_kind import figure_kind
from frictiondisk.tasks.find_jump.figure_layers import (
    failure_lines,
    mark_no_jump,
    no_jump_label,
    point_labels,
)
from frictiondisk.tasks.find_jump.figure_line_data import (
    JumpLine,
    ShownRuns,
    flagged,
    further_jumps,
    shown_runs,
)
from frictiondisk.tasks.find_jump.figure_regions import label_regions
from frictiondisk.verdict.outcomes import record


def _draw_further_jumps(ax: Axes, extra: dict[str, np.ndarray]) -> list[Any]:
    """Triangles with brackets: further rising jumps (^) and falling jumps (v)."""
    handles = []
    for rising, marker, color, label in (
        (True, "^", STICK_COLOR, "further jump: not stick below, stick above"),
        (False, "v", NON_MONOTONE_COLOR, "falling jump: stick below, not stick above"),
    ):
        sel = extra["rising"] == rising
        if not sel.any():
            continue
        mid = 0.5 * (extra["lo"][sel] + extra["hi"][sel])
        handles.append(
            ax.errorbar(
                extra["x"][sel],
                mid,
                yerr=[mid - extra["lo"][sel], extra["hi"][sel] - mid],
                fmt=marker,
                color=color,
                markersize=6,
                elinewidth=1.2,
                capsize=3,
                zorder=5,
                label=label,
            )
        )
    return handles


@styled
def plot_jump_line(
    results: xr.Dataset, runs: xr.Dataset | None = None, *, show_runs: bool = False
) -> Figure:
    """mu* against the one varied key of a find_jump campaign (paper Figs 9-11).

    Each converged point is drawn at its bracket midpoint mu* with an error bar spanning
    [mu_lo, mu_hi] (asymmetric yerr). A failed point with a partial bracket is drawn in red
    with that bracket; one without a bracket as a red 'x' at the bottom of the axes; all
    failed points are numbered and listed below the plot with their reasons. Points whose
    runs contradict a single jump (monotone == 0) are ringed; `uncertain` ones (certification
    flag) are drawn hollow and named in the legend. The region above the line is
    labelled "pure sticking", below "outer limit cycle" (a `between` boundary: its upper
    and lower motion, in their outcome colours; the title names both). A find_jump that
    bisects another key (`parameter`) names that key and its unit on the y axis and in the
    legend. `show_runs` overlays every run of `runs` (runs.nc) as a dot at (coordinate,
    value), in its outcome's style.
    """
    if figure_kind(results) != "jump_line":
        raise ValueError("plot_jump_line needs a find_jump result along one key")
    if show_runs and runs is None:
        raise ValueError("show_runs needs the runs Dataset (runs.nc)")
    line = JumpLine.of(results)
    fail_lines = failure_lines(results, point_labels(results), line.failed)
    fig, main, note = new_figure(results, 7.2, 5.2, len(fail_lines) + 1 if fail_lines else 0)
    ax = main.add_subplot()

    extra = further_jumps(results, line.dim)
    key = searched_key(results)
    shown = shown_runs(line, extra, runs if show_runs else None)
    run_handles = _draw_runs(ax, shown, key)
    handles = _draw_line(ax, results, line, key)
    handles += _draw_further_jumps(ax, extra)
    handles += _draw_failed(ax, results, line, shown.y_range)
    handles += _draw_non_monotone(ax, line)
    label_regions(fig, ax, line, shown, region_labels(results))

    ax.set_xlabel(axis_label(results[line.dim]))
    ax.set_ylabel(key.label)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    main.suptitle(f"{scene_title(results)}: {line_title(results)}", wrap=True)
    handles += run_handles
    if handles:
        legend_above(ax, handles, 2)
    if note is not None:
        add_note(note, fail_lines, f"failed points ({int(line.failed.sum())}):")
    return fig


def line_title(results: xr.Dataset) -> str:
    """What the line is: the stick jump "jump \u03bc* from the outer limit cycle to pure
    sticking", or a `between` boundary "boundary \u03bc* from self_centring (slides to rest)
    below to slide_cycle (pure-sliding cycle) above" (the bisected key's symbol)."""
    star = searched_key(results).star
    sides = boundary_sides(results)
    if sides is None:
        return f"jump {star} from the outer limit cycle to pure sticking"
    below, above = (_legend_of(name) for name in sides)
    return f"boundary {star} from {below} below to {above} above"


def _legend_of(name: str) -> str:
    try:
        return record(name).legend
    except ValueError:
        return name


def region_labels(results: xr.Dataset) -> tuple[tuple[str, bool, str], ...]:
    """(text, above the line, colour) of the two sides: "pure sticking" and "outer limit
    cycle" for the stick jump, the two motions of `between` (their edge colours) else."""
    sides = boundary_sides(results)
    if sides is None:
        return (("pure sticking", True, STICK_COLOR), ("outer limit cycle", False, "#3f6e8c"))
    below, above = sides
    return ((above, True, _edge_of(above)), (below, False, _edge_of(below)))


def _edge_of(name: str) -> str:
    try:
        return record(name).edge
    except ValueError:
        return LINE_COLOR


def _draw_runs(ax: Axes, runs: ShownRuns, key: SearchedKey) -> list[Any]:
    """Every run in view as a dot, those above it as triangles at the top; legend entries."""
    handles: list[Any] = []
    if runs.mu.size:
        inside = runs.in_view
        handles = run_dots(ax, runs.x[inside], runs.mu[inside], runs.outcome[inside])
    above = ~runs.in_view
    if above.any():
        top = blended_transform_factory(ax.transData, ax.transAxes)
        ax.plot(
            runs.x[above],
            np.full(int(above.sum()), 0.985),
            transform=top,
            linestyle="none",
            marker="^",
            markersize=5,
            color="0.4",
            clip_on=False,
            zorder=6,
            gid="runs_above",
        )
        handles.append(
            Line2D(
                [],
                [],
                linestyle="none",
                marker="^",
                markersize=5,
                color="0.4",
                label=f"run above the view ({key.symbol} up to {runs.mu[above].max():.3g})",
            )
        )
    return handles


def _draw_line(ax: Axes, results: xr.Dataset, line: JumpLine, key: SearchedKey) -> list[Any]:
    """The converged points with their brackets, joined; the uncertain ones hollow."""
    handles: list[Any] = []
    tol = results.attrs.get("tol")
    tol_text = f", tol {float(tol):g}" if tol is not None else ""
    if line.ok.any():
        sel = line.on_line
        container = ax.errorbar(
            line.x[sel],
            line.mu_star[sel],
            yerr=[line.mu_star[sel] - line.mu_lo[sel], line.mu_hi[sel] - line.mu_star[sel]],
            fmt="-o",
            color=LINE_COLOR,
            markerfacecolor=STICK_COLOR,
            markeredgecolor=STICK_COLOR,
            markersize=5,
            linewidth=1.2,
            elinewidth=1.2,
            capsize=4,
            zorder=4,
            label=f"{key.star} with its bracket [{key.symbol}_lo, {key.symbol}_hi]{tol_text}",
        )
        handles.append(container)
    uncertain = line.ok & flagged(results, "uncertain")
    if uncertain.any():  # converged, but not confirmed at the strictest certification level
        handles += ax.plot(
            line.x[uncertain],
            line.mu_star[uncertain],
            linestyle="none",
            marker="o",
            markersize=8,
            markerfacecolor="white",
            markeredgecolor=LINE_COLOR,
            zorder=5,
            gid="uncertain",
            label=f"uncertain: {key.star} not confirmed by stricter numerics (hollow)",
        )
    return handles


def _draw_failed(
    ax: Axes, results: xr.Dataset, line: JumpLine, y_range: tuple[float, float]
) -> list[Any]:
    """Failed points: with the bracket they stopped at (red), without one on the rug at
    the bottom; points without a jump at the top; the failed ones numbered as listed.
    Sets the axes limits first (the rug and the marks sit in axes fractions)."""
    handles: list[Any] = []
    x, failed, bracketed = line.x, line.failed, line.bracketed
    partial = failed & bracketed
    if partial.any():
        mid, lo, hi = line.mu_star[partial], line.mu_lo[partial], line.mu_hi[partial]
        handles.append(
            ax.errorbar(
                x[partial],
                mid,
                yerr=[mid - lo, hi - mid],
                fmt="o",
                color=FAIL_COLOR,
                markerfacecolor="white",
                markersize=6,
                elinewidth=1.2,
                capsize=4,
                zorder=5,
                label="failed: bracket when it stopped",
            )
        )
    # limits before anything is placed in axes fractions
    ax.set_xlim(*padded(float(x.min()), float(x.max()), 0.06))
    unbracketed = failed & ~bracketed
    ax.set_ylim(*y_range)
    if unbracketed.any():
        handles.append(_mark_unbracketed(ax, x[unbracketed]))
    if line.without.any():
        handles.append(mark_no_jump(ax, x[line.without], no_jump_label(results)))
    for k, i in enumerate(np.flatnonzero(failed)[:MAX_LISTED], start=1):
        at = {"xy": (x[i], line.mu_hi[i]), "xytext": (0, 6)}
        if not bracketed[i]:
            rug = blended_transform_factory(ax.transData, ax.transAxes)
            at = {"xy": (x[i], RUG_Y), "xycoords": rug, "xytext": (0, 8)}
        ax.annotate(
            f"[{k}]",
            textcoords="offset points",
            ha="center",
            va="bottom",
            fontsize="x-small",
            color=FAIL_COLOR,
            **at,
        )
    return handles


def _mark_unbracketed(ax: Axes, x: np.ndarray) -> Line2D:
    """Failed points without a bracket as red crosses on the rug; their legend entry."""
    make_rug_room(ax, 0.08)  # for the marks of failed points
    rug = blended_transform_factory(ax.transData, ax.transAxes)
    cross = {"linestyle": "none", "marker": "x", "markeredgewidth": 2, "color": FAIL_COLOR}
    ax.plot(
        x,
        np.full(x.size, RUG_Y),
        transform=rug,
        markersize=9,
        clip_on=False,
        zorder=6,
        gid="failed_points",
        **cross,
    )
    return Line2D([], [], markersize=8, label="failed: no bracket (listed below)", **cross)


def _draw_non_monotone(ax: Axes, line: JumpLine) -> list[Any]:
    """Points whose runs contradict a single jump, ringed; their legend entry."""
    contradict = (line.monotone == 0) & line.bracketed
    if not contradict.any():
        return []
    ring = {
        "linestyle": "none",
        "marker": "o",
        "markerfacecolor": "none",
        "markeredgecolor": NON_MONOTONE_COLOR,
        "markeredgewidth": 2,
    }
    ax.plot(
        line.x[contradict],
        line.mu_star[contradict],
        markersize=14,
        zorder=7,
        gid="non_monotone",
        **ring,
    )
    label = "non-monotone: a run contradicts a single jump"
    return [Line2D([], [], markersize=10, label=label, **ring)]
