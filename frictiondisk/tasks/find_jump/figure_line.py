"""The figure of a find_jump campaign along one key (paper Figs 9-11): `plot_jump_line`.

mu* (or the bisected key's value) against the key, every point with its bracket
[mu_lo, mu_hi] as an error bar, the two sides labelled: "pure sticking" (above the line)
and "outer limit cycle" (below) for the stick jump, the two motions of `between` in their
outcome colours for any other boundary; failed
points marked at the bottom of the axes and listed with their reasons, non-monotone points
ringed; further jumps of a prescan as triangles, and optionally every run of runs.nc.
"""

from __future__ import annotations

import dataclasses
import math
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
    REGION_FONT_PT,
    RUG_Y,
    SearchedKey,
    add_note,
    axis_label,
    boundary_sides,
    check_vars,
    legend_above,
    make_rug_room,
    new_figure,
    padded,
    run_dots,
    scene_title,
    searched_key,
)
from frictiondisk.figures.style import STICK_COLOR, styled
from frictiondisk.store.cf import flag_meanings
from frictiondisk.tasks.find_jump.figure_kind import figure_kind
from frictiondisk.tasks.find_jump.figure_layers import (
    failed_and_without,
    failure_lines,
    mark_no_jump,
    no_jump_label,
    point_labels,
)
from frictiondisk.verdict.outcomes import record

RUNS_VIEW = 2.0  # runs above this many times the largest bracket end are drawn at the top
_RUN_VARS = ("point", "mu", "outcome")


def _free_spot(
    ax: Axes,
    xs: np.ndarray,
    ys: np.ndarray,
    others: np.ndarray,
    above: bool,
    box: tuple[float, float],
    axes_in: tuple[float, float],
) -> tuple[float, float] | None:
    """Axes-fraction centre for a region label of size `box` (width, height [in]) above (or
    below) the polyline (xs, ys), as far as possible from the line, from the points
    `others` (N x 2, data) and from the frame; `axes_in` is the axes size [in]. None if no
    position puts the whole label on its side of the line."""
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    w, h = axes_in
    dense_x = np.linspace(x0, x1, 400)
    items = [
        np.column_stack(
            [(dense_x - x0) / (x1 - x0) * w, (np.interp(dense_x, xs, ys) - y0) / (y1 - y0) * h]
        )
    ]
    if len(others):
        items.append(
            np.column_stack(
                [(others[:, 0] - x0) / (x1 - x0) * w, (others[:, 1] - y0) / (y1 - y0) * h]
            )
        )
    pts = np.vstack(items)
    hw, hh = 0.5 * box[0], 0.5 * box[1]
    best, spot = 0.0, None
    for cx in np.linspace(hw + 0.05, w - hw - 0.05, 31):
        for cy in np.linspace(hh + 0.25, h - hh - 0.05, 31):
            # the label's corners must lie on its side of the line
            cxs = np.array([cx - hw, cx + hw]) / w * (x1 - x0) + x0
            line = (np.interp(cxs, xs, ys) - y0) / (y1 - y0) * h
            if above and not np.all(cy - hh > line):
                continue
            if not above and not np.all(cy + hh < line):
                continue
            dx = np.maximum(np.abs(pts[:, 0] - cx) - hw, 0.0)
            dy = np.maximum(np.abs(pts[:, 1] - cy) - hh, 0.0)
            dist = min(float(np.min(np.hypot(dx, dy))), cy - hh, h - cy - hh)
            if dist > best:
                best, spot = dist, (float(cx / w), float(cy / h))
    return spot


def _further_jumps(results: xr.Dataset, dim: str) -> dict[str, np.ndarray]:
    """The jumps of a prescanned find_jump line besides each point's primary one (the
    line): x, lo, hi and rising (bool) of each. Empty without a prescan."""
    empty = {key: np.empty(0) for key in ("x", "lo", "hi", "rising")}
    if "jump_mu_lo" not in results.variables:
        return empty
    lo = np.asarray(results["jump_mu_lo"].transpose(dim, "jump").values, dtype=float)
    hi = np.asarray(results["jump_mu_hi"].transpose(dim, "jump").values, dtype=float)
    rising = np.asarray(results["jump_rising"].transpose(dim, "jump").values) == 1
    x = np.broadcast_to(np.asarray(results[dim].values, dtype=float)[:, None], lo.shape)
    primary_lo = np.asarray(results["mu_lo"].values, dtype=float)[:, None]
    primary_hi = np.asarray(results["mu_hi"].values, dtype=float)[:, None]
    keep = np.isfinite(lo) & ~((lo == primary_lo) & (hi == primary_hi))
    return {"x": x[keep], "lo": lo[keep], "hi": hi[keep], "rising": rising[keep]}


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


def _flagged(results: xr.Dataset, meaning: str) -> np.ndarray:
    """Where the `certification` flag of results.nc has `meaning` (all False without it)."""
    if "certification" not in results:
        return np.zeros(results["mu_star"].shape, bool)
    var = results["certification"]
    codes = [code for code, name in flag_meanings(var).items() if name == meaning]
    return np.isin(np.asarray(var.values), codes)


@dataclasses.dataclass(frozen=True)
class _Line:
    """The arrays of a find_jump line, in the Dataset's order; `order` sorts them by x."""

    dim: str
    x: np.ndarray
    mu_star: np.ndarray
    mu_lo: np.ndarray
    mu_hi: np.ndarray
    monotone: np.ndarray
    failed: np.ndarray  # status failed
    without: np.ndarray  # no jump on the point's grid (an answer)
    bracketed: np.ndarray  # both bracket ends finite
    ok: np.ndarray  # not failed, bracketed: on the line
    order: np.ndarray

    @classmethod
    def of(cls, results: xr.Dataset) -> _Line:
        (dim,) = results["mu_star"].dims
        x = np.asarray(results[dim].values, dtype=float)
        mu_lo = np.asarray(results["mu_lo"].values, dtype=float)
        mu_hi = np.asarray(results["mu_hi"].values, dtype=float)
        failed, without = failed_and_without(results)
        bracketed = np.isfinite(mu_lo) & np.isfinite(mu_hi)
        return cls(
            dim=dim,
            x=x,
            mu_star=np.asarray(results["mu_star"].values, dtype=float),
            mu_lo=mu_lo,
            mu_hi=mu_hi,
            monotone=np.asarray(results["monotone"].values).astype(int),
            failed=failed,
            without=without,
            bracketed=bracketed,
            ok=~failed & bracketed,
            order=np.argsort(x),
        )

    @property
    def on_line(self) -> np.ndarray:
        """Indices of the points on the line, sorted by x."""
        return self.order[self.ok[self.order]]


@dataclasses.dataclass(frozen=True)
class _Runs:
    """The runs of runs.nc shown (empty without --runs) and the mu range of the view."""

    x: np.ndarray
    mu: np.ndarray
    outcome: np.ndarray
    in_view: np.ndarray  # mu below the view's top (the rest are marked at the top)
    y_range: tuple[float, float]


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
    line = _Line.of(results)
    fail_lines = failure_lines(results, point_labels(results), line.failed)
    fig, main, note = new_figure(results, 7.2, 5.2, len(fail_lines) + 1 if fail_lines else 0)
    ax = main.add_subplot()

    extra = _further_jumps(results, line.dim)
    key = searched_key(results)
    shown = _shown_runs(line, extra, runs if show_runs else None)
    run_handles = _draw_runs(ax, shown, key)
    handles = _draw_line(ax, results, line, key)
    handles += _draw_further_jumps(ax, extra)
    handles += _draw_failed(ax, results, line, shown.y_range)
    handles += _draw_non_monotone(ax, line)
    _label_regions(fig, ax, line, shown, region_labels(results))

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


def _shown_runs(line: _Line, extra: dict[str, np.ndarray], runs: xr.Dataset | None) -> _Runs:
    """The runs to draw and the mu range shown: every bracket, and the runs up to RUNS_VIEW
    x the largest bracket end (a bracket widened towards the limits must not squash the
    line)."""
    b = line.bracketed
    ends = np.concatenate([line.mu_lo[b], line.mu_hi[b], extra["lo"], extra["hi"]])
    run_x = run_mu = run_outcome = np.empty(0)
    if runs is not None:
        check_vars(runs, _RUN_VARS, "runs")
        # each run at its point's coordinate: a find_jump bisecting another key along mu
        # keeps the bisected values in runs.nc's `mu`, which then is not the coordinate
        run_x = line.x[np.asarray(runs["point"].values, dtype=int)]
        run_mu = np.asarray(runs["mu"].values, dtype=float)
        run_outcome = np.asarray(runs["outcome"].values).astype(str)
    cap = RUNS_VIEW * float(ends.max()) if ends.size else math.inf
    in_view = run_mu <= cap
    shown = np.concatenate([ends, run_mu[in_view]])
    shown = shown[np.isfinite(shown)]
    if shown.size:
        y_lo, y_hi = padded(float(shown.min()), float(shown.max()), 0.1)
        if shown.min() >= 0.0:
            y_lo = max(y_lo, 0.0)
    else:
        y_lo, y_hi = 0.0, 1.0
    return _Runs(run_x, run_mu, run_outcome, in_view, (y_lo, y_hi))


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


def _draw_runs(ax: Axes, runs: _Runs, key: SearchedKey) -> list[Any]:
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


def _draw_line(ax: Axes, results: xr.Dataset, line: _Line, key: SearchedKey) -> list[Any]:
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
    uncertain = line.ok & _flagged(results, "uncertain")
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
    ax: Axes, results: xr.Dataset, line: _Line, y_range: tuple[float, float]
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


def _draw_non_monotone(ax: Axes, line: _Line) -> list[Any]:
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


def _label_regions(
    fig: Figure, ax: Axes, line: _Line, runs: _Runs, labels: tuple[tuple[str, bool, str], ...]
) -> None:
    """The two regions of the (coordinate, mu) plane (paper Fig. 9), each labelled with its
    (text, above, colour) of `labels` where it is farthest from the line, the points and
    the runs; or "no point converged"."""
    if not line.ok.any():
        ax.text(
            0.5,
            0.5,
            "no point converged",
            transform=ax.transAxes,
            ha="center",
            va="center",
            color=FAIL_COLOR,
        )
        return
    sel = line.on_line
    others = np.column_stack([line.x[sel], line.mu_star[sel]])
    others = np.vstack([others, np.column_stack([runs.x[runs.in_view], runs.mu[runs.in_view]])])
    fig.draw_without_rendering()  # lay out once to learn the axes size
    extent = ax.get_window_extent()
    axes_in = (extent.width / fig.dpi, extent.height / fig.dpi)
    for text, above, color in labels:
        box = (0.55 * REGION_FONT_PT * len(text) / 72, 1.4 * REGION_FONT_PT / 72)
        spot = _free_spot(ax, line.x[sel], line.mu_star[sel], others, above, box, axes_in)
        if spot is not None:
            ax.text(
                *spot,
                text,
                transform=ax.transAxes,
                ha="center",
                va="center",
                fontsize=REGION_FONT_PT,
                fontstyle="italic",
                color=color,
                alpha=0.85,
                zorder=1,
            )
