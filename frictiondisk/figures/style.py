"""The one plot style of every frictiondisk figure: colours, font sizes, matplotlib rc.

Every function that builds a figure is decorated with `styled`, which draws it inside
`matplotlib.rc_context(RC)`: the same fonts, line widths, grid and resolution whichever
command, notebook or benchmark asks, and whatever rcParams the caller has set. Figures
are built on `matplotlib.figure.Figure` (no pyplot state), so nothing here selects a
backend.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import TypeVar

from frictiondisk.verdict.outcomes import SLIDE_COLOR, STICK_COLOR  # noqa: F401 (the outcome records')

TITLE_FONT_PT = 11.0
LABEL_FONT_PT = 10.0
TICK_FONT_PT = 9.0
LEGEND_FONT_PT = 8.5
NOTE_FONT_PT = 7.0
CAPTION_FONT_PT = 7.0

RC: dict[str, object] = {
    "font.family": "DejaVu Sans",
    "font.size": LABEL_FONT_PT,
    "axes.titlesize": TITLE_FONT_PT,
    "axes.labelsize": LABEL_FONT_PT,
    "xtick.labelsize": TICK_FONT_PT,
    "ytick.labelsize": TICK_FONT_PT,
    "legend.fontsize": LEGEND_FONT_PT,
    "figure.titlesize": TITLE_FONT_PT + 1.0,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.6,
    "lines.linewidth": 1.5,
    "lines.markersize": 5.0,
    "errorbar.capsize": 3.0,
    "figure.dpi": 100,
    "savefig.dpi": 150,
    "savefig.bbox": "tight",
    "mathtext.default": "regular",
}

F = TypeVar("F", bound=Callable)


def styled(build: F) -> F:
    """Run a figure-building function inside the house style (`RC`)."""

    @functools.wraps(build)
    def wrapper(*args, **kwargs):
        import matplotlib

        with matplotlib.rc_context(RC):
            return build(*args, **kwargs)

    return wrapper  # type: ignore[return-value]
