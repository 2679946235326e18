"""Output paths checked before any work, and OS errors told in plain words.

`check_output_dir` and `check_output_file` run before a campaign directory is created or a
simulation starts, so a path that cannot be written fails at once, not after the work.
`describe_os_error` turns an OSError into "PATH: cause", the cause in words (no space
left on the device, read-only file system, not a directory, ...). `refuse_symlink` is the
lstat check that keeps every read and write of a campaign directory inside it, and
`open_nofollow` / `read_nofollow` open a file without ever following a link.
"""

from __future__ import annotations

import errno
import os
import shutil
import uuid
from pathlib import Path

__all__ = [
    "SymlinkRefused",
    "netcdf_write_error",
    "check_output_dir",
    "check_output_file",
    "describe_os_error",
    "open_nofollow",
    "read_nofollow",
    "refuse_symlink",
]

_CAUSES = {
    errno.ENOSPC: "no space left on the device",
    errno.EDQUOT: "disk quota exceeded",
    errno.EROFS: "read-only file system",
    errno.EACCES: "permission denied",
    errno.EPERM: "operation not permitted",
    errno.ENOTDIR: "a part of the path is not a directory",
    errno.EISDIR: "is a directory",
    errno.ENOENT: "no such file or directory",
    errno.EEXIST: "already exists",
    errno.ELOOP: "is a symbolic link (not followed)",
    errno.ENAMETOOLONG: "file name too long",
    errno.EIO: "input/output error",
}


class SymlinkRefused(OSError):
    """A path inside a campaign directory is a symbolic link: never followed."""

    def __init__(self, path: Path) -> None:
        super().__init__(errno.ELOOP, "is a symbolic link; refusing to follow it", str(path))


def describe_os_error(err: OSError, path: str | os.PathLike[str] | None = None) -> str:
    """ "PATH: cause" for an OSError, the cause in words and the errno name kept."""
    where = path if path is not None else err.filename
    cause = _CAUSES.get(err.errno) if err.errno is not None else None
    if err.strerror and (err.errno is None or err.strerror != os.strerror(err.errno)):
        cause = err.strerror  # our own words (raised here), not the C library's
    if cause is None:
        cause = err.strerror or str(err) or type(err).__name__
    name = errno.errorcode.get(err.errno, "") if err.errno is not None else ""
    tail = f" ({name})" if name else ""
    return f"{where}: {cause}{tail}" if where is not None else f"{cause}{tail}"


def refuse_symlink(path: str | os.PathLike[str]) -> Path:
    """`path`, unless it is a symbolic link (then SymlinkRefused). A missing path is fine."""
    path = Path(path)
    if path.is_symlink():
        raise SymlinkRefused(path)
    return path


def open_nofollow(path: Path, flags: int, mode: int = 0o666) -> int:
    """os.open with O_NOFOLLOW; a symbolic link raises SymlinkRefused naming `path`."""
    try:
        return os.open(path, flags | os.O_NOFOLLOW, mode)
    except OSError as err:
        if err.errno == errno.ELOOP:
            raise SymlinkRefused(path) from None
        raise


def read_nofollow(path: Path) -> bytes:
    """The bytes of the file `path`, opened with O_NOFOLLOW (see `open_nofollow`)."""
    fd = open_nofollow(path, os.O_RDONLY)
    with open(fd, "rb") as fh:
        return fh.read()


def _probe_writable(directory: Path) -> None:
    """Create and remove a file in `directory`; raise the OSError if that fails. (A real
    write, not os.access: access() says yes to root on a full or read-only-mounted disk
    only sometimes, and never for a full one.)"""
    probe = directory / f".frictiondisk-probe-{os.getpid()}-{uuid.uuid4().hex}"
    fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
    os.close(fd)
    os.unlink(probe)


def _existing_ancestor(path: Path) -> Path:
    """The nearest of path, its parent, ... that exists (as anything)."""
    current = path.absolute()
    while not os.path.lexists(current) and current != current.parent:
        current = current.parent
    return current


def check_output_dir(path: str | os.PathLike[str], what: str = "output directory") -> None:
    """Raise OSError (filename = the offending path) unless `path` is a writable directory
    or can be created as one: its nearest existing ancestor must be a writable directory."""
    path = Path(path)
    if os.path.lexists(path):
        if not path.is_dir():
            raise NotADirectoryError(errno.ENOTDIR, f"{what} exists and is not a directory", path)
        _probe_writable(path)
        return
    ancestor = _existing_ancestor(path)
    if not ancestor.is_dir():
        raise NotADirectoryError(
            errno.ENOTDIR, f"is not a directory, so {path} cannot be created", str(ancestor)
        )
    _probe_writable(ancestor)


def check_output_file(path: str | os.PathLike[str], min_free_bytes: int = 1 << 20) -> None:
    """Raise OSError unless a file `path` can be written: `path` not a directory, its
    directory writable or creatable (`check_output_dir`), with at least `min_free_bytes`
    free on its file system."""
    path = Path(path)
    if path.is_dir():
        raise IsADirectoryError(errno.EISDIR, "is a directory", str(path))
    parent = path.absolute().parent
    check_output_dir(parent, "directory of the output")
    existing = _existing_ancestor(parent)
    if shutil.disk_usage(existing).free < min_free_bytes:
        raise OSError(errno.ENOSPC, "no space left on the device", str(existing))


def netcdf_write_error(path: str | os.PathLike[str], err: Exception) -> OSError:
    """The OSError behind a failed netCDF write. The netCDF library reports a full disk as
    "NetCDF: HDF error", so the free space of the target's file system decides the words."""
    if isinstance(err, OSError) and err.errno is not None:
        return OSError(err.errno, err.strerror or str(err), str(path))
    parent = Path(path).absolute().parent
    try:
        free = shutil.disk_usage(parent).free
    except OSError:
        free = None
    if free is not None and free < (16 << 20):
        return OSError(errno.ENOSPC, f"no space left on the device ({free} bytes free)", str(path))
    return OSError(errno.EIO, f"writing netCDF failed: {err}", str(path))
