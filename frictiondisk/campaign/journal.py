"""Append-only run journal and single-writer lock of a campaign directory.

Layout of a campaign directory DIR::

    DIR/lock                        flock'ed by the one process allowed to write (CampaignLock)
    DIR/journal/<kk>/<key>.json     one entry per finished run, kk = key[:2]
    DIR/journal/computed.log        one line "<key>" appended per put (what was computed, when)
    DIR/journal/corrupt/<key>.<n>.json   entries that failed verification, kept for inspection

A run is addressed by its key (`run_key`): the sha256 of its canonical scene plus the
kernel version, so a changed input or changed numerics give a new key and an old entry is
simply never looked up again. Each entry is written to a temporary file and renamed
(`Journal.put`), so a crash leaves either no entry or a complete one; a reader still verifies
every entry (`Journal.get`) and treats anything that fails as absent, i.e. to be recomputed.
"""

from __future__ import annotations

import collections
import contextlib
import datetime
import errno
import fcntl
import functools
import hashlib
import json
import math
import os
import re
import time
from pathlib import Path
from types import TracebackType
from typing import Any

from frictiondisk.files import TEMP_SUFFIX, fsync_directory, temporary_name

__all__ = [
    "ENTRY_VERSION",
    "CampaignLock",
    "CampaignLocked",
    "Journal",
    "kernel_version",
    "run_key",
]

ENTRY_VERSION = 1
_ENTRY_FIELDS = ("version", "key", "inputs", "result", "sha256")
_KEY = re.compile(r"[0-9a-f]{64}")  # a sha256 hex digest, as made by run_key
_PACKAGE_ROOT = Path(__file__).resolve().parent.parent  # the `frictiondisk` package folder
# The numerics of a run: the kernel, the door into it, and the classifier of its outcome.
# Everything that turns a scene into a result: the kernel, its Python door and classifier,
# the cross-check integrator (numerics.method: scipy-radau), the result fields, and the
# config (derived inputs such as the default contact damping and the contact layout).
_KERNEL_SOURCES = (
    "kernel/*.py",
    "simulate.py",
    "classify.py",
    "crosscheck.py",
    "result.py",
    "config.py",
    "layouts.py",
)


# --- keys ---------------------------------------------------------------------------------


def _source_digest(root: Path, patterns: tuple[str, ...] = _KERNEL_SOURCES) -> str:
    """First 16 hex digits of the sha256 over the files matching `patterns` under `root`.

    Files are taken in order of their path relative to `root`; each contributes its relative
    path, its length and its bytes, so a renamed, moved or edited file changes the digest.
    A pattern naming a single file that does not exist raises FileNotFoundError.
    """
    files: set[Path] = set()
    for pattern in patterns:
        if any(ch in pattern for ch in "*?["):
            files.update(p for p in root.glob(pattern) if p.is_file())
        else:
            path = root / pattern
            if not path.is_file():
                raise FileNotFoundError(f"kernel source {path} not found")
            files.add(path)
    digest = hashlib.sha256()
    for name, path in sorted((p.relative_to(root).as_posix(), p) for p in files):
        data = path.read_bytes()
        digest.update(name.encode() + b"\0" + len(data).to_bytes(8, "big") + data)
    return digest.hexdigest()[:16]


@functools.cache
def kernel_version() -> str:
    """Version of the numerics: 16 hex digits of a sha256 over the source code.

    Hashes the bytes of every file in `_KERNEL_SOURCES` (the kernel, simulate.py,
    classify.py, crosscheck.py, result.py, config.py), sorted by path. Any change to those
    files (even a comment)
    changes the version, hence every `run_key`: journal entries computed by older numerics
    are never reused. Computed once per process.
    """
    return _source_digest(_PACKAGE_ROOT)


def run_key(config: Any) -> str:
    """Journal key of one run: sha256 hex of its canonical scene and the kernel version.

    `config` is a validated `SceneConfig` (anything with `.canonical()` works). The key is
    the sha256 of `{"scene": config.canonical(), "kernel": kernel_version()}` as compact,
    key-sorted JSON.
    """
    text = json.dumps(
        {"scene": config.canonical(), "kernel": kernel_version()},
        sort_keys=True,
        separators=(",", ":"),
    )
    return hashlib.sha256(text.encode()).hexdigest()


def _check_key(key: Any) -> str:
    if not isinstance(key, str) or not _KEY.fullmatch(key):
        raise ValueError(
            f"journal key {key!r} is not valid: expected a sha256 hex digest "
            "(64 lowercase hex digits), as made by run_key"
        )
    return key


# --- journal ------------------------------------------------------------------------------


def _canonical_json(value: Any) -> str:
    return json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False)


def _entry_digest(key: str, inputs: Any, result: Any) -> str:
    """sha256 hex of the canonical JSON of {"key", "inputs", "result"}."""
    text = _canonical_json({"key": key, "inputs": inputs, "result": result})
    return hashlib.sha256(text.encode()).hexdigest()


def _non_finite_path(value: Any, path: str) -> str | None:
    """Dotted path of the first NaN or infinity inside `value`, or None."""
    if isinstance(value, float) and not math.isfinite(value):
        return path
    if isinstance(value, dict):
        items = value.items()
    elif isinstance(value, list | tuple):
        items = enumerate(value)
    else:
        return None
    for k, item in items:
        found = _non_finite_path(item, f"{path}.{k}" if path else str(k))
        if found is not None:
            return found
    return None


class Journal:
    """Append-only store of finished runs in `campaign_dir/journal`, keyed by `run_key`.

    `put` commits one run at once (atomic rename) and logs it in `computed.log`;
    `get` returns a run's result only if its entry verifies, else moves the entry to
    `corrupt/` and returns None so the run is recomputed. Use one writer at a time
    (hold a `CampaignLock`); readers may run alongside, but note that `get` moves corrupt
    entries away.

    Attributes
    ----------
    path: the journal folder, `campaign_dir/journal`.
    log_path: `path/computed.log`.
    n_corrupt: number of entries this instance found corrupt (and moved to `corrupt/`).
    corrupt_reasons: one short line per corrupt entry found: "<key>: <reason>".
    """

    def __init__(self, campaign_dir: str | os.PathLike[str]) -> None:
        self.campaign_dir = Path(campaign_dir)
        self.path = self.campaign_dir / "journal"
        self.path.mkdir(parents=True, exist_ok=True)
        self.log_path = self.path / "computed.log"
        self.corrupt_dir = self.path / "corrupt"
        self.n_corrupt = 0
        self.corrupt_reasons: list[str] = []

    def entry_path(self, key: str) -> Path:
        """Where the entry of `key` lives: `path/<key[:2]>/<key>.json`."""
        _check_key(key)
        return self.path / key[:2] / f"{key}.json"

    # reading ------------------------------------------------------------------------------

    def get(self, key: str) -> dict[str, Any] | None:
        """The stored result of run `key`, or None if there is none or it is not trustworthy.

        An entry is trusted only if it is UTF-8 JSON with the fields version (= 1), key,
        inputs, result and sha256, its key equals `key` and its sha256 matches the canonical
        JSON of {"key", "inputs", "result"}. Otherwise it is moved to
        `corrupt/<key>.<n>.json`, counted in `n_corrupt`, explained in `corrupt_reasons` and
        None is returned. A missing entry gives None and is not counted.
        """
        path = self.entry_path(key)
        try:
            raw = path.read_bytes()
        except FileNotFoundError:
            return None
        except OSError as err:
            return self._corrupt(key, path, f"unreadable ({err.strerror or err})")
        entry, reason = self._verify(key, raw)
        if reason is not None:
            return self._corrupt(key, path, reason)
        return entry["result"]

    @classmethod
    def peek(cls, campaign_dir: str | os.PathLike[str], key: str) -> dict[str, Any] | None:
        """Read-only `get` for workers: the verified result of `key`, else None.

        Writes nothing (no folder is created, a bad entry stays where it is for the driver's
        `get` to deal with), so a worker may call it while the driver holds the lock."""
        _check_key(key)
        path = Path(campaign_dir) / "journal" / key[:2] / f"{key}.json"
        try:
            raw = path.read_bytes()
        except OSError:
            return None
        entry, reason = cls._verify(key, raw)
        return None if reason is not None else entry["result"]

    @staticmethod
    def _verify(key: str, raw: bytes) -> tuple[Any, str | None]:
        """(entry, None) if `raw` is a valid entry of `key`, else (None, reason)."""
        try:
            entry = json.loads(raw.decode("utf-8"))
        except (UnicodeDecodeError, ValueError) as err:
            # json.JSONDecodeError is a ValueError; so is an out-of-range number
            what = "empty file" if not raw.strip() else f"truncated or not JSON ({err})"
            return None, what
        if not isinstance(entry, dict):
            return None, f"not a JSON object but {type(entry).__name__}"
        missing = [name for name in _ENTRY_FIELDS if name not in entry]
        if missing:
            return None, f"missing field(s) {', '.join(missing)}"
        if entry["version"] != ENTRY_VERSION:
            return None, f"unsupported entry version {entry['version']!r} (expected 1)"
        if entry["key"] != key:
            return None, f"key field {entry['key']!r} differs from the file's key"
        if not isinstance(entry["inputs"], dict) or not isinstance(entry["result"], dict):
            return None, "inputs and result must be JSON objects"
        try:
            digest = _entry_digest(key, entry["inputs"], entry["result"])
        except ValueError:  # NaN or Infinity written by hand: json.loads accepts them
            return None, "contains NaN or infinity"
        if entry["sha256"] != digest:
            return None, "sha256 mismatch (content altered)"
        return entry, None

    def _corrupt(self, key: str, path: Path, reason: str) -> None:
        """Move a bad entry to `corrupt/<key>.<n>.json` (first free n >= 1) and record why."""
        self.n_corrupt += 1
        self.corrupt_reasons.append(f"{key}: {reason}")
        self.corrupt_dir.mkdir(exist_ok=True)
        for n in range(1, 1_000_000):
            target = self.corrupt_dir / f"{key}.{n}.json"
            if target.exists():
                continue
            try:
                os.rename(path, target)
            except FileNotFoundError:  # already moved away (by another reader)
                return None
            except OSError as err:
                self.corrupt_reasons[-1] += f" (could not move it to corrupt/: {err})"
                return None
            fsync_directory(path.parent)
            fsync_directory(self.corrupt_dir)
            return None
        return None

    def keys(self) -> list[str]:
        """Sorted keys of the entries present (not verified; `get` verifies)."""
        found = []
        for shard in self.path.iterdir():
            if len(shard.name) != 2 or not shard.is_dir():
                continue
            for entry in shard.glob("*.json"):
                key = entry.stem
                if _KEY.fullmatch(key) and key[:2] == shard.name:
                    found.append(key)
        return sorted(found)

    def __len__(self) -> int:
        return len(self.keys())

    @staticmethod
    def count(campaign_dir: str | os.PathLike[str]) -> int:
        """Entries present in a campaign's journal, without creating anything (status)."""
        return sum(1 for _ in (Path(campaign_dir) / "journal").glob("??/*.json"))

    def __contains__(self, key: object) -> bool:
        """Whether an entry file for `key` exists (not verified)."""
        return isinstance(key, str) and bool(_KEY.fullmatch(key)) and self.entry_path(key).exists()

    def computed_counts(self) -> collections.Counter[str]:
        """How many times each key was put, from `computed.log`.

        A last line without its newline (a write cut short) and lines that are not keys are
        ignored. A key counted more than once was computed more than once.
        """
        try:
            data = self.log_path.read_bytes()
        except FileNotFoundError:
            return collections.Counter()
        lines = data.split(b"\n")[:-1]  # the part after the last newline is incomplete
        return collections.Counter(
            text for line in lines if _KEY.fullmatch(text := line.decode("ascii", "replace"))
        )

    # writing ------------------------------------------------------------------------------

    def put(self, key: str, inputs: dict[str, Any], result: dict[str, Any]) -> None:
        """Commit run `key` at once, then log it in `computed.log`.

        The entry `{"version": 1, "key", "inputs", "result", "sha256"}` is written as JSON
        to a temporary file next to its final name and renamed over it: a killed process
        leaves no entry or the complete one. An existing entry of `key` is replaced
        atomically. Then the line `<key>` is appended to `computed.log` (O_APPEND), also
        when the entry existed before.

        No fsync: it cost 1.5 ms a run here, as much as a typical decision run. A process
        that dies (SIGKILL, Ctrl-C) cannot lose a renamed entry; a power loss can lose or
        tear the latest ones, and a torn entry fails its sha256 in `get` and is computed
        again, which is the journal's contract anyway.

        `inputs` and `result` must be JSON-serializable dicts without NaN or infinity (pass
        None for a missing number): ValueError names the offending field, TypeError a value
        JSON cannot store.
        """
        _check_key(key)
        for name, value in (("inputs", inputs), ("result", result)):
            if not isinstance(value, dict):
                raise TypeError(f"journal entry {key}: {name} must be a dict, got {value!r}")
        try:
            # Round-trip through JSON first, so the digest is computed on exactly what a
            # reader will load (tuples become lists, etc.).
            inputs, result = json.loads(_canonical_json([inputs, result]))
        except ValueError as err:  # NaN or infinity: walk the values only now, to name it
            for name, value in (("inputs", inputs), ("result", result)):
                bad = _non_finite_path(value, name)
                if bad is not None:
                    raise ValueError(
                        f"journal entry {key}: {bad} is NaN or infinite, which JSON cannot "
                        "store; pass None for a missing number"
                    ) from None
            raise ValueError(f"journal entry {key}: {err}; pass None for NaN") from None
        except TypeError as err:
            raise TypeError(f"journal entry {key}: {err}") from None
        entry = {
            "version": ENTRY_VERSION,
            "key": key,
            "inputs": inputs,
            "result": result,
            "sha256": _entry_digest(key, inputs, result),
        }
        # compact: indent would switch json to its pure-Python encoder (3x slower here)
        data = (json.dumps(entry, sort_keys=True, allow_nan=False) + "\n").encode()

        path = self.entry_path(key)
        if not path.parent.is_dir():
            path.parent.mkdir(exist_ok=True)
        tmp = temporary_name(path)
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
            with open(fd, "wb") as fh:
                fh.write(data)
            os.replace(tmp, path)
        except BaseException:
            with contextlib.suppress(OSError):
                tmp.unlink()
            raise
        self._log(key)

    def _log(self, key: str) -> None:
        """Append `<key>\\n` to computed.log in one write (O_APPEND: atomic per line)."""
        fd = os.open(self.log_path, os.O_RDWR | os.O_APPEND | os.O_CREAT, 0o666)
        try:
            line = f"{key}\n".encode()
            size = os.fstat(fd).st_size
            if size and os.pread(fd, 1, size - 1) != b"\n":
                # A previous append was cut short: end that line first, so it cannot
                # swallow this key (computed_counts ignores the fragment).
                line = b"\n" + line
            os.write(fd, line)
        finally:
            os.close(fd)

    def clean_temp_files(self) -> int:
        """Remove temporary files left by writers that died mid-put; returns how many.

        Call it only while holding the campaign's `CampaignLock`: it would also remove the
        temporary file of a live writer.
        """
        removed = 0
        for tmp in self.path.glob(f"??/.*{TEMP_SUFFIX}"):
            with contextlib.suppress(FileNotFoundError):
                tmp.unlink()
                removed += 1
        return removed


# --- lock ---------------------------------------------------------------------------------

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
        fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o666)
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
            fd = os.open(Path(campaign_dir) / "lock", os.O_RDONLY)
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
