"""Append-only run journal of a campaign directory (its lock is in store/lock.py).

Layout of a campaign directory DIR::

    DIR/lock                        flock'ed by the one process allowed to write (CampaignLock)
    DIR/journal/<kk>/<key>.json     one entry per finished run, kk = key[:2]
    DIR/journal/computed.log        one line "<key>" appended per put (what was computed, when)
    DIR/journal/corrupt/<key>.<n>.json   entries that failed verification, kept for inspection
    DIR/journal/corrupt/reasons.log      one line "<key>.<n>.json<TAB><reason>" per entry moved

A run is addressed by its key (`run_key`): the sha256 of its canonical scene plus the
kernel version, so a changed input or changed numerics give a new key and an old entry is
simply never looked up again. Each entry is written to a temporary file and renamed
(`Journal.put`), so a crash leaves either no entry or a complete one; a reader still verifies
every entry (`Journal.get`) and treats anything that fails as absent, i.e. to be recomputed.

Integrity (issue 14). An entry stores its run's full canonical scene (`inputs`); on read the
key is recomputed from them, so an entry filed under another run's key (a copy, a mix-up, an
edited input) is rejected. No symbolic link inside DIR is followed: the lock, the log and
every entry are opened with O_NOFOLLOW, and a linked journal folder is refused. Threat model:
this protects against corruption and mix-ups, not against a malicious writer to DIR, who can
always write a self-consistent entry.
"""

from __future__ import annotations

import collections
import contextlib
import functools
import hashlib
import json
import math
import os
import re
from importlib import metadata
from pathlib import Path
from typing import Any

from frictiondisk.store.files import TEMP_SUFFIX, atomic_write_bytes, fsync_directory
from frictiondisk.store.paths import SymlinkRefused, open_nofollow, read_nofollow, refuse_symlink
from frictiondisk.version import NUMERICS_VERSION

__all__ = [
    "ENTRY_VERSION",
    "Journal",
    "kernel_version",
    "run_key",
]

ENTRY_VERSION = 1
_REASONS_LOG = "reasons.log"  # in journal/corrupt/: why each entry was moved there
_ENTRY_FIELDS = ("version", "key", "inputs", "result", "sha256")
_KEY = re.compile(r"[0-9a-f]{64}")  # a sha256 hex digest, as made by run_key


# --- keys ---------------------------------------------------------------------------------

# The libraries whose versions change what a run computes (numba compiles the kernel, numpy
# and scipy do its arithmetic, scipy-radau and coulomb integrate with scipy).
NUMERICS_LIBRARIES = ("numba", "numpy", "scipy")


@functools.cache
def kernel_version() -> str:
    """Version of the numerics, part of every `run_key`, e.g.
    "numerics 1, numba 0.68.1, numpy 2.4.6, scipy 1.17.1".

    `NUMERICS_VERSION` (frictiondisk/version.py) is bumped by hand with any change that
    alters what a run computes; an edited comment or docstring leaves every key as it was.
    The library versions come from the installed distributions' metadata (nothing is
    imported): a new numba, numpy or scipy can change results in the last digits, so
    journal entries computed with other versions are not reused. Computed once per process.
    """
    libraries = ", ".join(f"{name} {metadata.version(name)}" for name in NUMERICS_LIBRARIES)
    return f"numerics {NUMERICS_VERSION}, {libraries}"


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


class _Inputs:
    """Stored canonical inputs, seen by `run_key` as the config they came from."""

    def __init__(self, canonical: dict[str, Any]) -> None:
        self._canonical = canonical

    def canonical(self) -> dict[str, Any]:
        return self._canonical


def key_of_inputs(inputs: dict[str, Any]) -> str:
    """The key `run_key` gives the config whose canonical form is `inputs` (current numerics)."""
    return run_key(_Inputs(inputs))


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
        self.path = refuse_symlink(self.campaign_dir / "journal")
        self.path.mkdir(parents=True, exist_ok=True)
        self.log_path = refuse_symlink(self.path / "computed.log")
        self.corrupt_dir = refuse_symlink(self.path / "corrupt")
        self.n_corrupt = 0
        self.corrupt_reasons: list[str] = []
        # Shard folders this object has checked (not a link) and made: a driver puts
        # thousands of entries, and on slow file systems the lstat and mkdir of each put
        # cost more than the rest of the put. Only the lock holder writes the journal.
        self._shards: set[str] = set()
        self._log_fd: int | None = None  # computed.log, open for appending after the first put

    def close(self) -> None:
        """Close computed.log if a put opened it (puts after this open it again)."""
        fd, self._log_fd = self._log_fd, None
        if fd is not None:
            os.close(fd)

    def __del__(self) -> None:
        with contextlib.suppress(Exception):
            self.close()

    def entry_path(self, key: str) -> Path:
        """Where the entry of `key` lives: `path/<key[:2]>/<key>.json`."""
        _check_key(key)
        shard = key[:2]
        if shard in self._shards:
            return self.path / shard / f"{key}.json"
        return refuse_symlink(self.path / shard) / f"{key}.json"

    # reading ------------------------------------------------------------------------------

    def get(self, key: str) -> dict[str, Any] | None:
        """The stored result of run `key`, or None if there is none or it is not trustworthy.

        An entry is trusted only if it is a regular file (not a symbolic link) of UTF-8 JSON
        with the fields version (= 1), key, inputs, result and sha256, its key equals `key`,
        its sha256 matches the canonical JSON of {"key", "inputs", "result"} and its inputs
        give `key` again (`key_of_inputs`). Otherwise it is moved to
        `corrupt/<key>.<n>.json`, counted in `n_corrupt`, explained in `corrupt_reasons` and
        None is returned. A missing entry gives None and is not counted.
        """
        path = self.entry_path(key)
        try:
            raw = read_nofollow(path)
        except FileNotFoundError:
            return None
        except SymlinkRefused:
            return self._corrupt(key, path, "a symbolic link (never followed)")
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
        shard = Path(campaign_dir) / "journal" / key[:2]
        if shard.is_symlink() or shard.parent.is_symlink():
            return None
        try:
            raw = read_nofollow(shard / f"{key}.json")
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
        try:
            from_inputs = key_of_inputs(entry["inputs"])
        except (TypeError, ValueError) as err:
            return None, f"inputs cannot be hashed ({err})"
        if from_inputs != key:
            return None, (
                f"its inputs give key {from_inputs[:12]}..., not {key[:12]}... "
                "(an entry of another run, edited inputs, or other numerics)"
            )
        return entry, None

    @classmethod
    def audit(cls, campaign_dir: str | os.PathLike[str]) -> tuple[list[str], list[str]]:
        """Read-only check of a journal for `status`: (problems of the entries present,
        reasons of the entries already moved to corrupt/), one line each.

        An entry whose inputs give another key under the current numerics is listed too:
        it is either stale (written by other numerics: never looked up again) or filed
        under the wrong key; `get` moves it aside only if a run asks for its key."""
        journal = Path(campaign_dir) / "journal"
        problems: list[str] = []
        if journal.is_symlink():
            return [f"{journal}: a symbolic link; refusing to follow it"], []
        if not journal.is_dir():
            return [], []
        for shard in sorted(journal.iterdir()):
            if len(shard.name) != 2:
                continue
            if shard.is_symlink():
                problems.append(f"{shard.name}/: a symbolic link; refusing to follow it")
                continue
            if not shard.is_dir():
                continue
            for path in sorted(shard.glob("*.json")):
                key = path.stem
                if not _KEY.fullmatch(key):
                    continue
                try:
                    raw = read_nofollow(path)
                except SymlinkRefused:
                    problems.append(f"{key}: a symbolic link (never followed)")
                    continue
                except OSError as err:
                    problems.append(f"{key}: unreadable ({err.strerror or err})")
                    continue
                _, reason = cls._verify(key, raw)
                if reason is not None:
                    problems.append(f"{key}: {reason}")
        return problems, cls.moved_aside(campaign_dir)

    @staticmethod
    def moved_aside(campaign_dir: str | os.PathLike[str]) -> list[str]:
        """Lines "<file>: <reason>" of every entry moved to corrupt/ so far (reasons.log)."""
        log = Path(campaign_dir) / "journal" / "corrupt" / _REASONS_LOG
        try:
            data = read_nofollow(log)
        except OSError:
            return []
        lines = data.decode("utf-8", "replace").splitlines()
        return [line.replace("\t", ": ", 1) for line in lines if "\t" in line]

    def _corrupt(self, key: str, path: Path, reason: str) -> None:
        """Move a bad entry to `corrupt/<key>.<n>.json` (first free n >= 1) and record why."""
        self.n_corrupt += 1
        self.corrupt_reasons.append(f"{key}: {reason}")
        refuse_symlink(self.corrupt_dir).mkdir(exist_ok=True)
        for n in range(1, 1_000_000):
            target = self.corrupt_dir / f"{key}.{n}.json"
            if os.path.lexists(target):
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
            self._append(self.corrupt_dir / _REASONS_LOG, f"{target.name}\t{reason}\n")
            return None
        return None

    def keys(self) -> list[str]:
        """Sorted keys of the entries present (not verified; `get` verifies)."""
        found = []
        for shard in self.path.iterdir():
            if len(shard.name) != 2 or shard.is_symlink() or not shard.is_dir():
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
            data = read_nofollow(self.log_path)
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
        if key[:2] not in self._shards:
            path.parent.mkdir(exist_ok=True)
            self._shards.add(key[:2])
        if os.path.lexists(path):
            # a run recomputed by a worker, which only peeks: a bad entry in its place is
            # moved aside and reported here, never silently overwritten
            self.get(key)
        # no fsync: a torn entry fails its sha256 on read and is computed again
        atomic_write_bytes(path, data, durable=False, make_parents=False)
        self._log(key)

    def _log(self, key: str) -> None:
        """Append `<key>\\n` to computed.log in one write (O_APPEND: atomic per line). The
        file stays open for the next put (see `close`): on slow file systems opening it by
        name cost more than the rest of a put."""
        if self._log_fd is None:
            self._log_fd = open_nofollow(self.log_path, os.O_RDWR | os.O_APPEND | os.O_CREAT)
        self._write_line(self._log_fd, f"{key}\n")

    @staticmethod
    def _write_line(fd: int, text: str) -> None:
        """Append one line to the open file `fd` in one write."""
        line = text.encode()
        size = os.fstat(fd).st_size
        if size and os.pread(fd, 1, size - 1) != b"\n":
            # A previous append was cut short: end that line first, so it cannot
            # swallow this key (computed_counts ignores the fragment).
            line = b"\n" + line
        os.write(fd, line)

    @classmethod
    def _append(cls, path: Path, text: str) -> None:
        """Append one line to `path` in one write (O_APPEND, O_NOFOLLOW)."""
        fd = open_nofollow(path, os.O_RDWR | os.O_APPEND | os.O_CREAT)
        try:
            cls._write_line(fd, text)
        finally:
            os.close(fd)

    def clean_temp_files(self) -> int:
        """Remove temporary files left by writers that died mid-put; returns how many.

        Call it only while holding the campaign's `CampaignLock`: it would also remove the
        temporary file of a live writer.
        """
        removed = 0
        for tmp in self.path.glob(f"??/.*{TEMP_SUFFIX}"):
            if tmp.parent.is_symlink():  # never reach outside DIR through a linked shard
                continue
            with contextlib.suppress(FileNotFoundError):
                tmp.unlink()
                removed += 1
        return removed
