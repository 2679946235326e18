"""The console script (`frictiondisk`, `python -m frictiondisk.cli`): run one command,
then leave without the interpreter's teardown.

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


def run() -> None:
    """Run the click command line and exit with its code, skipping interpreter teardown."""
    from frictiondisk.cli.main import main

    try:
        main.main(prog_name="frictiondisk")
        code = 0
    except SystemExit as stop:  # click ends every command so, Ctrl-C included
        code = _exit_code(stop.code)
    logging.shutdown()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe (| head): nothing left to say
            pass
    os._exit(code)


def _exit_code(code: object) -> int:
    """SystemExit's code as a process exit status: None is 0, text is printed and 1."""
    if code is None:
        return 0
    if isinstance(code, int):
        return code
    print(code, file=sys.stderr)
    return 1
