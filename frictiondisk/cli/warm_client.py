"""Hand a `run` or `resume` to the warm server of this environment, if one is up
(cli/warm_server.py), and stand in for it: forward our signals to it, exit as it exits.

Imports only the standard library: a command handed over starts in the time Python
takes to start and to hash the package's sources (about 20 ms).
"""

from __future__ import annotations

import os
import signal
import socket
import sys
import time

from frictiondisk.cli.warm_protocol import (
    FORWARDED_SIGNALS,
    UnsafeServerDir,
    private_dir,
    receive_message,
    send_message,
    socket_path,
)

LOST_POLL_S = 0.1  # [s] between checks that a command whose server vanished still runs


def hand_over(args: list[str]) -> int | None:
    """Run `frictiondisk *args` in the warm server; its exit code, or None if no server
    serves this environment (nothing was started: the caller runs the command itself)."""
    conn = _connect()
    if conn is None:
        return None
    with conn:
        ignored = [int(s) for s in FORWARDED_SIGNALS if signal.getsignal(s) is signal.SIG_IGN]
        request = {
            "argv": args,
            "cwd": os.getcwd(),
            "env": dict(os.environ),
            "umask": _umask(),
            "ignored_signals": ignored,
        }
        try:
            send_message(conn, request, [0, 1, 2])
            reply, _ = receive_message(conn)
        except (OSError, ValueError):
            return None
        if not reply or "pid" not in reply:
            return None  # refused (stopping, malformed): nothing runs
        pid = int(reply["pid"])
        for signum in FORWARDED_SIGNALS:
            if int(signum) not in ignored:
                signal.signal(signum, lambda received, frame: _forward(pid, received))
        try:
            reply, _ = receive_message(conn)
        except (OSError, ValueError):
            reply = None
    if reply is None or "exit" not in reply:
        return _await_lost_command(pid)
    return _exit_status(int(reply["exit"]))


def _connect() -> socket.socket | None:
    try:
        path = socket_path(private_dir(create=False))
    except (OSError, UnsafeServerDir):
        return None
    if not path.is_socket():
        return None
    conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        conn.connect(str(path))
    except OSError:  # a dead server's socket
        conn.close()
        return None
    return conn


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _forward(pid: int, signum: int) -> None:
    try:
        os.kill(pid, signum)
    except ProcessLookupError:
        pass


def _exit_status(code: int) -> int:
    """The command's exit code as ours; a command killed by a signal kills us alike."""
    if code >= 0:
        return code
    sys.stdout.flush()
    sys.stderr.flush()
    signal.signal(-code, signal.SIG_DFL)
    os.kill(os.getpid(), -code)
    return 128 - code  # the signal did not end us (it is blocked)


def _await_lost_command(pid: int) -> int:
    """The server went away mid-command: wait for the command itself to end (still
    forwarding signals), then exit 1, since its exit status is lost."""
    print(
        f"frictiondisk: the warm server went away; waiting for the command (pid {pid}) to end",
        file=sys.stderr,
    )
    while True:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            break
        except PermissionError:
            break
        time.sleep(LOST_POLL_S)
    print("frictiondisk: its exit status is unknown", file=sys.stderr)
    return 1
