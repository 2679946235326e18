"""Start, ping and stop the warm server of this environment from another process
(`frictiondisk serve --detach`, `--stop`; the server itself is cli/warm_server.py), and
the lock that lets one server at a time start for an environment."""

from __future__ import annotations

import socket
import sys
import time
from pathlib import Path

from frictiondisk.cli.warm_protocol import (
    private_dir,
    receive_message,
    send_message,
    socket_path,
)

ANSWER_TIMEOUT_S = 5.0  # [s] for a server to answer a ping or a stop


class ServerError(Exception):
    """The server cannot start (another one serves this environment, or unsafe state)."""


class ServerLock:
    """An exclusive lock on `path` while one server of this environment starts and runs;
    ServerError if another holds it."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def __enter__(self) -> ServerLock:
        import fcntl

        self.file = open(self.path, "a")  # noqa: SIM115  held until __exit__
        try:
            fcntl.flock(self.file, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            self.file.close()
            raise ServerError(
                f"a server of this environment is starting or running ({self.path})"
            ) from None
        return self

    def __exit__(self, *exc) -> None:
        self.file.close()


def answers(path: Path) -> dict | None:
    """The reply of the server at `path` to a ping, or None if none listens there."""
    return _ask(path, {"ping": True})


def request_stop(path: Path) -> int | None:
    """Ask the server at `path` to stop; the number of commands it lets finish first, or
    None if no server listens there."""
    reply = _ask(path, {"stop": True})
    return None if reply is None else int(reply.get("stopping", 0))


def _ask(path: Path, message: dict) -> dict | None:
    """The server's reply to `message`, or None if none listens at `path`."""
    conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    conn.settimeout(ANSWER_TIMEOUT_S)
    try:
        conn.connect(str(path))
        send_message(conn, message)
        reply, _ = receive_message(conn)
        return reply
    except (OSError, ValueError):
        return None
    finally:
        conn.close()


def detach(idle_timeout_s: float, ready_timeout_s: float) -> tuple[int, Path, Path]:
    """Start `frictiondisk serve` in the background (its own session; its log in the
    socket directory) and wait until it answers; returns (pid, socket, log), those of the
    server already running (or starting beside it) if there is one.
    ServerError if it exits first or does not answer within `ready_timeout_s` [s]."""
    import subprocess

    directory = private_dir(create=True)
    path = socket_path(directory)
    log_path = path.with_suffix(".log")
    running = answers(path)
    if running is not None and "pong" in running:
        return int(running["pong"]), path, log_path
    with open(log_path, "ab") as log_file:
        process = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "frictiondisk.cli",
                "serve",
                "--idle-timeout",
                f"{idle_timeout_s:g}",
            ],
            stdin=subprocess.DEVNULL,
            stdout=log_file,
            stderr=log_file,
            start_new_session=True,
            # `-m` puts the working directory first on the path: start where it finds the
            # package this process runs, not another checkout in the user's directory
            cwd=Path(__file__).resolve().parents[2],
        )
    deadline = time.monotonic() + ready_timeout_s
    while time.monotonic() < deadline:
        reply = answers(path)
        if reply is not None and "pong" in reply:  # ours, or one started beside it
            return int(reply["pong"]), path, log_path
        if process.poll() is not None and not lock_held(path.with_suffix(".lock")):
            tail = log_path.read_text(errors="replace").strip().splitlines()[-5:]
            raise ServerError(
                f"the server exited with code {process.returncode}: " + " | ".join(tail)
            )
        time.sleep(0.05)
    process.terminate()
    raise ServerError(f"the server did not answer within {ready_timeout_s:g} s (log: {log_path})")


def lock_held(path: Path) -> bool:
    """Whether a server holds (starts or serves with) the lock at `path`."""
    try:
        with ServerLock(path):
            return False
    except ServerError:
        return True
