"""The warm server (`frictiondisk serve`): import Dask, xarray and netCDF4 and load the
compiled kernel once, then run each `run` or `resume` handed over by a client
(cli/warm_client.py) in a forked copy of this process.

A cold `run` spends about 1.2 s before and around its first run on these imports, on
numba loading the kernel and on xarray importing dask.array (docs/benchmarks.md). A
forked child inherits all of it and starts its own Dask cluster, so it pays only that
cluster and its own work. The child takes the client's stdin/stdout/stderr (passed as
file descriptors), directory, environment and umask, and sits in a process group of its
own: the client forwards its signals to it, and the server sends a SIGTERM (a graceful
stop, as from a batch scheduler) if the client goes away.

The server forks only while it is the process's one thread, since a fork copies no other
thread. It ends after `idle_timeout_s` without a command, on SIGTERM, SIGINT or SIGHUP,
or when asked (`serve --stop`); commands still running then finish first.
"""

from __future__ import annotations

import os
import selectors
import signal
import socket
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from frictiondisk.cli.warm_child import fork_command
from frictiondisk.cli.warm_protocol import (
    FORWARDED_SIGNALS,
    private_dir,
    receive_message,
    send_message,
    socket_path,
)

POLL_S = 0.05  # [s] between checks for finished commands and stop requests
REQUEST_TIMEOUT_S = 5.0  # [s] for a client to send its request once connected


class ServerError(Exception):
    """The server cannot start (another one serves this environment, or unsafe state)."""


@dataclass
class _Command:
    conn: socket.socket
    args: list[str]
    started: float = field(default_factory=time.perf_counter)
    client_gone: bool = False


def preload() -> float:
    """Import what `run` and `resume` use, load (or compile) the kernel and write a tiny
    netCDF file once; returns the time it took [s]."""
    t0 = time.perf_counter()
    import dask.array  # noqa: F401  xarray imports it at its first Dataset
    import distributed  # noqa: F401
    import netCDF4  # noqa: F401
    import numpy as np
    import xarray as xr
    from distributed.deploy.local import LocalCluster  # noqa: F401

    import frictiondisk.engine.progress  # noqa: F401
    import frictiondisk.engine.runner  # noqa: F401
    from frictiondisk.engine.tasks import warm_up
    from frictiondisk.store.files import atomic_write_netcdf

    warm_up()
    with tempfile.TemporaryDirectory(prefix="frictiondisk-warm-") as tmp:
        probe = xr.Dataset({"x": ("t", np.zeros(2))}, coords={"t": [0.0, 1.0]})
        atomic_write_netcdf(probe, Path(tmp) / "warm.nc")
    return time.perf_counter() - t0


def answers(path: Path) -> dict | None:
    """The reply of the server at `path` to a ping, or None if none listens there."""
    conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    conn.settimeout(REQUEST_TIMEOUT_S)
    try:
        conn.connect(str(path))
        send_message(conn, {"ping": True})
        reply, _ = receive_message(conn)
        return reply
    except (OSError, ValueError):
        return None
    finally:
        conn.close()


def serve(idle_timeout_s: float, group, log=None) -> int:
    """Serve this environment's commands of the click `group` until idle for
    `idle_timeout_s` [s] or stopped; returns the number of commands run. `log(text)` gets
    one line per event (default: stderr)."""
    log = log or (lambda text: print(f"frictiondisk serve: {text}", file=sys.stderr, flush=True))
    path = socket_path(private_dir(create=True))
    with _ServerLock(path.with_suffix(".lock")):
        preload_s = preload()
        others = [t.name for t in threading.enumerate() if t is not threading.main_thread()]
        if others:
            raise ServerError(f"threads {others} run after preloading; forking would lose them")
        server = _Server(path, group, log)
        log(
            f"ready at {path} (pid {os.getpid()}, preloaded in {preload_s:.2f} s); `run` and "
            f"`resume` in this environment start here. Stops after {idle_timeout_s:g} s "
            "idle, on Ctrl-C or with `frictiondisk serve --stop`"
        )
        try:
            server.loop(idle_timeout_s)
        finally:
            server.close()
        log(f"stopped after {server.served} command(s)")
        return server.served


class _ServerLock:
    """An exclusive lock on `path` while one server of this environment starts and runs;
    ServerError if another holds it."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def __enter__(self) -> _ServerLock:
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


class _Server:
    """The listening socket, the commands running and their clients' connections."""

    def __init__(self, path: Path, group, log) -> None:
        self.path = path
        self.group = group
        self.log = log
        self.listener = _bind(path)
        self.inode = os.stat(path).st_ino
        self.selector = selectors.DefaultSelector()
        self.selector.register(self.listener, selectors.EVENT_READ)
        self.commands: dict[int, _Command] = {}  # pid -> its client
        self.served = 0
        self.stop_requested = False
        for signum in FORWARDED_SIGNALS:
            signal.signal(signum, self._stop_on_signal)

    def _stop_on_signal(self, signum, frame) -> None:
        self.stop_requested = True

    def loop(self, idle_timeout_s: float) -> None:
        idle_since = time.monotonic()
        while True:
            for key, _ in self.selector.select(timeout=POLL_S):
                if key.fileobj is self.listener:
                    self._accept()
                else:
                    self._client_readable(key.fileobj)
            if self._reap():
                idle_since = time.monotonic()
            if self.stop_requested and self.listener.fileno() >= 0:
                self._stop_listening()
                if self.commands:
                    self.log(f"stopping once {len(self.commands)} running command(s) end")
            if self.stop_requested and not self.commands:
                return
            if not self.commands and time.monotonic() - idle_since > idle_timeout_s:
                self.log(f"idle for {idle_timeout_s:g} s; stopping")
                return

    def close(self) -> None:
        if self.listener.fileno() >= 0:
            self._stop_listening()
        self.selector.close()

    def _stop_listening(self) -> None:
        """No new client reaches us: they run their commands themselves."""
        self.selector.unregister(self.listener)
        self.listener.close()
        try:
            if os.stat(self.path).st_ino == self.inode:  # not a later server's socket
                self.path.unlink()
        except OSError:
            pass

    def _accept(self) -> None:
        """Answer one client: a ping, a stop, or a command (forked)."""
        conn, _ = self.listener.accept()
        conn.settimeout(REQUEST_TIMEOUT_S)
        fds: list[int] = []
        try:
            request, fds = receive_message(conn, max_fds=3)
            if request is None or not _same_user(conn):
                conn.close()
            elif request.get("ping"):
                send_message(conn, {"pong": os.getpid(), "running": len(self.commands)})
                conn.close()
            elif request.get("stop"):
                self.stop_requested = True
                send_message(conn, {"stopping": len(self.commands)})
                conn.close()
            elif _valid_command(request, fds):
                self._start(conn, request, fds)
            else:
                send_message(conn, {"error": "malformed request"})
                conn.close()
        except (OSError, ValueError) as exc:
            self.log(f"a client's request failed: {exc!r}")
            conn.close()
        finally:
            for fd in fds:
                os.close(fd)  # a command has its own copies

    def _start(self, conn: socket.socket, request: dict, fds: list[int]) -> None:
        others = [command.conn for command in self.commands.values()]
        sockets = [self.listener, conn, *others]
        pid = fork_command(request, fds, sockets, self.selector, self.group)
        self.commands[pid] = _Command(conn, list(request["argv"]))
        self.served += 1
        conn.settimeout(None)
        send_message(conn, {"pid": pid})
        self.selector.register(conn, selectors.EVENT_READ, pid)
        self.log(f"pid {pid}: {' '.join(request['argv'])}")

    def _client_readable(self, conn: socket.socket) -> None:
        """A client sends nothing after its request: readable means it went away (or
        broke the protocol). Its command gets SIGTERM, a graceful stop."""
        pid = self.selector.get_key(conn).data
        self.selector.unregister(conn)
        command = self.commands.get(pid)
        if command is None or command.client_gone:
            return
        command.client_gone = True
        self.log(f"pid {pid}: its client went away; sending SIGTERM")
        try:
            os.kill(pid, signal.SIGTERM)
        except ProcessLookupError:
            pass

    def _reap(self) -> bool:
        """Send every finished command's exit code to its client; True if any finished."""
        finished = False
        while self.commands:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                break
            if pid == 0:
                break
            command = self.commands.pop(pid, None)
            if command is None:
                continue
            finished = True
            code = os.waitstatus_to_exitcode(status)
            took = time.perf_counter() - command.started
            self.log(f"pid {pid}: exit {code} after {took:.2f} s")
            if not command.client_gone:
                self.selector.unregister(command.conn)
                try:
                    send_message(command.conn, {"exit": code})
                except OSError:
                    pass
            command.conn.close()
        return finished


def _bind(path: Path) -> socket.socket:
    if path.exists() or path.is_symlink():
        path.unlink()  # we hold the lock: a dead server's socket
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    old_umask = os.umask(0o077)
    try:
        listener.bind(str(path))
    except OSError as exc:
        listener.close()
        raise ServerError(f"cannot listen at {path}: {exc.strerror}") from None
    finally:
        os.umask(old_umask)
    listener.listen(16)
    return listener


def _same_user(conn: socket.socket) -> bool:
    """Whether the peer runs as this user (Linux SO_PEERCRED; elsewhere the private
    directory alone keeps others out)."""
    option = getattr(socket, "SO_PEERCRED", None)
    if option is None:
        return True
    import struct

    creds = conn.getsockopt(socket.SOL_SOCKET, option, struct.calcsize("3i"))
    _, uid, _ = struct.unpack("3i", creds)
    return uid == os.getuid()


def _valid_command(request: dict, fds: list[int]) -> bool:
    argv = request.get("argv")
    return (
        len(fds) == 3
        and isinstance(argv, list)
        and all(isinstance(a, str) for a in argv)
        and isinstance(request.get("cwd"), str)
        and isinstance(request.get("env"), dict)
        and isinstance(request.get("umask"), int)
        and isinstance(request.get("ignored_signals", []), list)
    )


def detach(idle_timeout_s: float, ready_timeout_s: float) -> tuple[int, Path, Path]:
    """Start `frictiondisk serve` in the background (its own session; its log in the
    socket directory) and wait until it answers; returns (pid, socket, log), those of the
    server already running if there is one.
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
        )
    deadline = time.monotonic() + ready_timeout_s
    while time.monotonic() < deadline:
        reply = answers(path)
        if reply is not None and reply.get("pong") == process.pid:
            return process.pid, path, log_path
        if process.poll() is not None:
            tail = log_path.read_text(errors="replace").strip().splitlines()[-5:]
            raise ServerError(
                f"the server exited with code {process.returncode}: " + " | ".join(tail)
            )
        time.sleep(0.05)
    process.terminate()
    raise ServerError(f"the server did not answer within {ready_timeout_s:g} s (log: {log_path})")
