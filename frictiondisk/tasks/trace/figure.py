"""The figure of a trace campaign: every jump curve of a (key, mu) plane (`plot_trace`).

Each curve is drawn through its certified points, with a shaded band on its sticking side
(a curve's points are stored with the sticking side on the left of their order); folds,
where two jumps meet and a sticking window or gap closes, are marked with their bracket;
uncertain points are hollow; the first look's keys are thin vertical lines; optionally
every run of runs.nc as a dot in its outcome's style, which shows how the curves were
followed. A trace `between` two motions names them in the title and shades the side of
its upper motion in that motion's colour.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle

from frictiondisk.figures.curves import curve_points
from frictiondisk.figures.shared import (
    FAIL_COLOR,
    LINE_COLOR,
    MU_LABEL,
    NON_MONOTONE_COLOR,
    axis_label,
    boundary_sides,
    check_vars,
    new_figure,
    run_dots,
    scene_title,
)
from frictiondisk.figures.style import STICK_COLOR, styled
from frictiondisk.store.cf import flag_meanings
from frictiondisk.verdict.outcomes import record

BAND = 0.025  # width of the sticking side's band, as a fraction of the plane
CURVE_COLORS = ("0.15", "#6a3d9a", "#b15928", "#1f78b4", "#33a02c", "#e31a1c")
TRACE_VARS = ("point_curve", "mu_star", "curve_first_point", "curve_points", "certification")


def _band(key: np.ndarray, mu: np.ndarray, spans: tuple[float, float]) -> np.ndarray:
    """The polygon between a curve and its copy moved BAND to its left, in units of the
    view's `spans`: the sticking side."""
    x, y = key / spans[0], mu / spans[1]
    tx, ty = np.gradient(x), np.gradient(y)
    length = np.hypot(tx, ty)
    length[length == 0] = 1.0
    nx, ny = -ty / length, tx / length
    inner = np.column_stack([x, y])
    outer = np.column_stack([x + BAND * nx, y + BAND * ny])[::-1]
    polygon = np.vstack([inner, outer])
    return polygon * np.asarray(spans)


@styled
def plot_trace(
    results: xr.Dataset, runs: xr.Dataset | None = None, *, show_runs: bool = False
) -> Figure:
    """The jump curves of a trace results.nc in the (key, mu) plane (see the module
    docstring); `show_runs` overlays every run of `runs` (runs.nc)."""
    check_vars(results, TRACE_VARS, "results (trace)")
    if show_runs and runs is None:
        raise ValueError("show_runs needs the runs Dataset (runs.nc)")
    name = str(results.attrs["trace_key_var"])
    key_lo, key_hi = (float(v) for v in np.atleast_1d(results.attrs["key_range"]))
    mu_lo, mu_hi = (float(v) for v in np.atleast_1d(results.attrs["mu_range"]))
    spans = (key_hi - key_lo, mu_hi - mu_lo)
    view = _mu_view(np.asarray(results["mu_star"].values, float), results, (mu_lo, mu_hi))

    fig, main, _ = new_figure(results, 7.2, 5.4, 0)
    ax = main.add_subplot()
    handles = _draw_first_look(ax, results, name)
    if show_runs and runs is not None:
        check_vars(runs, (name, "mu", "outcome"), "runs")
        handles += run_dots(
            ax,
            np.asarray(runs[name].values, float),
            np.asarray(runs["mu"].values, float),
            np.asarray(runs["outcome"].values).astype(str),
        )
    # the band's width is a fraction of the view
    handles += _draw_curves(ax, results, name, (key_lo, mu_lo), (spans[0], view[1] - view[0]))
    handles += _draw_uncertain(ax, results, name)
    handles += _draw_folds(ax, results, name)

    # the plane, zoomed to its curves in mu (a plane may be much taller than its curves)
    ax.add_patch(
        Rectangle((key_lo, mu_lo), *spans, fill=False, edgecolor="0.6", linewidth=0.8, zorder=0)
    )
    ax.set_xlim(key_lo - 0.02 * spans[0], key_hi + 0.02 * spans[0])
    ax.set_ylim(*view)
    ax.set_xlabel(axis_label(results[name]))
    ax.set_ylabel(MU_LABEL)
    if not results.sizes["curve"]:
        ax.text(
            0.5,
            0.5,
            "no jump curve found",
            transform=ax.transAxes,
            ha="center",
            va="center",
            color=FAIL_COLOR,
        )
    main.suptitle(f"{scene_title(results)}: {_title(results, name)}", wrap=True)
    if handles:
        ax.legend(
            handles=handles,
            loc="lower left",
            bbox_to_anchor=(0.0, 1.01),
            ncols=2,
            fontsize="small",
            frameon=False,
        )
    return fig


def _draw_first_look(ax, results: xr.Dataset, name: str) -> list[Any]:
    """The keys of the first look as thin vertical lines; their legend entry."""
    for k in np.atleast_1d(results[f"look_{name}"].values) if f"look_{name}" in results else []:
        ax.axvline(float(k), color="0.75", linewidth=0.8, linestyle=":", zorder=0)
    if f"look_{name}" in results and results.sizes.get("look"):
        label = "first look (keys searched in \u03bc)"
        return [Line2D([], [], color="0.75", linestyle=":", label=label)]
    return []


def _title(results: xr.Dataset, name: str) -> str:
    """ "jump curves in the (x_ms, \u03bc) plane", or for a boundary between two motions
    "boundary curves between A and B in the ... plane"."""
    sides = boundary_sides(results)
    plane = f"in the ({name}, \u03bc) plane"
    if sides is None:
        return f"jump curves {plane}"
    return f"boundary curves between {sides[0]} and {sides[1]} {plane}"


def _shaded_side(results: xr.Dataset) -> tuple[str, str]:
    """(legend text, colour) of the side left of a curve's order: sticking for the stick
    jump, the upper motion of `between` (its outcome colour) else."""
    sides = boundary_sides(results)
    if sides is None:
        return "its sticking side", STICK_COLOR
    try:
        color = record(sides[1]).color
    except ValueError:
        color = STICK_COLOR
    return f"its {sides[1]} side", color


def _draw_curves(ax, results: xr.Dataset, name: str, origin, shown) -> list[Any]:
    """Each curve through its points, its sticking side shaded (a band `shown` wide in
    units of the view, from `origin`: the plane's low corner); their legend entries."""
    key_lo, mu_lo = origin
    side_label, side_color = _shaded_side(results)
    for c, (points_key, points_mu) in enumerate(curve_points(results, name)):
        color = CURVE_COLORS[c % len(CURVE_COLORS)]
        ck, cm = points_key, points_mu  # a closed curve's line returns to its first point
        if int(results["curve_closed"][c]) and len(ck) > 2:
            ck, cm = np.append(ck, ck[0]), np.append(cm, cm[0])
        if len(ck) > 1:
            ax.fill(
                *_band(ck - key_lo, cm - mu_lo, shown).T + np.array([[key_lo], [mu_lo]]),
                color=side_color,
                alpha=0.18,
                linewidth=0,
                zorder=1,
            )
        ax.plot(ck, cm, "-", color=color, linewidth=1.4, zorder=3)
        ax.plot(points_key, points_mu, "o", color=color, markersize=3.2, zorder=4)
    if not results.sizes["curve"]:
        return []
    tol = float(results.attrs["tol"])
    return [
        Line2D(
            [],
            [],
            color=LINE_COLOR,
            marker="o",
            markersize=3.2,
            label=f"{'jump' if boundary_sides(results) is None else 'boundary'} curve: "
            f"certified points, tol {tol:g} in \u03bc",
        ),
        Patch(color=side_color, alpha=0.18, label=side_label),
    ]


def _draw_uncertain(ax, results: xr.Dataset, name: str) -> list[Any]:
    """The uncertain points, hollow; their legend entry."""
    flags = flag_meanings(results["certification"])
    uncertain = np.asarray(
        [flags.get(int(v)) == "uncertain" for v in results["certification"].values]
    )
    if not uncertain.any():
        return []
    key = np.asarray(results[name].values, float)
    mu = np.asarray(results["mu_star"].values, float)
    hollow = {"markersize": 7, "markerfacecolor": "white", "markeredgecolor": LINE_COLOR}
    ax.plot(key[uncertain], mu[uncertain], "o", zorder=5, gid="uncertain", **hollow)
    label = "uncertain: not confirmed by stricter numerics"
    return [Line2D([], [], linestyle="none", marker="o", label=label, **hollow)]


def _mu_view(mu: np.ndarray, results: xr.Dataset, plane: tuple[float, float]):
    """Limits of the mu axis: the curves and folds, padded, within the plane (padded)."""
    shown = [mu[np.isfinite(mu)]]
    if results.sizes.get("fold"):
        shown += [np.asarray(results[n].values, float) for n in ("fold_mu_lo", "fold_mu_hi")]
    values = np.concatenate(shown)
    values = values[np.isfinite(values)]
    span = plane[1] - plane[0]
    if values.size == 0:
        return plane[0] - 0.02 * span, plane[1] + 0.02 * span
    lo, hi = float(values.min()), float(values.max())
    pad = max(0.08 * (hi - lo), 0.02 * span * (hi - lo == 0))
    return max(plane[0] - 0.02 * span, lo - pad), min(plane[1] + 0.02 * span, hi + pad)


def _draw_folds(ax, results: xr.Dataset, name: str) -> list[Any]:
    """Every fold: a star at its tip, with its bracket; failed ones red."""
    if not results.sizes.get("fold"):
        return []
    handles = []
    status = np.asarray(results["fold_status"].values).astype(str)
    k = np.asarray(results[f"fold_{name}"].values, float)
    m = np.asarray(results["fold_mu"].values, float)
    k_in = np.asarray(results[f"fold_{name}_in"].values, float)
    k_out = np.asarray(results[f"fold_{name}_out"].values, float)
    lo = np.asarray(results["fold_mu_lo"].values, float)
    hi = np.asarray(results["fold_mu_hi"].values, float)
    located = status == "located"
    if located.any():
        ax.errorbar(
            k[located],
            m[located],
            xerr=np.abs(
                [
                    k[located] - np.minimum(k_in, k_out)[located],
                    np.maximum(k_in, k_out)[located] - k[located],
                ]
            ),
            yerr=[m[located] - lo[located], hi[located] - m[located]],
            fmt="*",
            color=NON_MONOTONE_COLOR,
            markersize=13,
            markeredgecolor="black",
            markeredgewidth=0.6,
            zorder=6,
            gid="folds",
        )
        handles.append(
            Line2D(
                [],
                [],
                linestyle="none",
                marker="*",
                markersize=11,
                color=NON_MONOTONE_COLOR,
                markeredgecolor="black",
                label="fold: two jumps meet (window or gap closes)",
            )
        )
    failed = ~located & np.isfinite(k_in)
    if failed.any():
        ax.plot(
            k_in[failed],
            np.where(np.isfinite(m), m, lo)[failed],
            "x",
            color=FAIL_COLOR,
            markersize=9,
            zorder=6,
        )
        handles.append(
            Line2D(
                [],
                [],
                linestyle="none",
                marker="x",
                color=FAIL_COLOR,
                label="fold not located (see results.nc fold_reason)",
            )
        )
    return handles
