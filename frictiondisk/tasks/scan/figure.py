"""The figures of a scan campaign: `plot_scan_mu` (mu alone, paper Figs 6-7) and
`plot_scan_family` (mu and one more key, one size curve per value of that key); which of
them fits the results (`figure_kind`) and `plot_scan`, which draws it.

Markers are coloured by outcome; points without a size sit hollow on the bottom edge of
the axes.
"""

from __future__ import annotations

import re

import numpy as np
import xarray as xr
import yaml
from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.transforms import blended_transform_factory

from frictiondisk.figures.shared import (
    A_LABEL,
    MU_LABEL,
    OUTCOME_LABEL,
    OUTCOME_STYLE,
    RUG_Y,
    SIZE_LABEL,
    axis_label,
    check_vars,
    make_rug_room,
    new_figure,
    padded,
    scene_title,
    value_text,
)
from frictiondisk.figures.style import SLIDE_COLOR, STICK_COLOR, styled
from frictiondisk.tasks.scan.spec import DEFAULT_SCAN_MODE, Scan
from frictiondisk.verdict.outcomes import STICK_SLIP, UNDETERMINED

FIGURE_KINDS = ("scan_mu", "scan_family")
SCAN_VARS = ("outcome", "reason", "size", "a")

_NO_SIZE_HANDLE = Line2D(
    [],
    [],
    linestyle="none",
    marker="o",
    markerfacecolor="none",
    markeredgecolor="0.35",
    label="hollow, below the dotted line: no size",
)


def mu_dimension(ds: xr.Dataset) -> str | None:
    """The dimension of a scan that varies mu (scene key params.mu), or None."""
    for dim in ds.dims:
        if dim in ds.coords and ds[dim].attrs.get("scene_key") == "params.mu":
            return str(dim)
    return "mu" if "mu" in ds.dims else None


def figure_kind(results: xr.Dataset) -> str:
    """One of FIGURE_KINDS; ValueError (saying what is wrong) for results it cannot draw."""
    check_vars(results, SCAN_VARS, "results (scan)")
    dims = list(results.dims)
    if mu_dimension(results) is None:
        raise ValueError(f"a scan result varies mu, this one varies only {dims}")
    if len(dims) == 1:
        return "scan_mu"
    if len(dims) == 2:
        return "scan_family"
    raise ValueError(f"a scan varies mu and at most one more key, this one {dims}")


def scan_mode(results: xr.Dataset) -> str:
    """The numerics.mode every run of the scan ran in: its own `mode` (campaign_yaml)."""
    try:
        spec = yaml.safe_load(str(results.attrs.get("campaign_yaml", ""))) or {}
        return (spec.get(Scan.kind) or {}).get("mode", DEFAULT_SCAN_MODE)
    except (yaml.YAMLError, AttributeError):
        return DEFAULT_SCAN_MODE


def plot_scan(results: xr.Dataset) -> Figure:
    """The figure that fits a scan's results (`figure_kind`)."""
    if figure_kind(results) == "scan_mu":
        return plot_scan_mu(results)
    return plot_scan_family(results)


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
        finite = mask & np.isfinite(value) & (name != UNDETERMINED)
        missing = mask & ~finite
        kwargs = {
            "linestyle": "none",
            "marker": style["marker"],
            "markersize": size,
            "markerfacecolor": style["color"],
            "markeredgecolor": style["edge"] if edge is None or name == UNDETERMINED else edge,
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
                **{**kwargs, "markerfacecolor": "none" if name != UNDETERMINED else None},
            )
    return on_rug


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
    mu_dim = mu_dimension(results)
    ds = _sorted_scan(results, mu_dim)
    mu = np.asarray(ds[mu_dim].values, float)
    outcome = np.asarray(ds["outcome"].values).astype(str)
    size = np.asarray(ds["size"].values, float)
    a = np.asarray(ds["a"].values, float)

    fig, main, _ = new_figure(results, 7.2, 6.6, 0, scan_mode(results))
    ax_size, ax_a = main.subplots(2, 1, sharex=True, height_ratios=[3, 2])

    finite = np.isfinite(size)
    ax_size.plot(mu[finite], size[finite], color="0.75", linewidth=0.8, zorder=2)
    if not finite.any():
        ax_size.set_ylim(0.0, 1.0)
    ax_size.margins(x=0.04, y=0.1)
    missing = ~finite | (outcome == UNDETERMINED)
    if missing.any():
        make_rug_room(ax_size, 0.08)
    _outcome_markers(ax_size, mu, size, outcome)
    handles = _outcome_handles(outcome)
    if (missing & (outcome != UNDETERMINED)).any():
        handles.append(_NO_SIZE_HANDLE)
    ax_size.legend(handles=handles, loc="best", fontsize="small")
    ax_size.set_ylabel(SIZE_LABEL)
    ax_size.grid(True, linewidth=0.4, alpha=0.5)
    ax_size.tick_params(labelbottom=False)
    main.suptitle(f"{scene_title(results)}: limit cycle size against \u03bc")

    cycle = (outcome == STICK_SLIP) & np.isfinite(a)
    if cycle.any():
        ax_a.plot(
            mu[cycle],
            a[cycle],
            linestyle="none",
            marker="o",
            markersize=6,
            markerfacecolor=SLIDE_COLOR,
            markeredgecolor=OUTCOME_STYLE[STICK_SLIP]["edge"],
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
    mu_dim = mu_dimension(results)
    (other,) = [d for d in results["outcome"].dims if d != mu_dim]
    ds = _sorted_scan(results, mu_dim, other)
    mu = np.asarray(ds[mu_dim].values, float)
    values = np.asarray(ds[other].values, float)
    outcome_all = np.asarray(ds["outcome"].values).astype(str)
    size_all = np.asarray(ds["size"].values, float)
    n = values.size

    fig, main, _ = new_figure(results, 8.4, 5.4, 0, scan_mode(results))
    ax = main.add_subplot()
    finite_all = size_all[np.isfinite(size_all)]
    ax.set_xlim(*padded(mu.min(), mu.max(), 0.04))
    if finite_all.size:
        ax.set_ylim(*padded(finite_all.min(), finite_all.max(), 0.08))
    else:
        ax.set_ylim(0.0, 1.0)
    missing = ~np.isfinite(size_all) | (outcome_all == UNDETERMINED)
    rows_needed = [k for k in range(n) if missing[k].any()]
    rug_rows = {k: RUG_Y + 0.035 * j for j, k in enumerate(rows_needed)}
    if rows_needed:
        make_rug_room(ax, 0.03 + 0.035 * len(rows_needed))

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
                label=value_text(ds[other], float(values[k])),
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
    if (missing & (outcome_all != UNDETERMINED)).any():
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
