"""The warm server (`frictiondisk serve`): import Dask, xarray and netCDF4 and load the
compiled kernel once, then run each `run` or `resume` handed over by a client
(cli/warm_client.py) in a forked copy of this process.

A cold `run` spends 1.2-1.6 s before and around its first run on these imports, on
numba loading the kernel and on xarray importing dask.array (docs/benchmarks.md). A
forked child inherits all of it and starts its own Dask cluster, so it pays only that
cluster and its own work. The child takes the client's stdin/stdout/stderr (passed as
file descriptors), directory, environment and umask, and sits in a process group of its
own: the client forwards its signals to it, and the server sends a SIGTERM (a graceful
stop, as from a batch scheduler) if the client goes away.

Requests are read without blocking, so a slow or silent client delays nobody. The
server forks only while it is the process's one thread, since a fork copies no other
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
from frictiondisk.cli.warm_control import ServerError, ServerLock
from frictiondisk.cli.warm_protocol import (
    MessageBuffer,
    private_dir,
    send_message,
    socket_path,
)

POLL_S = 0.05  # [s] between checks for finished commands and stop requests
REQUEST_TIMEOUT_S = 5.0  # [s] for a client to send its whole request once connected
STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


@dataclass
class _Command:
    """A forked command; `conn` to its client, None once the client went away."""

    conn: socket.socket | None
    started: float = field(default_factory=time.perf_counter)


@dataclass
class _Request:
    """A connection whose request is still arriving (read without blocking)."""

    buffer: MessageBuffer
    deadline: float  # [monotonic s]


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


def serve(idle_timeout_s: float, group, log=None) -> int:
    """Serve this environment's commands of the click `group` until idle for
    `idle_timeout_s` [s] or stopped; returns the number of commands run. `log(text)` gets
    one line per event (default: stderr)."""
    log = log or (lambda text: print(f"frictiondisk serve: {text}", file=sys.stderr, flush=True))
    path = socket_path(private_dir(create=True))
    with ServerLock(path.with_suffix(".lock")) as lock:
        preload_s = preload()
        others = [t.name for t in threading.enumerate() if t is not threading.main_thread()]
        if others:
            raise ServerError(f"threads {others} run after preloading; forking would lose them")
        server = _Server(path, group, log, lock.file)
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


class _Server:
    """The listening socket, the requests arriving, the commands running and their
    clients' connections."""

    def __init__(self, path: Path, group, log, lock_file) -> None:
        self.path = path
        self.group = group
        self.log = log
        self.lock_file = lock_file  # closed in every command, and when we stop listening
        self.listener = _bind(path)
        self.listener.setblocking(False)
        self.inode = os.stat(path).st_ino
        self.selector = selectors.DefaultSelector()
        self.selector.register(self.listener, selectors.EVENT_READ)
        self.requests: dict[socket.socket, _Request] = {}
        self.commands: dict[int, _Command] = {}  # pid -> its client
        self.served = 0
        self.stop_requested = False
        for signum in STOP_SIGNALS:
            signal.signal(signum, self._stop_on_signal)

    def _stop_on_signal(self, signum, frame) -> None:
        self.stop_requested = True

    def loop(self, idle_timeout_s: float) -> None:
        idle_since = time.monotonic()
        while True:
            for key, _ in self.selector.select(timeout=POLL_S):
                if key.fileobj is self.listener:
                    self._accept()
                elif key.fileobj in self.requests:
                    self._read_request(key.fileobj)
                else:
                    self._client_gone(key.fileobj, key.data)
            self._expire_requests()
            if self._reap() or self.requests:
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
        for conn in list(self.requests):
            self._drop_request(conn)
        self.selector.close()

    def _stop_listening(self) -> None:
        """No new client reaches us: they run their commands themselves, and a new server
        may start while our last commands finish."""
        self.selector.unregister(self.listener)
        self.listener.close()
        self.lock_file.close()
        try:
            if os.stat(self.path).st_ino == self.inode:  # not a later server's socket
                self.path.unlink()
        except OSError:
            pass

    def _accept(self) -> None:
        try:
            conn, _ = self.listener.accept()
        except BlockingIOError:
            return
        if not _same_user(conn):
            conn.close()
            return
        conn.setblocking(False)
        self.requests[conn] = _Request(MessageBuffer(), time.monotonic() + REQUEST_TIMEOUT_S)
        self.selector.register(conn, selectors.EVENT_READ)

    def _read_request(self, conn: socket.socket) -> None:
        """Take what a client sent; answer once its request is whole: a ping, a stop, or
        a command (forked)."""
        pending = self.requests[conn]
        try:
            if not pending.buffer.receive(conn, max_fds=3):
                self._drop_request(conn)
                return
            request = pending.buffer.message()
        except BlockingIOError:
            return
        except (OSError, ValueError) as exc:
            self.log(f"a client's request failed: {exc!r}")
            self._drop_request(conn)
            return
        if request is None:
            return  # more to come
        fds = pending.buffer.fds
        self.selector.unregister(conn)
        del self.requests[conn]
        gave_up = _peer_closed(conn)  # while the socket does not block
        conn.settimeout(REQUEST_TIMEOUT_S)
        try:
            if request.get("ping"):
                send_message(conn, {"pong": os.getpid(), "running": len(self.commands)})
            elif request.get("stop"):
                self.stop_requested = True
                send_message(conn, {"stopping": len(self.commands)})
            elif self.stop_requested:  # the client runs it itself
                send_message(conn, {"error": "stopping"})
            elif _valid_command(request, fds):
                if not gave_up and self._start(conn, request, fds):
                    return
            else:
                send_message(conn, {"error": "malformed request"})
        except OSError as exc:
            self.log(f"a client went away before its answer: {exc!r}")
        finally:
            pending.buffer.close_fds()  # a command has its own copies
        conn.close()

    def _drop_request(self, conn: socket.socket) -> None:
        pending = self.requests.pop(conn)
        pending.buffer.close_fds()
        self.selector.unregister(conn)
        conn.close()

    def _expire_requests(self) -> None:
        now = time.monotonic()
        for conn in [c for c, pending in self.requests.items() if pending.deadline < now]:
            self.log(f"a client sent no whole request within {REQUEST_TIMEOUT_S:g} s")
            self._drop_request(conn)

    def _start(self, conn: socket.socket, request: dict, fds: list[int]) -> bool:
        """Fork the command; False (the client told) if the fork failed."""
        to_close = [self.listener, conn, self.selector, self.lock_file, *self.requests]
        to_close += [command.conn for command in self.commands.values() if command.conn]
        others = [fd for pending in self.requests.values() for fd in pending.buffer.fds]
        try:
            pid = fork_command(request, fds, to_close, others, self.group)
        except OSError as exc:  # EAGAIN at a process limit, ENOMEM
            self.log(f"cannot fork a command: {exc!r}")
            send_message(conn, {"error": f"cannot fork: {exc.strerror}"})
            return False
        command = _Command(conn)
        self.commands[pid] = command
        self.served += 1
        self.log(f"pid {pid}: {' '.join(request['argv'])}")
        try:
            send_message(conn, {"pid": pid})
        except OSError:
            self._client_gone(conn, pid)
            return True
        conn.settimeout(None)
        self.selector.register(conn, selectors.EVENT_READ, pid)
        return True

    def _client_gone(self, conn: socket.socket, pid: int) -> None:
        """A client sends nothing after its request: readable means it went away (or
        broke the protocol). Its command gets SIGTERM, a graceful stop."""
        command = self.commands[pid]
        if conn.fileno() >= 0 and self.selector.get_map().get(conn) is not None:
            self.selector.unregister(conn)
        conn.close()
        command.conn = None
        self.log(f"pid {pid}: its client went away; sending SIGTERM")
        try:
            os.kill(pid, signal.SIGTERM)
            os.kill(pid, signal.SIGCONT)  # a command suspended with its client (Ctrl-Z)
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
            if command.conn is not None:
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


def _peer_closed(conn: socket.socket) -> bool:
    """Whether the client closed its end after its request (it gave up waiting); `conn`
    must be non-blocking (with a timeout, Python would wait for data first)."""
    try:
        return conn.recv(1, socket.MSG_PEEK) == b""
    except BlockingIOError:
        return False
    except OSError:
        return True


def _valid_command(request: dict, fds: list[int]) -> bool:
    argv = request.get("argv")
    return (
        len(fds) == 3
        and isinstance(argv, list)
        and all(isinstance(a, str) for a in argv)
        and isinstance(request.get("cwd"), str)
        and isinstance(request.get("env"), dict)
        and all(isinstance(v, str) for v in request.get("env", {}).values())
        and isinstance(request.get("umask"), int)
        and isinstance(request.get("ignored_signals", []), list)
    )
