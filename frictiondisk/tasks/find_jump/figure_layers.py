"""What the find_jump figures (a line, a grid, sizes) share: the numbered list of failed
points, the points without a jump on their grid (an answer, not a failure), the label of
each point."""

from __future__ import annotations

import math
import textwrap

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.lines import Line2D
from matplotlib.transforms import blended_transform_factory

from frictiondisk.figures.shared import (
    LIST_WIDTH,
    MAX_LISTED,
    boundary_sides,
    searched_key,
    value_text,
)
from frictiondisk.figures.style import STICK_COLOR
from frictiondisk.tasks.jump_search.jump_result import NO_JUMP


def failure_lines(results: xr.Dataset, labels: list[str], failed: np.ndarray) -> list[str]:
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


# ---- points without a jump on their grid (status no_jump) ---------------------------------
def failed_and_without(results: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """Boolean masks, in the Dataset's order, of the failed points and of the points without
    a jump on their grid: NO_JUMP is an answer (no value of the grid sticks), not a failure."""
    status = np.asarray(results["status"].values).astype(str)
    without = status == NO_JUMP
    return (status != "converged") & ~without, without


def no_jump_label(results: xr.Dataset) -> str:
    """Legend text for points on whose whole prescan grid nothing sticks."""
    key = searched_key(results)
    sides = boundary_sides(results)
    top = float(results["scan_mu"].max()) if "scan_mu" in results.coords else math.nan
    grid = f"up to {key.symbol} = {top:.3g}" if math.isfinite(top) else "of the grid"
    verb = "sticks" if sides is None else f"gives {sides[1]}"
    return f"no jump: no value {grid} {verb} ({key.star} above)"


def mark_no_jump(ax: Axes, x: np.ndarray, label: str) -> Line2D:
    """Such points as open triangles at the top edge of a line's axes (mu* lies above the
    view); returns the legend entry."""
    style = {"linestyle": "none", "marker": "^", "markersize": 8, "color": STICK_COLOR}
    style |= {"markerfacecolor": "white"}  # open: no mu* to mark, only where it is not
    top = blended_transform_factory(ax.transData, ax.transAxes)
    ax.plot(
        x, np.full(x.size, 0.955), transform=top, clip_on=False, zorder=6, gid="no_jump", **style
    )
    return Line2D([], [], label=label, **style)


def point_labels(results: xr.Dataset) -> list[str]:
    """ "x_ms = 0.1 m, x0 = 0 m" for every point, in the Dataset's (C) order."""
    dims = list(results["mu_star"].dims)
    grids = np.meshgrid(*[results[d].values for d in dims], indexing="ij")
    flat = [g.reshape(-1) for g in grids]
    return [
        ", ".join(value_text(results[d], float(f[i])) for d, f in zip(dims, flat, strict=True))
        for i in range(flat[0].size)
    ]
