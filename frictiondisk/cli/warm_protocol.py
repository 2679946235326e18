"""Where a warm server (`frictiondisk serve`) listens, and how a client talks to it.

A server holds one exact environment warm: this package's sources, the Python, what is
installed, and the environment variables read at import time (NUMBA_*, DASK_*,
PYTHON*, the locale). Its socket is named by a hash of all of these, so a client whose
environment differs finds no server and runs the command itself, with identical results.

Messages are JSON objects behind a 4-byte big-endian length. The client's first message
carries its stdin, stdout and stderr as SCM_RIGHTS file descriptors.
"""

from __future__ import annotations

import hashlib
import json
import os
import signal
import socket
import stat
import struct
import sys
from pathlib import Path

SERVER_DIR_ENV = "FRICTIONDISK_SERVER_DIR"  # where sockets live (default below)
NO_SERVER_ENV = "FRICTIONDISK_NO_SERVER"  # set (non-empty): never hand a command over
_ENV_READ_AT_IMPORT = ("NUMBA_", "DASK_", "PYTHON", "LC_", "FRICTIONDISK_")
_ENV_EXACT = ("LANG", "LANGUAGE")
FORWARDED_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)  # client -> command
_HEADER = struct.Struct(">I")
MAX_MESSAGE = 1 << 20  # [bytes]


class UnsafeServerDir(Exception):
    """The socket directory is not a private directory of this user."""


def server_dir() -> Path:
    """$FRICTIONDISK_SERVER_DIR, else $XDG_RUNTIME_DIR/frictiondisk, else
    <tmp>/frictiondisk-<uid>."""
    chosen = os.environ.get(SERVER_DIR_ENV)
    if chosen:
        return Path(chosen)
    runtime = os.environ.get("XDG_RUNTIME_DIR")
    if runtime:
        return Path(runtime) / "frictiondisk"
    import tempfile

    return Path(tempfile.gettempdir()) / f"frictiondisk-{os.getuid()}"


def private_dir(create: bool) -> Path:
    """server_dir(), checked to be a real directory owned by this user that nobody else
    may enter (mode 0700; created so if `create`). UnsafeServerDir otherwise, naming what
    is wrong; FileNotFoundError if it is absent and not `create`."""
    path = server_dir()
    if create:
        path.mkdir(mode=0o700, parents=True, exist_ok=True)
    info = os.lstat(path)
    if not stat.S_ISDIR(info.st_mode):
        raise UnsafeServerDir(f"{path}: not a directory (a symbolic link is refused)")
    if info.st_uid != os.getuid():
        raise UnsafeServerDir(f"{path}: owned by uid {info.st_uid}, not by you ({os.getuid()})")
    if info.st_mode & 0o077:
        raise UnsafeServerDir(
            f"{path}: mode {stat.S_IMODE(info.st_mode):04o}; others may enter it "
            f"(chmod 700 {path}, or set {SERVER_DIR_ENV} to a private directory)"
        )
    return path


def environment_key() -> str:
    """16 hex digits naming this exact environment (see the module docstring)."""
    package = Path(__file__).resolve().parents[1]  # frictiondisk/
    digest = hashlib.sha256()
    for part in (sys.executable, sys.version, str(package)):
        digest.update(part.encode() + b"\0")
    for source in sorted(package.rglob("*.py")):
        digest.update(str(source.relative_to(package)).encode() + b"\0")
        digest.update(source.read_bytes())
    # sys.path[0] is the script's folder or the working directory: the package's own
    # location, hashed above, is what counts. An install or upgrade changes the mtime
    # of its site-packages folder.
    for entry in sys.path[1:]:
        try:
            digest.update(f"{entry}:{os.stat(entry).st_mtime_ns}\0".encode())
        except OSError:
            digest.update(f"{entry}:absent\0".encode())
    for name in sorted(os.environ):
        if name in (SERVER_DIR_ENV, NO_SERVER_ENV):
            continue
        if name.startswith(_ENV_READ_AT_IMPORT) or name in _ENV_EXACT:
            digest.update(f"{name}={os.environ[name]}\0".encode())
    return digest.hexdigest()[:16]


def socket_path(directory: Path) -> Path:
    """The socket of the server of this environment in `directory`."""
    return directory / f"{environment_key()}.sock"


def send_message(conn: socket.socket, message: dict, fds: list[int] | None = None) -> None:
    data = json.dumps(message).encode()
    framed = _HEADER.pack(len(data)) + data
    if fds:
        sent = socket.send_fds(conn, [framed], fds)
        conn.sendall(framed[sent:])
    else:
        conn.sendall(framed)


def receive_message(conn: socket.socket, max_fds: int = 0) -> tuple[dict | None, list[int]]:
    """(message, file descriptors received with it); (None, []) if the peer closed the
    connection first. ValueError on a malformed or oversized message."""
    if max_fds:
        chunk, fds, _, _ = socket.recv_fds(conn, MAX_MESSAGE, max_fds)
    else:
        chunk, fds = conn.recv(MAX_MESSAGE), []
    if not chunk:
        return None, fds
    buffer = bytearray(chunk)
    while len(buffer) < _HEADER.size:
        more = conn.recv(MAX_MESSAGE)
        if not more:
            return None, fds
        buffer += more
    (length,) = _HEADER.unpack_from(buffer)
    if length > MAX_MESSAGE:
        raise ValueError(f"message of {length} bytes (at most {MAX_MESSAGE})")
    while len(buffer) < _HEADER.size + length:
        more = conn.recv(MAX_MESSAGE)
        if not more:
            return None, fds
        buffer += more
    message = json.loads(bytes(buffer[_HEADER.size : _HEADER.size + length]))
    if not isinstance(message, dict):
        raise ValueError("a message must be a JSON object")
    return message, fds
