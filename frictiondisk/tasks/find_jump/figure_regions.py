"""The region labels of the line figure of a find_jump campaign: each side of the line
named where it lies farthest from the line, the points and the runs shown (paper Fig. 9)."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from frictiondisk.figures.shared import FAIL_COLOR, REGION_FONT_PT
from frictiondisk.tasks.find_jump.figure_line_data import JumpLine, ShownRuns


def free_spot(
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


def label_regions(
    fig: Figure,
    ax: Axes,
    line: JumpLine,
    runs: ShownRuns,
    labels: tuple[tuple[str, bool, str], ...],
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
        spot = free_spot(ax, line.x[sel], line.mu_star[sel], others, above, box, axes_in)
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
