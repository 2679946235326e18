"""Work-precision figure of an accuracy study (accuracy.nc in, matplotlib Figure out).

After DiffEqDevTools' work-precision sets: the error |mu* - mu*_ref| on the x axis, the
cost on the y axis, both logarithmic, one marker series per knob (per integrator for the
`method` knob), each point labelled with its setting. Left column: accepted integrator
steps summed over the bisection's runs; right column: their wall time. Top row: the
integrator knobs (rtol, method, preset), all against one reference, the tightest numerics
; bottom row: t_decide and the physics knobs, each against its
own limit (named in accuracy.nc's `reference`). A reference that is not a setting of its
knob's ladder (the tightest numerics, the Coulomb pin) is drawn once, as a black star.

The located mu* is a bracket midpoint, so an error below the bisection tolerance `tol`
says nothing: that region is shaded and the tol line drawn. Each point carries an error
bar of the two brackets' half widths (its own and its reference's). Errors below tol/10
(the references themselves, error 0) are drawn at tol/10 with open markers. Rows whose
bisection failed are listed under the figure, not drawn.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from frictiondisk.figures.footer import add_footer, data_footer
from frictiondisk.figures.style import styled
from frictiondisk.studies.accuracy.ladder import INTEGRATOR_KNOBS

COSTS = (
    ("n_steps", "accepted steps, summed over the bisection's runs"),
    ("wall_s", "wall time of the bisection's runs [s]"),
)
FLOOR_PER_TOL = 0.1  # errors below tol * this are drawn at that floor
MARKERS = "osD^v<>ph*X"


@styled
def work_precision_figure(ds: xr.Dataset) -> Figure:
    """The work-precision figure of `ds` (as written by `frictiondisk accuracy`)."""
    tol = float(ds.attrs["tol"])
    floor = FLOOR_PER_TOL * tol
    knobs = [str(k) for k in ds["knob"].values]
    groups: dict[str, list[int]] = {"integrator": [], "model and decision": []}
    added: dict[str, dict[str, list[int]]] = {kind: {} for kind in groups}
    for i, knob in enumerate(knobs):
        kind = "integrator" if knob in INTEGRATOR_KNOBS else "model and decision"
        if int(ds["in_ladder"].values[i]):
            groups[kind].append(i)
        else:  # a reference added to its knob: one black star per scene, not per knob
            added[kind].setdefault(str(ds["config_hash"].values[i]), []).append(i)
    for kind, refs in added.items():
        groups[kind] += [rows[0] for rows in refs.values()]
    kinds = [kind for kind, rows in groups.items() if rows]
    fig = Figure(figsize=(12, 4.6 * len(kinds) + 0.8), layout="constrained")
    axes = np.atleast_2d(fig.subplots(len(kinds), len(COSTS), squeeze=False))
    failed = []
    for r, kind in enumerate(kinds):
        rows = groups[kind]
        series = list(dict.fromkeys(_series_key(ds, i) for i in rows))
        for c, (cost, cost_label) in enumerate(COSTS):
            ax = axes[r, c]
            for s, key in enumerate(series):
                idx = [i for i in rows if _series_key(ds, i) == key]
                if not int(ds["in_ladder"].values[idx[0]]):
                    color, marker = "k", "*"
                    label = f"reference: {ds['label'].values[idx[0]]}"
                else:
                    color, marker = f"C{s % 10}", MARKERS[s % len(MARKERS)]
                    label = f"{key[0]}: {key[1]}"
                _draw_series(ax, ds, idx, cost, floor, color, marker)
                if c == 0:
                    ax.plot([], [], marker=marker, color=color, label=label)
            ax.axvspan(floor / 3, tol, color="0.9", zorder=0)
            ax.axvline(tol, color="0.4", ls="--", lw=1)
            ax.text(
                tol,
                1.0,
                " bisection tol",
                transform=ax.get_xaxis_transform(),
                va="top",
                ha="left",
                fontsize=7,
                color="0.3",
            )
            ax.set_xscale("log")
            _cost_scale(ax, np.isfinite(ds["error"].values[rows]).any())
            ax.set_xlabel("error |\u03bc* \u2212 \u03bc*_ref| [-]")
            ax.set_ylabel(cost_label)
            ax.grid(True, which="major", alpha=0.3)
            reference = (
                "reference: the tightest numerics"
                if kind == "integrator"
                else "each against its own limit (accuracy.nc 'reference')"
            )
            ax.set_title(f"{kind} knobs — {reference}", fontsize=9)
            if c == 0:
                ax.legend(fontsize=7, loc="best")
        failed += [i for i in rows if not math.isfinite(float(ds["error"].values[i]))]
    title = (
        f"work-precision of \u03bc*: campaign {ds.attrs.get('campaign_name', '?')}, "
        f"scene {ds.attrs.get('scene', '?')}, {ds.attrs.get('point', '')}, tol = {tol:g}"
    )
    fig.suptitle(title, fontsize=10)
    name = ds.attrs.get("campaign_name", "?")
    add_footer(fig, data_footer(f"frictiondisk accuracy, campaign {name}", [ds]))
    if failed:
        lines = [
            f"not shown: {ds['label'].values[i]} ({ds['status'].values[i]}: "
            f"{str(ds['reason'].values[i])[:90]})"
            for i in failed
        ]
        bottom = fig.get_layout_engine().get()["rect"][1]  # above the footer
        fig.text(0.01, bottom, "\n".join(lines), fontsize=6, va="bottom", ha="left")
        bottom += 0.012 * len(lines)
        fig.get_layout_engine().set(rect=(0, bottom, 1, 1 - bottom))
    return fig


def _cost_scale(ax, drawn: bool) -> None:
    """A log cost axis, or where no row of the panel has an error to draw (every
    bisection, or its reference, failed: listed under the figure) a note saying so; a log
    axis without positive data cannot be drawn."""
    if drawn:
        ax.set_yscale("log")
        return
    ax.set_yticks([])
    ax.text(
        0.5,
        0.5,
        "nothing to draw: no setting of these knobs\nhas an error (the failures are listed below)",
        transform=ax.transAxes,
        ha="center",
        va="center",
        fontsize=8,
        color="0.3",
    )


def _series_key(ds: xr.Dataset, i: int) -> tuple[str, str]:
    if not int(ds["in_ladder"].values[i]):  # an added reference: its own series
        return "reference", str(ds["config_hash"].values[i])
    return str(ds["knob"].values[i]), str(ds["series"].values[i])


def _draw_series(ax, ds: xr.Dataset, idx: list[int], cost: str, floor: float, color, marker):
    err = np.array([float(ds["error"].values[i]) for i in idx])
    bound = np.array([float(ds["error_bound"].values[i]) for i in idx])
    y = np.array([float(ds[cost].values[i]) for i in idx])
    tags = [str(ds["tag"].values[i]) for i in idx]
    ok = np.isfinite(err) & (y > 0)
    if not ok.any():
        return
    err, bound, y = err[ok], bound[ok], y[ok]
    tags = [t for t, keep in zip(tags, ok, strict=True) if keep]
    x = np.maximum(err, floor)
    ax.plot(x, y, "-", color=color, lw=1, alpha=0.6)
    clipped = err < floor
    ax.plot(x[~clipped], y[~clipped], marker, color=color, ms=5, ls="none")
    ax.plot(x[clipped], y[clipped], marker, mfc="none", color=color, ms=5, ls="none")
    shown = ~clipped
    lo = np.maximum(err[shown] - bound[shown], floor)
    ax.errorbar(
        x[shown],
        y[shown],
        xerr=[x[shown] - lo, bound[shown]],
        fmt="none",
        ecolor=color,
        elinewidth=0.8,
        capsize=2,
    )
    for xi, yi, tag in zip(x, y, tags, strict=True):
        ax.annotate(
            tag, (xi, yi), textcoords="offset points", xytext=(3, 3), fontsize=6, color=color
        )
