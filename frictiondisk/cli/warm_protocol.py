"""Where a warm server (`frictiondisk serve`) listens, and how a client talks to it.

A server holds one exact environment warm: this package's sources, the Python and its
flags, what is installed, what is read at import time (the NUMBA_*, DASK_*, PYTHON*,
locale, LD_*, OMP_*, MKL_* and OPENBLAS_* variables, HOME, Dask's YAML configuration,
numba's .numba_config.yaml) and what a forked copy keeps of its parent (CPU affinity,
nice, resource limits, cgroup). Its socket
is named by a hash of all of these, so a client whose environment differs finds no server
and runs the command itself, with identical results.

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
# read at import or when a library loads: numba, Dask, Python, the locale, the loader and
# the BLAS/OpenMP thread pools
_ENV_READ_AT_IMPORT = (
    *("NUMBA_", "DASK_", "PYTHON", "LC_", "FRICTIONDISK_"),
    *("LD_", "OMP_", "MKL_", "OPENBLAS_"),
)
_ENV_EXACT = ("LANG", "LANGUAGE", "HOME", "XDG_CONFIG_HOME")  # HOME: ~/.config/dask
# Signals whose disposition (ignored or not) a command takes from its client, and which
# the client passes on (Ctrl-Z, SIGTSTP, stops both; cli/warm_client.py)
MIRRORED_SIGNALS = tuple(
    getattr(signal, name)
    for name in ("SIGINT", "SIGTERM", "SIGHUP", "SIGQUIT", "SIGUSR1", "SIGUSR2", "SIGTSTP")
    if hasattr(signal, name)
)
_HEADER = struct.Struct(">I")
MAX_MESSAGE = 8 << 20  # [bytes] an environment may hold up to ARG_MAX (2 MiB on Linux)
RECEIVE_CHUNK = 1 << 16  # [bytes]


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
    # location, hashed above, is what counts. An install or upgrade changes the mtime of
    # its site-packages folder; other folders on the path count by name only, since a
    # campaign writing into one (PYTHONPATH=.) must not change the key.
    import site

    site_folders = {*site.getsitepackages(), site.getusersitepackages()}
    for entry in sys.path[1:]:
        try:
            stamp = os.stat(entry).st_mtime_ns if entry in site_folders else "folder"
        except OSError:
            stamp = "absent"
        digest.update(f"{entry}:{stamp}\0".encode())
    for name in sorted(os.environ):
        if name in (SERVER_DIR_ENV, NO_SERVER_ENV):
            continue
        if name.startswith(_ENV_READ_AT_IMPORT) or name in _ENV_EXACT:
            digest.update(f"{name}={os.environ[name]}\0".encode())
    digest.update(repr((sys.flags, sys.warnoptions, sys._xoptions)).encode())
    for config in _config_files():  # read at import: a change shows in mtime and size
        try:
            info = os.stat(config)
            digest.update(f"{config}:{info.st_mtime_ns}:{info.st_size}\0".encode())
        except OSError:
            pass
    digest.update(_process_attributes().encode())
    return digest.hexdigest()[:16]


def _config_files() -> list[str]:
    """Dask's YAML configuration (where dask.config looks) and numba's
    .numba_config.yaml in the working directory."""
    import site

    folders = [
        os.environ.get("DASK_ROOT_CONFIG", "/etc/dask"),
        os.path.join(sys.prefix, "etc", "dask"),
        *[os.path.join(prefix, "etc", "dask") for prefix in site.PREFIXES],
        os.path.join(os.path.expanduser("~"), ".config", "dask"),
    ]
    if os.environ.get("DASK_CONFIG"):
        folders.append(os.environ["DASK_CONFIG"])
    files = [os.path.abspath(".numba_config.yaml")]
    for folder in folders:
        try:
            files += sorted(os.path.join(folder, name) for name in os.listdir(folder))
        except OSError:  # absent, or a file (DASK_CONFIG may name one)
            files.append(folder)
    return files


def _process_attributes() -> str:
    """What a forked copy would keep of the server's process rather than the client's:
    CPU affinity, nice, resource limits and cgroup (a batch job's limits and accounting)."""
    import resource

    parts: list = [os.getpriority(os.PRIO_PROCESS, 0)]
    if hasattr(os, "sched_getaffinity"):
        parts.append(sorted(os.sched_getaffinity(0)))
    limits = sorted(name for name in dir(resource) if name.startswith("RLIMIT_"))
    parts += [(name, resource.getrlimit(getattr(resource, name))) for name in limits]
    try:
        parts.append(Path("/proc/self/cgroup").read_text())
    except OSError:
        pass
    return repr(parts)


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


class MessageBuffer:
    """One message's bytes, and the file descriptors that came with them, as they arrive."""

    def __init__(self) -> None:
        self.data = bytearray()
        self.fds: list[int] = []

    def receive(self, conn: socket.socket, max_fds: int) -> bool:
        """Read what `conn` has; False if the peer closed the connection."""
        chunk, fds, _, _ = socket.recv_fds(conn, RECEIVE_CHUNK, max(max_fds, 1))
        self.fds += fds
        if len(self.fds) > max_fds:
            raise ValueError(f"{len(self.fds)} file descriptors (at most {max_fds})")
        self.data += chunk
        return bool(chunk)

    def message(self) -> dict | None:
        """The message once complete, else None. ValueError if malformed or oversized."""
        if len(self.data) < _HEADER.size:
            return None
        (length,) = _HEADER.unpack_from(self.data)
        if length > MAX_MESSAGE:
            raise ValueError(f"message of {length} bytes (at most {MAX_MESSAGE})")
        if len(self.data) < _HEADER.size + length:
            return None
        try:
            message = json.loads(bytes(self.data[_HEADER.size : _HEADER.size + length]))
        except RecursionError:  # nested deeper than the parser's stack
            raise ValueError("a message nested too deeply") from None
        if not isinstance(message, dict):
            raise ValueError("a message must be a JSON object")
        return message

    def close_fds(self) -> None:
        for fd in self.fds:
            os.close(fd)
        self.fds.clear()


def receive_message(conn: socket.socket, max_fds: int = 0) -> tuple[dict | None, list[int]]:
    """Block until one message arrives: (message, file descriptors received with it);
    (None, []) if the peer closed the connection first. ValueError on a malformed or
    oversized message; the descriptors are closed on any error."""
    buffer = MessageBuffer()
    try:
        while (message := buffer.message()) is None:
            if not buffer.receive(conn, max_fds):
                buffer.close_fds()
                return None, []
    except BaseException:
        buffer.close_fds()
        raise
    return message, buffer.fds
