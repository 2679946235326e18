"""The figure of a `trajectory` campaign (paper Figs 4-5), from results.nc and trajectory.nc.

`show: whole` draws the orbit from the start through the transient onto the limit cycle;
`show: cycle` draws the last complete limit cycle only (between the last two instants at
which the slave started to stick as a whole), with the sticking circle of radius `size`
dashed and the deviation `a` (paper Fig. 5) marked where the slave is farthest outside it.
Sticking is dark, sliding light. Nothing here simulates.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
import yaml
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from frictiondisk.figures.plotting import STICK_COLOR, draw_orbit
from frictiondisk.figures.shared import new_figure
from frictiondisk.figures.style import styled

A_COLOR = "tab:orange"


def cycle_window(t: np.ndarray, all_stick: np.ndarray) -> tuple[float, float]:
    """(t0, t1) [s] of the last complete cycle: the last two instants at which every
    contact starts to stick. ValueError if the record holds fewer than two."""
    starts = t[1:][all_stick[1:] & ~all_stick[:-1]]
    if starts.size < 2:
        raise ValueError(
            f"trajectory: {starts.size} sticking phase(s) recorded, a complete cycle needs 2 "
            "(run longer, numerics.mode: converge)"
        )
    return float(starts[-2]), float(starts[-1])


@styled
def plot_trajectory(results: xr.Dataset, trajectory: xr.Dataset) -> Figure:
    """Orbit figure of a trajectory campaign (see the module docstring)."""
    show = str(results.attrs.get("show", "whole"))
    t = np.asarray(trajectory["time"].values, dtype=float)
    x = np.asarray(trajectory["x"].values, dtype=float)
    y = np.asarray(trajectory["y"].values, dtype=float)
    all_stick = np.all(np.asarray(trajectory["mode"].values) == 1, axis=1)
    scene, x_ms = _headline(trajectory)
    outcome = str(results["outcome"].values)
    mu = float(results.attrs.get("mu", np.nan))

    fig, plot, _ = new_figure(results, 8.4 if show == "cycle" else 6.4, 6.0, 0)
    ax = plot.subplots()
    if show == "cycle":
        t0, t1 = cycle_window(t, all_stick)
        keep = (t >= t0) & (t <= t1)
        draw_orbit(ax, x[keep], y[keep], all_stick[keep], x_ms)
        _mark_deviation(ax, x[keep], y[keep], all_stick[keep], float(results["size"].values))
        span = f"last cycle, t = {t0:.1f} to {t1:.1f} s"
    else:
        draw_orbit(ax, x, y, all_stick, x_ms)
        span = f"t = 0 to {t[-1]:.1f} s"
    ax.set_title(f"{scene}: \u03bc = {mu:g}, x_ms = {x_ms:g} m, {span}\noutcome: {outcome}")
    return fig


def _mark_deviation(ax, x, y, stick, size: float) -> None:
    """Dash the sticking circle |r| = size and mark a = max(|r| - size) while sliding."""
    if not np.isfinite(size):
        return
    phi = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(size * np.cos(phi), size * np.sin(phi), "--", color=STICK_COLOR, lw=0.8, zorder=1)
    r = np.hypot(x, y)
    sliding = ~stick
    if not sliding.any():
        return
    k = np.flatnonzero(sliding)[np.argmax(r[sliding])]
    a = r[k] - size
    foot = (x[k] * size / r[k], y[k] * size / r[k])
    ax.annotate(
        "",
        xy=(x[k], y[k]),
        xytext=foot,
        arrowprops={"arrowstyle": "<->", "color": A_COLOR, "lw": 1.4},
        zorder=5,
    )
    ax.text(
        (x[k] + foot[0]) / 2,
        (y[k] + foot[1]) / 2,
        f"  a = {a:.4f} m",
        color=A_COLOR,
        fontsize=9,
        ha="left",
        va="center",
    )
    handles = list(ax.get_legend().legend_handles)
    handles += [
        Line2D([], [], ls="--", color=STICK_COLOR, lw=0.8, label=f"sticking circle {size:.4f} m"),
        Line2D([], [], color=A_COLOR, lw=1.4, label="deviation a while sliding"),
    ]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small")


def _headline(trajectory: xr.Dataset) -> tuple[str, float]:
    """Scene name and x_ms [m] from the configuration stored with the trajectory."""
    scene = yaml.safe_load(str(trajectory.attrs.get("scene_yaml", ""))) or {}
    return str(scene.get("scene", "?")), float((scene.get("params") or {}).get("x_ms", 0.0))
