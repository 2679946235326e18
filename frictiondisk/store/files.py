"""Atomic file writes and a validity check for netCDF files.

A reader (or a resumed campaign after a crash) must never see a half-written file. Every
writer here follows the same recipe: write a uniquely named temporary file in the target's
own directory (same file system, so the rename is atomic), flush and fsync it, `os.replace`
it over the target, then fsync the directory so the rename itself survives a power cut.
On any failure, including KeyboardInterrupt, the temporary file is removed and the target
is left untouched.

`netcdf_is_valid` is the other half: a file that does not load completely (for example one
truncated by a crash of a writer that did not use this module) is reported as invalid, so
the caller recomputes it instead of trusting it.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import uuid
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import xarray as xr

from frictiondisk.store.paths import netcdf_write_error

__all__ = [
    "atomic_write",
    "atomic_write_bytes",
    "atomic_write_netcdf",
    "atomic_write_text",
    "fsync_directory",
    "netcdf_is_valid",
    "temporary_name",
]

TEMP_SUFFIX = ".tmp"  # every temporary file made here is named ".<target>.<pid>.<token><n>.tmp"
# One random token per process (a reused pid must not meet an old temporary file) and a
# counter: a uuid4 per write drew from os.urandom, 0.2 ms a call on our machines.
_TOKEN = uuid.uuid4().hex[:16]
_COUNTER = itertools.count()


def temporary_name(path: Path) -> Path:
    """A unique hidden name next to `path` for the temporary file of an atomic write."""
    return path.with_name(f".{path.name}.{os.getpid()}.{_TOKEN}{next(_COUNTER)}{TEMP_SUFFIX}")


def fsync_directory(directory: str | os.PathLike[str]) -> None:
    """Make a rename or file creation in `directory` durable (best effort: some platforms and
    file systems do not allow fsync on a directory)."""
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def _fsync_file(path: Path) -> None:
    with open(path, "rb+") as fh:
        os.fsync(fh.fileno())


def atomic_write(
    path: str | os.PathLike[str],
    write: Callable[[Path], None],
    durable: bool = True,
    make_parents: bool = True,
) -> Path:
    """The one atomic writer: run `write(tmp)` to make a temporary file next to `path`, then
    rename it over `path` (and, if `durable`, fsync the file before and the directory after).

    Every file this package writes goes through here (netCDF, text, JSON, figures, journal
    entries). `durable=False` skips the fsyncs where a torn file is detected and recomputed
    anyway (journal entries carry their own sha256). Missing parent directories are created
    unless `make_parents` is False (a caller that knows they exist saves the mkdir call).
    Returns the path written.
    """
    path = Path(path)
    if make_parents:
        path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temporary_name(path)
    try:
        write(tmp)
        if durable:
            _fsync_file(tmp)
        os.replace(tmp, path)
    except BaseException as err:  # also KeyboardInterrupt: never leave a temporary file behind
        with contextlib.suppress(OSError):
            tmp.unlink()
        if isinstance(err, OSError) and err.filename in (None, str(tmp), tmp):  # name the target
            raise OSError(err.errno, err.strerror, str(path)) from err
        raise
    if durable:
        fsync_directory(path.parent)
    return path


def atomic_write_bytes(
    path: str | os.PathLike[str], data: bytes, durable: bool = True, make_parents: bool = True
) -> Path:
    """Write `data` to `path` atomically: `path` holds either all of it or its old content.

    Missing parent directories are created (see `atomic_write`). Returns the path written.
    """

    def write(tmp: Path) -> None:
        # O_EXCL: the unique name must not exist; mode 0o666 & ~umask, like any new file
        # (tempfile.mkstemp would make it 0o600).
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        with open(fd, "wb") as fh:
            fh.write(data)

    return atomic_write(path, write, durable, make_parents)


def atomic_write_text(path: str | os.PathLike[str], text: str, encoding: str = "utf-8") -> Path:
    """Write `text` to `path` atomically (see `atomic_write_bytes`). Returns the path."""
    return atomic_write_bytes(path, text.encode(encoding))


def atomic_write_netcdf(
    ds: xr.Dataset,
    path: str | os.PathLike[str],
    *,
    encoding: Mapping[str, Mapping[str, Any]] | None = None,
) -> Path:
    """Write `ds` to `path` as NETCDF4 (engine netcdf4), atomically.

    The Dataset is written to a temporary file in the same directory, fsynced and renamed
    over `path`; the directory is then fsynced. `path` thus holds either the complete new
    file or its old content, never a partial file. Missing parent directories are created.
    `encoding` is passed to `Dataset.to_netcdf` (e.g. `{"x": {"zlib": True}}`).
    Returns the path written.
    """

    # CF: coordinate variables hold no missing values, so they carry no _FillValue
    # (xarray would give every float coordinate a NaN one)
    full = {name: {"_FillValue": None} for name in ds.coords}
    for name, spec in (encoding or {}).items():
        full[name] = {**full.get(name, {}), **spec}

    def write(tmp: Path) -> None:
        try:
            with _written_here():
                ds.to_netcdf(tmp, mode="w", format="NETCDF4", engine="netcdf4", encoding=full)
        except (OSError, RuntimeError) as err:  # "NetCDF: HDF error" on a full disk
            raise netcdf_write_error(path, err) from err

    return atomic_write(path, write)


def _written_here():
    """A context in which xarray writes with a lock of this process. While a Dask client
    is current (a campaign's), xarray takes a distributed Lock, a round trip to the
    scheduler, for every access to every variable (a 4 000-run scan's two files: 712
    round trips, 0.15 s of the driver); a file this process alone writes needs none."""
    import dask

    return dask.config.set(scheduler="synchronous")


def netcdf_is_valid(path: str | os.PathLike[str]) -> bool:
    """True only if `path` exists, opens as netCDF and every variable loads completely.

    Any exception while opening or reading (missing file, truncated or corrupted file, not
    netCDF at all) gives False: the caller should recompute the file, not trust it.
    """
    import xarray as xr

    path = Path(path)
    if not path.is_file():
        return False
    try:
        # cache=False and the context manager: no file handle outlives this check, so a
        # repaired file can be renamed over `path` right afterwards.
        with xr.open_dataset(path, cache=False) as ds:
            ds.load()
    except Exception:
        return False
    return True
