"""The console script (`frictiondisk`, `python -m frictiondisk.cli`): run one command line
in this process and leave without the interpreter's teardown (cli/run_and_exit.py).

Ctrl-C exits 130 with one notice at any moment: until the commands are imported a handler
leaves at once (nothing has started), then a KeyboardInterrupt does, handled by
run_and_exit and, inside a campaign, by its loop."""

from __future__ import annotations

import os
import signal
import sys
from typing import NoReturn

from frictiondisk.cli.run_and_exit import run_and_exit


def run() -> NoReturn:
    """Run the command line `frictiondisk ...` and exit with its code."""
    _leave_on_ctrl_c_while_starting()
    run_and_exit(_main_group, sys.argv[1:])


def _main_group():
    """The click group, imported inside run_and_exit (it restores Python's Ctrl-C handler
    once the commands are imported)."""
    from frictiondisk.cli.main import main

    return main


# stop_notice(KeyboardInterrupt()) of frictiondisk.engine.signals, written out: the handler
# is installed before anything is imported (tests/test_hostile_inputs.py holds them equal)
EARLY_NOTICE = "interrupted; no finished run is lost. Run the same command again to continue"


def _leave_on_ctrl_c_while_starting() -> None:
    """Ctrl-C during the imports (about a second): print the notice and exit 130 at once;
    nothing has been read or written yet. An ignored SIGINT (nohup, a background job)
    stays ignored."""

    def leave(signum, frame):
        os.write(2, f"error: {EARLY_NOTICE}\n".encode())
        os._exit(130)

    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, leave)
