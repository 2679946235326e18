"""The console script (`frictiondisk`, `python -m frictiondisk.cli`): run one command line
in this process and leave without the interpreter's teardown (cli/run_and_exit.py)."""

from __future__ import annotations

import sys
from typing import NoReturn

from frictiondisk.cli.run_and_exit import run_and_exit


def run() -> NoReturn:
    """Run the command line `frictiondisk ...` and exit with its code."""
    from frictiondisk.cli.main import main

    run_and_exit(main, sys.argv[1:])
