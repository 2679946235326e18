"""Run a click command line in this process, then leave with its exit code and without
the interpreter's teardown (the console script, cli/entry.py).

Tearing down numba, llvmlite and Dask's modules took 0.12 s after a warm `simulate` of
0.58 s (benchmarks/bench_startup.py). Nothing is lost by skipping it: every command
closes what it writes (atomic files, the journal, the Dask cluster) before it returns,
and the process exit releases the campaign lock. Tests that call `main` in-process
(click's CliRunner) do not come through here.

Ctrl-C at any moment, the imports of the first second included, exits 130 with the notice
of frictiondisk.engine.signals.stop_notice (click alone would print "Aborted!" and exit 1).
"""

from __future__ import annotations

import errno
import os
import signal
import sys
from collections.abc import Callable
from typing import NoReturn


def run_and_exit(load_group: Callable[[], object], args: list[str]) -> NoReturn:
    """Run the click command line `frictiondisk *args` of the group `load_group()` returns
    (imported here, so that a Ctrl-C during the imports is handled too) and exit."""
    sys.argv = ["frictiondisk", *args]
    try:
        code = _run(load_group, args)
    except KeyboardInterrupt as stop:  # before click runs, or outside its main
        code = _stopped(stop)
    exit_now(code)


def _run(load_group: Callable[[], object], args: list[str]) -> int:
    import click

    from frictiondisk.engine.signals import noted_stop

    try:
        group = load_group()
        _note_ctrl_c()
        value = group.main(args=args, prog_name="frictiondisk", standalone_mode=False)
        stop = noted_stop()
        if stop is not None:  # a Ctrl-C that a library swallowed (Dask's teardown, say)
            return _stopped(stop())
        return value if isinstance(value, int) and not isinstance(value, bool) else 0
    except SystemExit as stop:  # our commands end so (fail, a stopped campaign)
        return exit_code(stop.code)
    except click.exceptions.Abort as abort:  # click turns a KeyboardInterrupt into Abort
        cause = abort.__context__
        return _stopped(cause if isinstance(cause, KeyboardInterrupt) else KeyboardInterrupt())
    except click.ClickException as problem:
        problem.show()
        return problem.exit_code
    except Exception as err:
        stop = noted_stop()
        if stop is not None:  # a stop that a library turned into its own error (numba's
            return _stopped(stop())  # C extensions make an interrupted import an ImportError)
        if isinstance(err, OSError) and err.errno == errno.EPIPE:  # | head: as click does
            return 1
        raise


def _note_ctrl_c() -> None:
    """From here on Ctrl-C raises KeyboardInterrupt (the handler of cli/entry.py left at
    once) and notes the stop first, so that a library that turns it into an error of its
    own still ends in the stop's notice and exit code."""
    from frictiondisk.engine.signals import request_stop

    def interrupt(signum, frame):
        request_stop(KeyboardInterrupt)
        raise KeyboardInterrupt

    if signal.getsignal(signal.SIGINT) not in (signal.SIG_IGN, signal.SIG_DFL):
        signal.signal(signal.SIGINT, interrupt)


def _stopped(stop: KeyboardInterrupt) -> int:
    """Print the stop's notice; its exit code (130 Ctrl-C, 143 SIGTERM, 129 SIGHUP)."""
    from frictiondisk.engine.signals import describe_stop, stop_notice

    _, code = describe_stop(stop)
    try:
        print(f"error: {stop_notice(stop)}", file=sys.stderr)
    except (OSError, ValueError):
        pass
    return code


def exit_now(code: int) -> NoReturn:
    """Flush stdout and stderr, then end the process with `code` at once."""
    import logging

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
