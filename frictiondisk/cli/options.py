"""What the command modules share: the usage exit code, error reports and option checks."""

from __future__ import annotations

from pathlib import Path
from typing import NoReturn

import click

EXIT_USAGE = 2  # bad command line, bad scene or campaign file, unreadable result file


def fail(header: str, lines: list[str], code: int = EXIT_USAGE) -> NoReturn:
    """Report `error: header` and one indented line per problem on stderr, then exit with
    `code` (no traceback). A stderr that is gone (a closed terminal: EIO; a closed pipe)
    changes nothing but the report."""
    try:
        click.echo(f"error: {header}", err=True)
        for line in lines:
            click.echo(f"  {line}", err=True)
    except OSError:
        pass
    raise SystemExit(code)


class TaskName(click.Choice):
    """The name of a registered task (frictiondisk.tasks.registry), read from the registry
    when click first needs the list: `frictiondisk --help` stays free of the task specs."""

    def __init__(self) -> None:
        super().__init__(())

    @property
    def choices(self) -> tuple[str, ...]:
        from frictiondisk.tasks.registry import TASKS

        return tuple(TASKS)

    @choices.setter
    def choices(self, value) -> None:  # Choice.__init__ sets it; the registry decides
        pass


def check_figure_suffix(
    ctx: click.Context, param: click.Parameter, value: Path | None
) -> Path | None:
    """A figure path whose suffix names a format matplotlib writes for us."""
    if value is None:
        return None
    from frictiondisk.figures.plotting import FIGURE_FORMATS

    if value.suffix.lower() not in FIGURE_FORMATS:
        raise click.BadParameter(
            f"{str(value)!r}: the suffix picks the format; use one of {', '.join(FIGURE_FORMATS)}"
        )
    return value
