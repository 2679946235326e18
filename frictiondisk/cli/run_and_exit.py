"""Run a click command line in this process, then leave with its exit code and without
the interpreter's teardown (the console script, cli/entry.py).

Tearing down numba, llvmlite and Dask's modules took 0.12 s after a warm `simulate` of
0.58 s (benchmarks/bench_startup.py). Nothing is lost by skipping it: every command
closes what it writes (atomic files, the journal, the Dask cluster) before it returns,
and the process exit releases the campaign lock. Tests that call `main` in-process
(click's CliRunner) do not come through here.
"""

from __future__ import annotations

import logging
import os
import sys
from typing import NoReturn


def run_and_exit(group, args: list[str]) -> NoReturn:
    """Run the click command line `frictiondisk *args` of `group` and exit."""
    sys.argv = ["frictiondisk", *args]
    try:
        group.main(args=args, prog_name="frictiondisk")
        code = 0
    except SystemExit as stop:  # click ends every command so, Ctrl-C included
        code = exit_code(stop.code)
    exit_now(code)


def exit_now(code: int) -> NoReturn:
    """Flush stdout and stderr, then end the process with `code` at once."""
    logging.shutdown()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe (| head): nothing left to say
            pass
    os._exit(code)


def exit_code(code: object) -> int:
    """SystemExit's code as a process exit status: None is 0, text is printed and 1."""
    if code is None:
        return 0
    if isinstance(code, int):
        return code
    print(code, file=sys.stderr)
    return 1
