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
from frictiondisk.cli.warm_protocol import MIRRORED_SIGNALS


def fork_command(
    request: dict, fds: list[int], to_close: list, fds_to_close: list[int], group
) -> int:
    """Fork (OSError if it cannot); the child closes `to_close` (the server's sockets,
    selector and lock) and `fds_to_close` (other clients' descriptors), becomes the
    client's command line of the click `group` and never returns."""
    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    # A signal the client forwards as soon as it has our pid must not reach the server's
    # handlers still installed in the child: blocked until the client's dispositions are.
    blocked = signal.pthread_sigmask(signal.SIG_BLOCK, MIRRORED_SIGNALS)
    try:
        pid = os.fork()
    except BaseException:
        signal.pthread_sigmask(signal.SIG_SETMASK, blocked)
        raise
    if pid:
        signal.pthread_sigmask(signal.SIG_SETMASK, blocked)
        return pid
    code = 1  # as Python exits on an exception no command caught
    try:
        # a session of its own: no Ctrl-C of the server's terminal, and never a
        # background job of it (stty tostop would stop its first write)
        os.setsid()
        for thing in to_close:
            thing.close()
        for fd in fds_to_close:
            os.close(fd)
        adopt_client(request, fds)
        signal.pthread_sigmask(signal.SIG_SETMASK, blocked)  # pending signals arrive now
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
    for signum in (*MIRRORED_SIGNALS, signal.SIGCHLD):
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
    unbuffered = bool(request.get("unbuffered"))
    sys.stdin = _standard_stream(0, sys.stdin, unbuffered)
    sys.stdout = _standard_stream(1, sys.stdout, unbuffered)
    sys.stderr = _standard_stream(2, sys.stderr, unbuffered)


def _standard_stream(fd: int, old: io.TextIOWrapper, unbuffered: bool) -> io.TextIOWrapper:
    """A text stream on `fd` built as Python builds its standard streams at start-up: the
    same encoding and error handler (the server's: the key includes the locale), buffered
    unless the client's were not (-u, PYTHONUNBUFFERED), line-buffered on a terminal and
    always for stderr."""
    reading = fd == 0
    unbuffered = unbuffered and not reading
    raw = io.FileIO(fd, "r" if reading else "w", closefd=False)
    if unbuffered:
        binary = raw
    elif reading:
        binary = io.BufferedReader(raw)
    else:
        binary = io.BufferedWriter(raw)
    return io.TextIOWrapper(
        binary,
        encoding=old.encoding,
        errors=old.errors,
        line_buffering=not unbuffered and (fd == 2 or raw.isatty()),
        write_through=unbuffered,
    )
