"""The console script (`frictiondisk`, `python -m frictiondisk.cli`): run one command in
this process (cli/run_and_exit.py), or hand a `run` or `resume` to the warm server of this
environment if one is up (`frictiondisk serve`, cli/warm_server.py), which starts it in
about a quarter of the time."""

from __future__ import annotations

import os
import sys
from typing import NoReturn

from frictiondisk.cli.run_and_exit import exit_now, run_and_exit

SERVED_COMMANDS = ("run", "resume")  # the commands whose start-up a warm server saves


def run() -> NoReturn:
    """Run the command line here, or in the warm server (then exit with its code)."""
    args = sys.argv[1:]
    code = _through_warm_server(args)
    if code is None:
        from frictiondisk.cli.main import main

        run_and_exit(main, args)
    exit_now(code)


def _through_warm_server(args: list[str]) -> int | None:
    if not args or args[0] not in SERVED_COMMANDS or os.name != "posix":
        return None
    if "--help" in args or "-h" in args:
        return None  # faster here than a fork
    from frictiondisk.cli.warm_protocol import NO_SERVER_ENV

    if os.environ.get(NO_SERVER_ENV):
        return None
    from frictiondisk.cli.warm_client import hand_over

    return hand_over(args)
