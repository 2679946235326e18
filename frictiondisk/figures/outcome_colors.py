"""A colour for every outcome a figure shows: the campaign figures' own colours
(figures/shared.py OUTCOME_STYLE), then a fixed palette for any outcome they do not know,
so an outcome added later still gets a colour of its own. Shared by the figures that
colour cells by outcome (basin maps, motion maps)."""

from __future__ import annotations

from frictiondisk.figures.shared import OUTCOME_STYLE

EXTRA_COLORS = ("tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink", "tab:olive")


def outcome_colors(outcomes: list[str]) -> dict[str, str]:
    """A colour per outcome: the campaign figures' colours, then a fixed palette for any
    outcome they do not know (an outcome added later still gets its own colour)."""
    extra = iter(EXTRA_COLORS * (1 + len(outcomes) // len(EXTRA_COLORS)))
    return {o: OUTCOME_STYLE[o]["color"] if o in OUTCOME_STYLE else next(extra) for o in outcomes}
