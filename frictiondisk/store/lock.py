"""The single-writer lock of a campaign directory: DIR/lock, flock'ed by the one process
allowed to write DIR (CampaignLock); CampaignLocked names the live holder."""

from __future__ import annotations

import contextlib
import datetime
import errno
import fcntl
import json
import os
import time
from pathlib import Path
from types import TracebackType

from frictiondisk.store.paths import open_nofollow

__all__ = ["CampaignLock", "CampaignLocked"]

# File descriptors of the locks this process holds. A child made by fork() inherits them,
# and an inherited descriptor would keep the lock alive after this process dies; the child
# therefore closes its copies (closing a copy does not release the parent's lock).
_HELD_FDS: set[int] = set()


def _close_inherited_lock_fds() -> None:
    for fd in _HELD_FDS:
        with contextlib.suppress(OSError):
            os.close(fd)
    _HELD_FDS.clear()


os.register_at_fork(after_in_child=_close_inherited_lock_fds)

_WAIT_FOR_HOLDER_INFO = 1.0  # [s] a new holder writes its PID right after locking


class CampaignLocked(Exception):
    """Another live process holds the lock of a campaign directory.

    Attributes: `directory`, `pid` (of the holder, None if it could not be read) and
    `started` (the holder's start time as ISO 8601 text, or None).
    """

    def __init__(self, directory: Path, pid: int | None, started: str | None) -> None:
        self.directory = directory
        self.pid = pid
        self.started = started
        who = f"PID {pid}" if pid is not None else "a process whose PID could not be read"
        since = f", started {started}" if started else ""
        super().__init__(
            f"campaign directory {directory} is in use by another frictiondisk process "
            f"({who}{since}); only one process may write to it at a time. Wait for it to "
            "finish or stop it, then run again."
        )


def _read_holder(fd: int) -> tuple[int | None, str | None]:
    """(pid, started) as written by the holder into the lock file, or (None, None)."""
    try:
        text = os.pread(fd, 4096, 0).decode("utf-8")
        info = json.loads(text)
        pid = info["pid"]
        started = info.get("started")
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None, None
    if not isinstance(pid, int) or isinstance(pid, bool):
        return None, None
    return pid, started if isinstance(started, str) else None


def _try_flock(fd: int, operation: int) -> bool:
    """flock(fd, operation | LOCK_NB): True if taken, False if another process holds it."""
    try:
        fcntl.flock(fd, operation | fcntl.LOCK_NB)
    except BlockingIOError:
        return False
    except OSError as err:  # EWOULDBLOCK under another name on some platforms
        if err.errno in (errno.EAGAIN, errno.EACCES):
            return False
        raise
    return True


class CampaignLock:
    """Exclusive lock of a campaign directory: at most one writing process per DIR.

    Use as a context manager (or `acquire()` / `release()`). Acquiring opens (creating it
    if needed) `DIR/lock` and takes a non-blocking exclusive `flock`; if another process
    holds it, `CampaignLocked` is raised, naming the DIR and the holder's PID. The holder
    writes `{"pid": ..., "started": ...}` into the file after locking.

    The kernel releases a flock when the last descriptor of the open file is closed, so the
    lock dies with its process however it ends (exit, exception, SIGKILL): a killed run
    never leaves a stuck lock, and the file's stale content does not matter. The file is
    never deleted (deleting it would let two processes lock two different files). Children
    made by fork() close their inherited copy of the descriptor and do not hold the lock.
    """

    def __init__(self, campaign_dir: str | os.PathLike[str]) -> None:
        self.campaign_dir = Path(campaign_dir)
        self.path = self.campaign_dir / "lock"
        self._fd: int | None = None

    @property
    def held(self) -> bool:
        """Whether this object holds the lock."""
        return self._fd is not None

    def acquire(self) -> CampaignLock:
        """Take the lock or raise `CampaignLocked`; returns self."""
        if self._fd is not None:
            raise RuntimeError(f"the lock of {self.campaign_dir} is already held by this object")
        self.campaign_dir.mkdir(parents=True, exist_ok=True)
        fd = open_nofollow(self.path, os.O_RDWR | os.O_CREAT)
        try:
            deadline = time.monotonic() + _WAIT_FOR_HOLDER_INFO
            while not _try_flock(fd, fcntl.LOCK_EX):
                pid, started = _read_holder(fd)
                # No PID yet: a holder that has just locked, or a brief `holder()` probe;
                # either resolves within moments, so try again before refusing.
                if pid is not None or time.monotonic() > deadline:
                    raise CampaignLocked(self.campaign_dir, pid, started)
                time.sleep(0.02)
            started = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
            info = json.dumps({"pid": os.getpid(), "started": started}) + "\n"
            os.ftruncate(fd, 0)
            os.pwrite(fd, info.encode(), 0)
            os.fsync(fd)
        except BaseException:
            os.close(fd)
            raise
        self._fd = fd
        _HELD_FDS.add(fd)
        return self

    def release(self) -> None:
        """Release the lock (no-op if not held)."""
        fd, self._fd = self._fd, None
        if fd is None:
            return
        _HELD_FDS.discard(fd)
        try:
            with contextlib.suppress(OSError):
                os.ftruncate(fd, 0)  # while still locked: no one reads a stale PID
            fcntl.flock(fd, fcntl.LOCK_UN)
        finally:
            os.close(fd)

    def __enter__(self) -> CampaignLock:
        return self.acquire()

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.release()

    @staticmethod
    def holder(campaign_dir: str | os.PathLike[str]) -> int | None:
        """PID of the live process holding the lock of `campaign_dir`, or None if it is free.

        Probes with a non-blocking shared flock (never creates the lock file). Returns -1 if
        the lock is held but the holder's PID could not be read within a second.
        """
        try:
            fd = open_nofollow(Path(campaign_dir) / "lock", os.O_RDONLY)
        except FileNotFoundError:
            return None
        try:
            deadline = time.monotonic() + _WAIT_FOR_HOLDER_INFO
            while True:
                if _try_flock(fd, fcntl.LOCK_SH):
                    fcntl.flock(fd, fcntl.LOCK_UN)
                    return None
                pid, _ = _read_holder(fd)
                if pid is not None:
                    return pid
                if time.monotonic() > deadline:
                    return -1
                time.sleep(0.02)
        finally:
            os.close(fd)
