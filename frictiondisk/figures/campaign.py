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

For find_jump figures `show_runs=True` overlays every run of runs.nc (paper Fig 7, middle
panel: how the jump was iterated): dots at (coordinate, mu), stick dark, not stick light,
undetermined red. A grid has no room for the mu of each run; its cells show their run count.

Every figure carries a caption line (campaign, task, tolerance, numerics, versions). Like
`frictiondisk.figures.plotting`, nothing here selects a backend, touches pyplot, imports the kernel
or simulates: figures are `matplotlib.figure.Figure` objects, saved with
`frictiondisk.figures.plotting.save_figure`.
"""

from __future__ import annotations

import math
import re
import textwrap
from typing import Any

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.figure import Figure, SubFigure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle
from matplotlib.ticker import FuncFormatter
from matplotlib.transforms import blended_transform_factory

from frictiondisk.figures.plotting import SLIDE_COLOR, STICK_COLOR
from frictiondisk.figures.shared import (  # noqa: F401  (re-exported)
    A_LABEL,
    CAPTION_FONT_PT,
    CAPTION_SEP,
    FAIL_COLOR,
    LINE_COLOR,
    LIST_WIDTH,
    MAX_LISTED,
    MU_LABEL,
    MU_STAR_LABEL,
    NON_MONOTONE_COLOR,
    NOTE_FONT_PT,
    OUTCOME_LABEL,
    OUTCOME_STYLE,
    REGION_FONT_PT,
    RUG_Y,
    SIZE_LABEL,
    SLIDE_GREY,
    _caption_parts,
    _fmt,
    _unit_text,
    _value_text,
    _wrap_parts,
    axis_label,
    caption_text,
    new_figure,
    scene_title,
)
from frictiondisk.figures.style import styled
from frictiondisk.store.cf import flag_meanings

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

FIGURE_KINDS = ("jump_line", "jump_grid", "jump_sizes", "scan_mu", "scan_family", "trajectory")

RUNS_VIEW = 2.0  # runs above this many times the largest bracket end are drawn at the top


def _make_rug_room(ax: Axes, frac: float) -> None:
    """Extend the y axis downwards so that the data keep the upper 1 - `frac` of it; the strip
    below (for marks of points without a value) is set off by a dotted line and has no tick
    labels, so that nobody reads a value off a mark there."""
    lo, hi = ax.get_ylim()
    new_lo = lo - frac / (1.0 - frac) * (hi - lo)
    ax.set_ylim(new_lo, hi)
    ax.axhline(lo, color="0.6", linewidth=0.6, linestyle=":", zorder=1, gid="rug_line")

    def label(value: float, pos: int | None = None) -> str:
        return "" if value < lo - 1e-9 * abs(hi - lo) else f"{value:.6g}"

    ax.yaxis.set_major_formatter(FuncFormatter(label))


_JUMP_VARS = ("mu_star", "mu_lo", "mu_hi", "status", "reason", "monotone")
_SCAN_VARS = ("outcome", "reason", "size", "a")
_RUN_VARS = ("point", "mu", "outcome")


# ---- what the Dataset holds --------------------------------------------------------------
def _check_vars(ds: xr.Dataset, names: tuple[str, ...], what: str) -> None:
    missing = [name for name in names if name not in ds.variables]
    if missing:
        raise ValueError(
            f"{what} lacks the variable(s) {', '.join(missing)}: "
            "not written by this version of frictiondisk?"
        )


def _mu_dim(ds: xr.Dataset) -> str | None:
    """The dimension of a scan that varies mu (scene key params.mu), or None."""
    for dim in ds.dims:
        if dim in ds.coords and ds[dim].attrs.get("scene_key") == "params.mu":
            return str(dim)
    return "mu" if "mu" in ds.dims else None


def figure_kind(results: xr.Dataset) -> str:
    """Which figure fits these results: one of `FIGURE_KINDS`.

    ValueError (with what is wrong) for a Dataset that is not a campaign's results.nc.
    """
    task = results.attrs.get("task")
    dims = list(results.dims)
    if task == "find_jump":
        _check_vars(results, _JUMP_VARS, "results (find_jump)")
        dims = list(results["mu_star"].dims)  # a prescan adds the dims jump and scan_mu
        if len(dims) == 1 and results.attrs.get("prescan_mode") == "converge":
            return "jump_sizes"
        if len(dims) == 1:
            return "jump_line"
        if len(dims) == 2:
            return "jump_grid"
        raise ValueError(f"a find_jump result varies 1 or 2 keys, this one {len(dims)}: {dims}")
    if task == "scan":
        _check_vars(results, _SCAN_VARS, "results (scan)")
        mu_dim = _mu_dim(results)
        if mu_dim is None:
            raise ValueError(f"a scan result varies mu, this one varies only {dims}")
        if len(dims) == 1:
            return "scan_mu"
        if len(dims) == 2:
            return "scan_family"
        raise ValueError(f"a scan varies mu and at most one more key, this one {dims}")
    if task == "trajectory":
        return "trajectory"
    raise ValueError(
        f"results attribute 'task' is {task!r}; expected 'find_jump', 'scan' or 'trajectory' "
        "(not a frictiondisk campaign result?)"
    )


def _add_note(note: SubFigure, lines: list[str], title: str) -> None:
    note.text(
        0.015,
        0.96,
        "\n".join([title, *lines]),
        ha="left",
        va="top",
        fontsize=NOTE_FONT_PT,
        family="monospace",
        bbox={"boxstyle": "round,pad=0.4", "facecolor": "#fff5f0", "edgecolor": FAIL_COLOR},
        gid="failed_list",
    )


# ---- find_jump ---------------------------------------------------------------------------
def _failure_lines(results: xr.Dataset, labels: list[str], failed: np.ndarray) -> list[str]:
    """ "[k] x_ms = 0.1 m: reason" for each failed point (wrapped), at most MAX_LISTED."""
    reasons = np.asarray(results["reason"].values).reshape(-1)
    lines: list[str] = []
    indices = np.flatnonzero(failed.reshape(-1))
    for k, i in enumerate(indices[:MAX_LISTED], start=1):
        lines += textwrap.wrap(
            f"[{k}] {labels[i]}: {str(reasons[i]) or '(no reason given)'}",
            width=LIST_WIDTH,
            subsequent_indent="      ",
            max_lines=3,
            placeholder=" ...",
        )
    if len(indices) > MAX_LISTED:
        lines.append(
            f"... and {len(indices) - MAX_LISTED} more failed points (variable 'reason' in results.nc)"
        )
    return lines


def _point_labels(results: xr.Dataset) -> list[str]:
    """ "x_ms = 0.1 m, x0 = 0 m" for every point, in the Dataset's (C) order."""
    dims = list(results["mu_star"].dims)
    grids = np.meshgrid(*[results[d].values for d in dims], indexing="ij")
    flat = [g.reshape(-1) for g in grids]
    return [
        ", ".join(_value_text(results[d], float(f[i])) for d, f in zip(dims, flat, strict=True))
        for i in range(flat[0].size)
    ]


def _run_dots(ax: Axes, x: np.ndarray, mu: np.ndarray, outcome: np.ndarray) -> list[Line2D]:
    """Every run as a small dot at (x, mu): stick dark, not stick light, undetermined red."""
    handles = []
    groups = (
        (outcome == "stick", "o", STICK_COLOR, "run: stick"),
        (
            (outcome == "stick_slip") | (outcome == "slide") | (outcome == "creep"),
            "o",
            SLIDE_COLOR,
            "run: not stick",
        ),
        (outcome == "undetermined", "x", FAIL_COLOR, "run: undetermined"),
    )
    for mask, marker, color, label in groups:
        if not mask.any():
            continue
        ax.plot(
            x[mask],
            mu[mask],
            linestyle="none",
            marker=marker,
            markersize=3.0,
            color=color,
            markeredgecolor=STICK_COLOR if marker == "o" else color,
            markeredgewidth=0.4,
            alpha=0.9,
            zorder=2,
        )
        handles.append(
            Line2D(
                [],
                [],
                linestyle="none",
                marker=marker,
                markersize=4,
                color=color,
                markeredgecolor=STICK_COLOR if marker == "o" else color,
                markeredgewidth=0.4,
                label=label,
            )
        )
    return handles


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
    labelled "pure sticking", below "outer limit cycle". `show_runs` overlays every run of
    `runs` (runs.nc) as a dot at (coordinate, mu), coloured by stick / not stick.
    """
    if figure_kind(results) != "jump_line":
        raise ValueError("plot_jump_line needs a find_jump result along one key")
    if show_runs and runs is None:
        raise ValueError("show_runs needs the runs Dataset (runs.nc)")
    (dim,) = results["mu_star"].dims
    coord = results[dim]
    x = np.asarray(coord.values, dtype=float)
    mu_star = np.asarray(results["mu_star"].values, dtype=float)
    mu_lo = np.asarray(results["mu_lo"].values, dtype=float)
    mu_hi = np.asarray(results["mu_hi"].values, dtype=float)
    status = np.asarray(results["status"].values).astype(str)
    monotone = np.asarray(results["monotone"].values).astype(int)
    failed = status != "converged"
    bracketed = np.isfinite(mu_lo) & np.isfinite(mu_hi)
    ok = ~failed & bracketed
    order = np.argsort(x)

    labels = _point_labels(results)
    fail_lines = _failure_lines(results, labels, failed)
    fig, main, note = new_figure(results, 7.2, 5.2, len(fail_lines) + 1 if fail_lines else 0)
    ax = main.add_subplot()
    handles: list[Any] = []
    run_handles: list[Any] = []

    extra = _further_jumps(results, dim)
    # the mu range shown: every bracket, and the runs up to RUNS_VIEW x the largest bracket
    # end (a bracket widened towards the limits must not squash the line)
    ends = np.concatenate([mu_lo[bracketed], mu_hi[bracketed], extra["lo"], extra["hi"]])
    run_x = run_mu = run_outcome = np.empty(0)
    if show_runs and runs is not None:
        _check_vars(runs, (*_RUN_VARS, dim), "runs")
        run_x = np.asarray(runs[dim].values, dtype=float)
        run_mu = np.asarray(runs["mu"].values, dtype=float)
        run_outcome = np.asarray(runs["outcome"].values).astype(str)
    cap = RUNS_VIEW * float(ends.max()) if ends.size else math.inf
    in_view = run_mu <= cap
    shown = np.concatenate([ends, run_mu[in_view]])
    shown = shown[np.isfinite(shown)]
    if shown.size:
        y_lo, y_hi = _padded(float(shown.min()), float(shown.max()), 0.1)
        if shown.min() >= 0.0:
            y_lo = max(y_lo, 0.0)
    else:
        y_lo, y_hi = 0.0, 1.0
    if run_mu.size:
        run_handles = _run_dots(ax, run_x[in_view], run_mu[in_view], run_outcome[in_view])
    if (~in_view).any():
        top = blended_transform_factory(ax.transData, ax.transAxes)
        ax.plot(
            run_x[~in_view],
            np.full(int((~in_view).sum()), 0.985),
            transform=top,
            linestyle="none",
            marker="^",
            markersize=5,
            color="0.4",
            clip_on=False,
            zorder=6,
            gid="runs_above",
        )
        run_handles.append(
            Line2D(
                [],
                [],
                linestyle="none",
                marker="^",
                markersize=5,
                color="0.4",
                label=f"run above the view (\u03bc up to {run_mu[~in_view].max():.3g})",
            )
        )

    tol = results.attrs.get("tol")
    tol_text = f", tol {float(tol):g}" if tol is not None else ""
    if ok.any():
        sel = order[ok[order]]
        container = ax.errorbar(
            x[sel],
            mu_star[sel],
            yerr=[mu_star[sel] - mu_lo[sel], mu_hi[sel] - mu_star[sel]],
            fmt="-o",
            color=LINE_COLOR,
            markerfacecolor=STICK_COLOR,
            markeredgecolor=STICK_COLOR,
            markersize=5,
            linewidth=1.2,
            elinewidth=1.2,
            capsize=4,
            zorder=4,
            label=f"\u03bc* with its bracket [\u03bc_lo, \u03bc_hi]{tol_text}",
        )
        handles.append(container)

    uncertain = ok & _flagged(results, "uncertain")
    if uncertain.any():  # converged, but not confirmed at the strictest certification level
        hollow = ax.plot(
            x[uncertain],
            mu_star[uncertain],
            linestyle="none",
            marker="o",
            markersize=8,
            markerfacecolor="white",
            markeredgecolor=LINE_COLOR,
            zorder=5,
            gid="uncertain",
            label="uncertain: μ* not confirmed by stricter numerics (hollow)",
        )
        handles += hollow

    handles += _draw_further_jumps(ax, extra)

    partial = failed & bracketed
    if partial.any():
        container = ax.errorbar(
            x[partial],
            mu_star[partial],
            yerr=[mu_star[partial] - mu_lo[partial], mu_hi[partial] - mu_star[partial]],
            fmt="o",
            color=FAIL_COLOR,
            markerfacecolor="white",
            markersize=6,
            elinewidth=1.2,
            capsize=4,
            zorder=5,
            label="failed: bracket when it stopped",
        )
        handles.append(container)

    # limits before anything is placed in axes fractions
    ax.set_xlim(*_padded(float(x.min()), float(x.max()), 0.06))
    unbracketed = failed & ~bracketed
    ax.set_ylim(y_lo, y_hi)
    if unbracketed.any():
        _make_rug_room(ax, 0.08)  # for the marks of failed points
        rug = blended_transform_factory(ax.transData, ax.transAxes)
        ax.plot(
            x[unbracketed],
            np.full(int(unbracketed.sum()), RUG_Y),
            transform=rug,
            linestyle="none",
            marker="x",
            markersize=9,
            markeredgewidth=2,
            color=FAIL_COLOR,
            clip_on=False,
            zorder=6,
            gid="failed_points",
        )
        handles.append(
            Line2D(
                [],
                [],
                linestyle="none",
                marker="x",
                markersize=8,
                markeredgewidth=2,
                color=FAIL_COLOR,
                label="failed: no bracket (listed below)",
            )
        )
    failed_idx = np.flatnonzero(failed)
    for k, i in enumerate(failed_idx[:MAX_LISTED], start=1):
        if bracketed[i]:
            ax.annotate(
                f"[{k}]",
                (x[i], mu_hi[i]),
                xytext=(0, 6),
                textcoords="offset points",
                ha="center",
                va="bottom",
                fontsize="x-small",
                color=FAIL_COLOR,
            )
        else:
            ax.annotate(
                f"[{k}]",
                (x[i], RUG_Y),
                xycoords=blended_transform_factory(ax.transData, ax.transAxes),
                xytext=(0, 8),
                textcoords="offset points",
                ha="center",
                va="bottom",
                fontsize="x-small",
                color=FAIL_COLOR,
            )

    contradict = (monotone == 0) & bracketed
    if contradict.any():
        ax.plot(
            x[contradict],
            mu_star[contradict],
            linestyle="none",
            marker="o",
            markersize=14,
            markerfacecolor="none",
            markeredgecolor=NON_MONOTONE_COLOR,
            markeredgewidth=2,
            zorder=7,
            gid="non_monotone",
        )
        handles.append(
            Line2D(
                [],
                [],
                linestyle="none",
                marker="o",
                markersize=10,
                markerfacecolor="none",
                markeredgecolor=NON_MONOTONE_COLOR,
                markeredgewidth=2,
                label="non-monotone: a run contradicts a single jump",
            )
        )

    # the two regions of the (coordinate, mu) plane, paper Fig. 9
    if ok.any():
        sel = order[ok[order]]
        others = np.column_stack([x[sel], mu_star[sel]])
        others = np.vstack([others, np.column_stack([run_x[in_view], run_mu[in_view]])])
        fig.draw_without_rendering()  # lay out once to learn the axes size
        extent = ax.get_window_extent()
        axes_in = (extent.width / fig.dpi, extent.height / fig.dpi)
        for text, above, color in (
            ("pure sticking", True, STICK_COLOR),
            ("outer limit cycle", False, "#3f6e8c"),
        ):
            box = (0.55 * REGION_FONT_PT * len(text) / 72, 1.4 * REGION_FONT_PT / 72)
            spot = _free_spot(ax, x[sel], mu_star[sel], others, above, box, axes_in)
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
    else:
        ax.text(
            0.5,
            0.5,
            "no point converged",
            transform=ax.transAxes,
            ha="center",
            va="center",
            color=FAIL_COLOR,
        )

    ax.set_xlabel(axis_label(coord))
    ax.set_ylabel(MU_LABEL)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    main.suptitle(
        f"{scene_title(results)}: jump \u03bc* from the outer limit cycle to pure sticking"
    )
    handles += run_handles
    if handles:
        ax.legend(
            handles=handles,
            loc="lower left",
            bbox_to_anchor=(0.0, 1.01),
            ncols=2,
            fontsize="small",
            frameon=False,
        )
    if note is not None:
        _add_note(note, fail_lines, f"failed points ({int(failed.sum())}):")
    return fig


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
    status = np.asarray(results["status"].values).astype(str)[np.ix_(ix, iy)]
    monotone = np.asarray(results["monotone"].values).astype(int)[np.ix_(ix, iy)]
    n_runs = np.asarray(results["n_runs"].values)[np.ix_(ix, iy)] if "n_runs" in results else None
    failed = status != "converged"

    labels = _point_labels(results)
    fail_lines = _failure_lines(
        results, labels, np.asarray(results["status"].values) != "converged"
    )
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
    flat_failed = np.flatnonzero(np.asarray(results["status"].values).reshape(-1) != "converged")
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
            if monotone[a, b] == 0 and not failed[a, b]:
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
        ax.legend(
            handles=handles,
            loc="lower left",
            bbox_to_anchor=(0.0, 1.01),
            ncols=len(handles),
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


# ---- scan --------------------------------------------------------------------------------
_NO_SIZE_HANDLE = Line2D(
    [],
    [],
    linestyle="none",
    marker="o",
    markerfacecolor="none",
    markeredgecolor="0.35",
    label="hollow, below the dotted line: no size",
)


def _outcome_handles(outcomes: np.ndarray) -> list[Line2D]:
    return [
        Line2D(
            [],
            [],
            linestyle="none",
            marker=style["marker"],
            markersize=7,
            markerfacecolor=style["color"],
            markeredgecolor=style["edge"],
            markeredgewidth=1.5 if style["marker"] == "x" else 0.8,
            label=OUTCOME_LABEL[name],
        )
        for name, style in OUTCOME_STYLE.items()
        if (outcomes == name).any()
    ]


def _outcome_markers(
    ax: Axes,
    mu: np.ndarray,
    value: np.ndarray,
    outcome: np.ndarray,
    *,
    size: float = 7.0,
    edge: str | None = None,
    rug_y: float = RUG_Y,
    gid: str = "",
) -> bool:
    """Markers at (mu, value) coloured by outcome; points without a value (NaN, or
    undetermined) on a rug at the bottom of the axes. True if any point went to the rug."""
    rug = blended_transform_factory(ax.transData, ax.transAxes)
    on_rug = False
    for name, style in OUTCOME_STYLE.items():
        mask = outcome == name
        if not mask.any():
            continue
        finite = mask & np.isfinite(value) & (name != "undetermined")
        missing = mask & ~finite
        kwargs = {
            "linestyle": "none",
            "marker": style["marker"],
            "markersize": size,
            "markerfacecolor": style["color"],
            "markeredgecolor": style["edge"] if edge is None or name == "undetermined" else edge,
            "markeredgewidth": 1.5 if style["marker"] == "x" or edge else 0.8,
            "zorder": 4,
        }
        if finite.any():
            ax.plot(mu[finite], value[finite], gid=f"{gid}{name}", **kwargs)
        if missing.any():
            on_rug = True
            ax.plot(
                mu[missing],
                np.full(int(missing.sum()), rug_y),
                transform=rug,
                clip_on=False,
                gid=f"{gid}{name}_rug",
                **{**kwargs, "markerfacecolor": "none" if name != "undetermined" else None},
            )
    return on_rug


def _padded(lo: float, hi: float, frac: float) -> tuple[float, float]:
    """(lo, hi) widened by `frac` of the span on each side (by 0.5 if lo == hi)."""
    span = hi - lo
    pad = frac * span if span > 0 else 0.5 * (abs(lo) or 1.0)
    return lo - pad, hi + pad


def _sorted_scan(results: xr.Dataset, mu_dim: str, other: str | None = None) -> xr.Dataset:
    ds = results.sortby(mu_dim)
    if other is not None:
        ds = ds.transpose(other, mu_dim).sortby(other)
    return ds


@styled
def plot_scan_mu(results: xr.Dataset) -> Figure:
    """A scan of mu alone (paper Figs 6-7): size and a against mu, sharing the mu axis.

    Top: `size` against mu, markers coloured by outcome (stick dark, stick_slip light, slide
    grey, undetermined red x); a point without a size (a slide, a cycle that did not
    converge, an undetermined run) is drawn hollow on the bottom edge of the axes. Bottom: `a`
    of the stick_slip points with its least-squares line, the slope in the legend (the paper
    finds a linear in mu).
    """
    if figure_kind(results) != "scan_mu":
        raise ValueError("plot_scan_mu needs a scan result over mu alone")
    mu_dim = _mu_dim(results)
    ds = _sorted_scan(results, mu_dim)
    mu = np.asarray(ds[mu_dim].values, float)
    outcome = np.asarray(ds["outcome"].values).astype(str)
    size = np.asarray(ds["size"].values, float)
    a = np.asarray(ds["a"].values, float)

    fig, main, _ = new_figure(results, 7.2, 6.6, 0)
    ax_size, ax_a = main.subplots(2, 1, sharex=True, height_ratios=[3, 2])

    finite = np.isfinite(size)
    ax_size.plot(mu[finite], size[finite], color="0.75", linewidth=0.8, zorder=2)
    if not finite.any():
        ax_size.set_ylim(0.0, 1.0)
    ax_size.margins(x=0.04, y=0.1)
    missing = ~finite | (outcome == "undetermined")
    if missing.any():
        _make_rug_room(ax_size, 0.08)
    _outcome_markers(ax_size, mu, size, outcome)
    handles = _outcome_handles(outcome)
    if (missing & (outcome != "undetermined")).any():
        handles.append(_NO_SIZE_HANDLE)
    ax_size.legend(handles=handles, loc="best", fontsize="small")
    ax_size.set_ylabel(SIZE_LABEL)
    ax_size.grid(True, linewidth=0.4, alpha=0.5)
    ax_size.tick_params(labelbottom=False)
    main.suptitle(f"{scene_title(results)}: limit cycle size against \u03bc")

    cycle = (outcome == "stick_slip") & np.isfinite(a)
    if cycle.any():
        ax_a.plot(
            mu[cycle],
            a[cycle],
            linestyle="none",
            marker="o",
            markersize=6,
            markerfacecolor=SLIDE_COLOR,
            markeredgecolor=OUTCOME_STYLE["stick_slip"]["edge"],
            label="stick_slip (converged cycle)",
            gid="a_points",
        )
    if cycle.sum() >= 2 and np.ptp(mu[cycle]) > 0:
        slope, intercept = np.polyfit(mu[cycle], a[cycle], 1)
        line_mu = np.array([mu[cycle].min(), mu[cycle].max()])
        sign = "-" if intercept < 0 else "+"
        residual = np.max(np.abs(a[cycle] - (slope * mu[cycle] + intercept)))
        ax_a.plot(
            line_mu,
            slope * line_mu + intercept,
            color=STICK_COLOR,
            linewidth=1.2,
            label=f"least squares: a = {slope:.4g} m \u00b7 \u03bc {sign} {abs(intercept):.3g} m "
            f"(slope {slope:.4g} m, largest residual {residual:.2g} m)",
            gid="a_fit",
        )
    if cycle.any():
        ax_a.legend(loc="best", fontsize="small")
    else:
        ax_a.text(
            0.5,
            0.5,
            "no converged stick_slip cycle: a is measured only on converged cycles\n"
            "(scan mode converge)",
            transform=ax_a.transAxes,
            ha="center",
            va="center",
            fontsize="small",
        )
        ax_a.set_ylim(0.0, 1.0)
    ax_a.set_ylabel(A_LABEL)
    ax_a.set_xlabel(MU_LABEL)
    ax_a.grid(True, linewidth=0.4, alpha=0.5)
    main.align_ylabels([ax_size, ax_a])
    return fig


@styled
def plot_scan_family(results: xr.Dataset) -> Figure:
    """A scan of mu and one more key: `size` against mu, one curve per value of that key.

    Curves differ in colour and marker size (the first drawn largest, so that coinciding
    curves stay visible); marker faces are coloured by outcome as in `plot_scan_mu`. Points
    without a size sit hollow on the bottom edge of the axes, one row per curve. The legends
    (the key's values with their unit; the outcomes) are right of the axes.
    """
    if figure_kind(results) != "scan_family":
        raise ValueError("plot_scan_family needs a scan result over mu and one more key")
    mu_dim = _mu_dim(results)
    (other,) = [d for d in results["outcome"].dims if d != mu_dim]
    ds = _sorted_scan(results, mu_dim, other)
    mu = np.asarray(ds[mu_dim].values, float)
    values = np.asarray(ds[other].values, float)
    outcome_all = np.asarray(ds["outcome"].values).astype(str)
    size_all = np.asarray(ds["size"].values, float)
    n = values.size

    fig, main, _ = new_figure(results, 8.4, 5.4, 0)
    ax = main.add_subplot()
    finite_all = size_all[np.isfinite(size_all)]
    ax.set_xlim(*_padded(mu.min(), mu.max(), 0.04))
    if finite_all.size:
        ax.set_ylim(*_padded(finite_all.min(), finite_all.max(), 0.08))
    else:
        ax.set_ylim(0.0, 1.0)
    missing = ~np.isfinite(size_all) | (outcome_all == "undetermined")
    rows_needed = [k for k in range(n) if missing[k].any()]
    rug_rows = {k: RUG_Y + 0.035 * j for j, k in enumerate(rows_needed)}
    if rows_needed:
        _make_rug_room(ax, 0.03 + 0.035 * len(rows_needed))

    colors = (
        [colormaps["tab10"](k) for k in range(n)]
        if n <= 10
        else [colormaps["viridis"](k / max(n - 1, 1)) for k in range(n)]
    )
    family_handles = []
    for k in range(n):
        size = size_all[k]
        color = colors[k]
        finite = np.isfinite(size)
        ax.plot(mu[finite], size[finite], color=color, linewidth=1.4, zorder=3, gid=f"family{k}")
        _outcome_markers(
            ax,
            mu,
            size,
            outcome_all[k],
            size=max(4.0, 10.0 - 2.0 * k),
            edge=color,
            rug_y=rug_rows.get(k, RUG_Y),
            gid=f"f{k}_",
        )
        family_handles.append(
            Line2D(
                [],
                [],
                color=color,
                linewidth=1.4,
                marker="o",
                markersize=6,
                markerfacecolor="white",
                markeredgecolor=color,
                markeredgewidth=1.5,
                label=_value_text(ds[other], float(values[k])),
            )
        )
    first = ax.legend(
        handles=family_handles,
        title=re.sub(r"\s*\[[^\]]*\]$", "", axis_label(ds[other])),
        loc="upper left",
        bbox_to_anchor=(1.02, 1.0),
        fontsize="small",
        title_fontsize="small",
    )
    ax.add_artist(first)
    outcome_handles = _outcome_handles(outcome_all)
    if (missing & (outcome_all != "undetermined")).any():
        outcome_handles.append(_NO_SIZE_HANDLE)
    ax.legend(
        handles=outcome_handles,
        title="outcome (marker face)",
        loc="lower left",
        bbox_to_anchor=(1.02, 0.0),
        fontsize="small",
        title_fontsize="small",
    )
    ax.set_xlabel(MU_LABEL)
    ax.set_ylabel(SIZE_LABEL)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    main.suptitle(
        f"{scene_title(results)}: limit cycle size against \u03bc, "
        f"one curve per {str(ds[other].attrs.get('scene_key', other)).split('.')[-1]}"
    )
    return fig


# ---- dispatch ----------------------------------------------------------------------------
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
