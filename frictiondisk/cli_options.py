"""Click callbacks shared by the command modules (validation at the command line)."""

from __future__ import annotations

from pathlib import Path

import click


def check_figure_suffix(
    ctx: click.Context, param: click.Parameter, value: Path | None
) -> Path | None:
    """A figure path whose suffix names a format matplotlib writes for us."""
    if value is None:
        return None
    from frictiondisk.plotting import FIGURE_FORMATS

    if value.suffix.lower() not in FIGURE_FORMATS:
        raise click.BadParameter(
            f"{str(value)!r}: the suffix picks the format; use one of {', '.join(FIGURE_FORMATS)}"
        )
    return value
