"""A command handed to the warm server runs in a forked copy of it (cli/warm_server.py)
that takes the client's stdin/stdout/stderr, directory, environment, umask and signal
dispositions, in a process group of its own, and leaves with the command's exit code."""

from __future__ import annotations

import io
import os
import signal
import sys
import tempfile
import traceback

from frictiondisk.cli.run_and_exit import run_and_exit
from frictiondisk.cli.warm_protocol import FORWARDED_SIGNALS


def fork_command(request: dict, fds: list[int], sockets: list, selector, group) -> int:
    """Fork; the child becomes the client's command line of the click `group` and never
    returns."""
    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    pid = os.fork()
    if pid:
        return pid
    code = 1  # as Python exits on an exception no command caught
    try:
        os.setpgid(0, 0)  # a Ctrl-C meant for the server's terminal is not for it
        selector.close()
        for sock in sockets:
            sock.close()
        adopt_client(request, fds)
        run_and_exit(group, request["argv"])
    except KeyboardInterrupt:
        code = 130
    except BaseException:  # noqa: BLE001  reported on the client's stderr
        traceback.print_exc()
    finally:
        os._exit(code)


def adopt_client(request: dict, fds: list[int]) -> None:
    """Make this (forked) process look like the client's own: its stdio, directory,
    environment, umask and signal dispositions."""
    for target, fd in enumerate(fds):
        os.dup2(fd, target)
        os.close(fd)
    fds.clear()
    ignored = set(request.get("ignored_signals", []))
    for signum in (*FORWARDED_SIGNALS, signal.SIGCHLD):
        if int(signum) in ignored:
            signal.signal(signum, signal.SIG_IGN)
        elif signum == signal.SIGINT:
            signal.signal(signum, signal.default_int_handler)
        else:
            signal.signal(signum, signal.SIG_DFL)
    os.umask(request["umask"])
    os.chdir(request["cwd"])
    os.environ.clear()
    os.environ.update(request["env"])
    tempfile.tempdir = None  # chosen anew from the client's TMPDIR
    encoding = sys.stdout.encoding
    sys.stdin = io.TextIOWrapper(io.FileIO(0, "r", closefd=False), encoding=encoding)
    sys.stdout = io.TextIOWrapper(
        io.FileIO(1, "w", closefd=False), encoding=encoding, line_buffering=os.isatty(1)
    )
    sys.stderr = io.TextIOWrapper(
        io.FileIO(2, "w", closefd=False),
        encoding=encoding,
        errors="backslashreplace",
        line_buffering=True,
    )
