"""Figures from results; nothing here simulates.

`plot_orbit` draws the orbit of the slave like the paper's Figs 4-5: the path of the pin (or
disk centre) in the fixed frame, sticking phases dark and sliding phases light, with the
master axis and the spring rest position marked.

This module never selects a matplotlib backend: figures are built with
`matplotlib.figure.Figure` directly (no pyplot state) unless an existing Axes is passed in.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from frictiondisk.figures.footer import FOOTER_KEY, footer_text
from frictiondisk.figures.style import SLIDE_COLOR, STICK_COLOR, styled  # noqa: F401 (re-exported)
from frictiondisk.model.headline import scene_headline
from frictiondisk.simulation.result import SimulationResult
from frictiondisk.store.files import atomic_write

STICK_WIDTH = 2.2
SLIDE_WIDTH = 1.0

FIGURE_FORMATS = {".png": "png", ".pdf": "pdf", ".svg": "svg"}
# where each format keeps the footer in its metadata (matplotlib's savefig `metadata=`)
FOOTER_FIELD = {"png": FOOTER_KEY, "pdf": "Subject", "svg": "Description"}


@styled
def plot_orbit(result: SimulationResult, config: Any, ax: Axes | None = None) -> Figure:
    """Draw the orbit y(x) of the slave position recorded in `result`.

    Segments during which every contact sticks (the slave moves rigidly with the master) are
    drawn dark and thick, all others light and thin; a segment takes the mode of the sample it
    starts at. The master axis (origin) is marked with '+', the spring rest position
    (x_ms, 0) with 'x'. Axes are in metres with equal aspect.

    Parameters
    ----------
    result:
        A run made with recording on (`result.trajectory` is not None).
    config:
        The scene configuration of the run (for scene, mu and x_ms).
    ax:
        Axes to draw into; a new Figure is made when None.

    Returns
    -------
    The Figure holding the plot.
    """
    traj = result.trajectory
    if traj is None:
        raise ValueError(
            "the result holds no trajectory: run the simulation with recording on "
            "(simulate(config, record=True, ...))"
        )
    head = scene_headline(config)

    if ax is None:
        fig = Figure(figsize=(6.4, 6.0), layout="constrained")
        ax = fig.add_subplot()
    else:
        fig = ax.figure
    draw_orbit(ax, traj.x, traj.y, traj.all_stick, head["x_ms"])
    ax.set_title(
        f"{head['scene']}: \u03bc = {head['mu']:g}, x_ms = {head['x_ms']:g} m\n"
        f"outcome: {result.outcome}"
    )
    return fig


def draw_orbit(ax: Axes, x: Any, y: Any, stick: Any, x_ms: float) -> None:
    """Draw the path (x, y) [m] into `ax`: samples where every contact sticks (`stick`)
    start dark, thick segments, the others light, thin ones; the master axis is marked
    '+', the spring rest position (x_ms, 0) 'x'; equal aspect, axes in metres, a legend."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    points = np.column_stack([x, y])
    segments = np.stack([points[:-1], points[1:]], axis=1)  # (n - 1, 2, 2)
    stuck = np.asarray(stick, dtype=bool)[:-1]

    ax.add_collection(
        LineCollection(segments[~stuck], colors=SLIDE_COLOR, linewidths=SLIDE_WIDTH, zorder=2)
    )
    ax.add_collection(
        LineCollection(
            segments[stuck],
            colors=STICK_COLOR,
            linewidths=STICK_WIDTH,
            capstyle="round",
            zorder=3,
        )
    )
    ax.plot([0.0], [0.0], linestyle="none", marker="+", markersize=14, color="black", zorder=4)
    ax.plot([x_ms], [0.0], linestyle="none", marker="x", markersize=9, color="tab:red", zorder=4)
    finite = np.flatnonzero(np.isfinite(x) & np.isfinite(y))
    if finite.size:
        start = finite[0]
        ax.plot([x[start]], [y[start]], "o", ms=7, mfc="white", mec="black", zorder=5)
        _direction_arrows(ax, x[finite], y[finite])

    # Frame the orbit and both markers.
    xs = np.concatenate([x[np.isfinite(x)], [0.0, x_ms]])
    ys = np.concatenate([y[np.isfinite(y)], [0.0]])
    ax.update_datalim(np.column_stack([[xs.min(), xs.max()], [ys.min(), ys.max()]]))
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.05)
    ax.autoscale_view()

    handles = [
        Line2D([], [], color=STICK_COLOR, linewidth=STICK_WIDTH, label="sticking"),
        Line2D([], [], color=SLIDE_COLOR, linewidth=SLIDE_WIDTH, label="sliding"),
        Line2D(
            [], [], linestyle="none", marker="+", markersize=10, color="black", label="master axis"
        ),
        Line2D(
            [],
            [],
            linestyle="none",
            marker="x",
            markersize=8,
            color="tab:red",
            label="spring rest position",
        ),
        Line2D([], [], ls="none", marker="o", ms=6, mfc="white", mec="black", label="start"),
        Line2D([], [], ls="none", marker=">", ms=6, color="black", label="direction of motion"),
    ]
    ax.legend(handles=handles, loc="best", fontsize="small")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, linewidth=0.4, alpha=0.5)


def _direction_arrows(ax: Axes, x: np.ndarray, y: np.ndarray, count: int = 4) -> None:
    """Arrowheads along the path (x, y) at `count` places, pointing the way it is travelled."""
    step = np.hypot(np.diff(x), np.diff(y))
    length = np.concatenate([[0.0], np.cumsum(step)])
    if length[-1] <= 0.0:
        return
    span = max(np.ptp(x), np.ptp(y), 1e-12)
    for frac in (np.arange(count) + 0.5) / count:
        i = int(np.searchsorted(length, frac * length[-1]))
        j = int(np.searchsorted(length, length[i] + 0.02 * span))  # ~2 % of the view ahead
        if j >= len(x) or (x[j], y[j]) == (x[i], y[i]):
            continue
        ax.annotate(
            "",
            xy=(x[j], y[j]),
            xytext=(x[i], y[i]),
            arrowprops={"arrowstyle": "-|>", "color": "black", "lw": 0.8, "mutation_scale": 12},
            zorder=5,
        )


def save_figure(fig: Figure, path: str | os.PathLike[str]) -> Path:
    """Save `fig` to `path`, format chosen by the suffix (.png, .pdf or .svg).

    Missing parent directories are created; the file is written to a temporary name next to
    `path` and renamed, so a reader never sees a partial image. The figure's footer (its
    caption, footer.py) goes into the file's metadata too (PNG: the "Description" text
    chunk), so that which numerics made a figure can be read without its pixels. Returns
    the path written.
    """
    path = Path(path)
    fmt = FIGURE_FORMATS.get(path.suffix.lower())
    if fmt is None:
        raise ValueError(
            f"cannot tell the figure format from {str(path)!r}: "
            f"expected a suffix among {', '.join(FIGURE_FORMATS)}"
        )
    footer = footer_text(fig)
    metadata = {FOOTER_FIELD[fmt]: footer} if footer else None
    return atomic_write(path, lambda tmp: fig.savefig(tmp, format=fmt, dpi=150, metadata=metadata))
