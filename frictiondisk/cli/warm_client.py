"""Hand a `run` or `resume` to the warm server of this environment, if one is up
(cli/warm_server.py), and stand in for it: pass our signals on, exit as it exits.

Imports only the standard library: a command handed over starts in the time Python
takes to start and to hash the package's sources (about 40 ms with click's import).
"""

from __future__ import annotations

import os
import signal
import socket
import sys
import time

from frictiondisk.cli.warm_protocol import (
    MIRRORED_SIGNALS,
    UnsafeServerDir,
    private_dir,
    receive_message,
    send_message,
    socket_path,
)

LOST_POLL_S = 0.1  # [s] between checks that a command whose server vanished still runs
HANDSHAKE_TIMEOUT_S = 10.0  # [s] for the server to start the command; then we run it here
# passed on as they come; SIGTSTP (Ctrl-Z) stops the command, then us (_suspend)
_PASSED_ON = tuple(s for s in MIRRORED_SIGNALS if s != getattr(signal, "SIGTSTP", None))
_PASSED_ON += tuple(getattr(signal, n) for n in ("SIGWINCH", "SIGCONT") if hasattr(signal, n))


def hand_over(args: list[str]) -> int | None:
    """Run `frictiondisk *args` in the warm server; its exit code, or None if no server
    serves this environment (nothing was started: the caller runs the command itself)."""
    conn = _connect()
    if conn is None:
        return None
    with conn:
        ignored = [int(s) for s in MIRRORED_SIGNALS if signal.getsignal(s) is signal.SIG_IGN]
        request = {
            "argv": args,
            "cwd": os.getcwd(),
            "env": dict(os.environ),
            "umask": _umask(),
            "ignored_signals": ignored,
            "unbuffered": bool(getattr(sys.stdout, "write_through", False)),  # -u
        }
        # held back until they can go to the command (or, if none starts, to us)
        held = signal.pthread_sigmask(signal.SIG_BLOCK, (*_PASSED_ON, *MIRRORED_SIGNALS))
        try:
            pid = _start_command(conn, request)
            if pid is None:
                return None
            conn.settimeout(None)
            _pass_signals_on(pid, ignored)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, held)  # what came meanwhile goes on
        try:
            reply, _ = receive_message(conn)
        except (OSError, ValueError):
            reply = None
    if reply is None or "exit" not in reply:
        return _await_lost_command(pid)
    return _exit_status(int(reply["exit"]))


def _start_command(conn: socket.socket, request: dict) -> int | None:
    """Send the request with our stdin, stdout and stderr; the command's pid, or None if
    the server started nothing (no answer in time, refused, gone)."""
    try:
        send_message(conn, request, [0, 1, 2])
        reply, _ = receive_message(conn)
    except TimeoutError:
        print(
            f"frictiondisk: the warm server did not answer within "
            f"{HANDSHAKE_TIMEOUT_S:g} s; running here",
            file=sys.stderr,
        )
        return None  # closing the connection tells the server not to start it
    except (OSError, ValueError):
        return None
    if not reply or not isinstance(reply.get("pid"), int):  # refused: nothing runs there
        if reply and reply.get("error") not in (None, "stopping"):
            print(f"frictiondisk: the warm server: {reply['error']}; running here", file=sys.stderr)
        return None
    return reply["pid"]


def _pass_signals_on(pid: int, ignored: list[int]) -> None:
    """From now on our signals are the command's (those we ignore, it ignores too)."""

    def forward(signum, frame) -> None:
        _forward(pid, signum)

    for signum in _PASSED_ON:
        if int(signum) not in ignored:
            signal.signal(signum, forward)
    tstp = getattr(signal, "SIGTSTP", None)
    if tstp is not None and int(tstp) not in ignored:

        def suspend(signum, frame) -> None:
            # A SIGCONT sent before we stop ourselves below is lost (we stop after it);
            # a shell's `fg` or `bg` comes only once it has seen us stop.
            _forward(pid, signal.SIGSTOP)
            signal.signal(tstp, signal.SIG_DFL)
            os.kill(os.getpid(), tstp)  # we stop here, as the shell expects
            signal.signal(tstp, suspend)  # `fg` or `bg` continued us
            _forward(pid, signal.SIGCONT)

        signal.signal(tstp, suspend)


def _connect() -> socket.socket | None:
    try:
        path = socket_path(private_dir(create=False))
    except (OSError, UnsafeServerDir):
        return None
    if not path.is_socket():
        return None
    conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    conn.settimeout(HANDSHAKE_TIMEOUT_S)
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
