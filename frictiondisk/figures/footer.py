"""The footer of a figure: one grey line (or a few) at its bottom saying what made it,
with the package and numerics versions, and the same text in the saved file's metadata.

A campaign figure's footer is its caption (shared.new_figure, from the results' attributes,
so it names the numerics that computed the data). A figure drawn without one gets a
footer here: `data_footer` from the attributes of the datasets it draws, `code_footer`
for a study that computed its data just now with this code. `save_figure`
(plotting.py) writes `footer_text(fig)` into the file too, so that a test or a user can
read which numerics made a PNG without reading its pixels.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

from matplotlib.figure import Figure, SubFigure
from matplotlib.layout_engine import ConstrainedLayoutEngine, TightLayoutEngine
from matplotlib.text import Text

from frictiondisk.figures.style import CAPTION_FONT_PT
from frictiondisk.store.journal_entry import kernel_version
from frictiondisk.version import __version__

FOOTER_GID = "caption"  # the gid of the caption of shared.new_figure, and of add_footer's text
FOOTER_KEY = "Description"  # the PNG text chunk (PDF: "Subject") that holds the footer
LINE_HEIGHT_IN = CAPTION_FONT_PT * 1.4 / 72.0  # one footer line [in]
NUMERICS_RE = re.compile(r"\bnumerics (\d+)\b")  # "numerics 7" in kernel_version's text
FOOTER_SEP = " | "  # between the parts of a footer; a line breaks only there
CHAR_WIDTH_EM = 0.56  # mean width of a character of the footer's font [font size]


def wrap_parts(parts: list[str], width: int) -> list[str]:
    """Join footer parts into lines of at most `width` characters (a part is never split)."""
    lines: list[str] = []
    for part in parts:
        if lines and len(lines[-1]) + len(FOOTER_SEP) + len(part) <= width:
            lines[-1] += FOOTER_SEP + part
        else:
            lines.append(part)
    return lines


def chars_per_line(width_in: float) -> int:
    """How many footer characters fit on a line `width_in` inches wide."""
    return int(width_in * 72 / (CHAR_WIDTH_EM * CAPTION_FONT_PT))


def figure_texts(fig: Figure | SubFigure) -> list[Text]:
    """The texts placed on `fig` and its subfigures (fig.text), not those of its axes."""
    return [*fig.texts, *(text for sub in fig.subfigs for text in figure_texts(sub))]


def footer_text(fig: Figure) -> str | None:
    """The text of `fig`'s footer (every figure text with gid FOOTER_GID), or None if it
    has none. (Not Figure.findobj: that asks every axis for its ticks, which fails on a log
    axis without positive data.)"""
    found = [t.get_text() for t in figure_texts(fig) if t.get_gid() == FOOTER_GID and t.get_text()]
    return "\n".join(dict.fromkeys(found)) or None


def numerics_versions(text: str) -> list[int]:
    """The numerics versions a footer names ("numerics 7, numba ..." -> [7])."""
    return [int(match) for match in NUMERICS_RE.findall(text)]


def code_footer(what: str) -> str:
    """The footer of a figure whose data this code computed just now: `what` (the command
    that drew it), the package version and this code's numerics version."""
    return f"{what} | frictiondisk {__version__} | {kernel_version()}"


def data_footer(what: str, datasets: Iterable[Any]) -> str:
    """The footer of a figure drawn from `datasets` (anything with .attrs as the store
    writes them): `what`, then each distinct frictiondisk and numerics version they name
    ("?" where a dataset names none)."""
    attrs = [dataset.attrs for dataset in datasets]
    packages = dict.fromkeys(str(a.get("frictiondisk_version", "?")) for a in attrs)
    kernels = dict.fromkeys(str(a.get("kernel_version", "numerics ?")) for a in attrs)
    return f"{what} | frictiondisk {', '.join(packages)} | {'; '.join(kernels)}"


def add_footer(fig: Figure, text: str) -> None:
    """Write `text` at the bottom left of `fig` in the caption's style and keep the plots
    above it: a constrained layout gets a smaller rectangle, any other figure a tight
    layout in the rectangle above the footer. Lines break at FOOTER_SEP to fit the width."""
    width = chars_per_line(fig.get_figwidth() * 0.98)
    text = "\n".join(
        "\n".join(wrap_parts(line.split(FOOTER_SEP), width)) for line in text.split("\n")
    )
    height = (LINE_HEIGHT_IN * (text.count("\n") + 1) + 0.1) / fig.get_figheight()
    fig.text(
        0.01,
        0.5 * height,
        text,
        ha="left",
        va="center",
        fontsize=CAPTION_FONT_PT,
        color="0.3",
        gid=FOOTER_GID,
    )
    engine = fig.get_layout_engine()
    if isinstance(engine, ConstrainedLayoutEngine):
        engine.set(rect=(0.0, height, 1.0, 1.0 - height))
    else:
        fig.set_layout_engine(TightLayoutEngine(rect=(0.0, height, 1.0, 1.0)))
