"""Append-only run journal of a campaign directory (its lock is in store/lock.py).

Layout of a campaign directory DIR::

    DIR/lock                        flock'ed by the one process allowed to write (CampaignLock)
    DIR/journal/<kk>/<key>.json     one entry per finished run, kk = key[:2]
    DIR/journal/packs/<n>.pack      the entries of one batch of runs, one line each (put_many)
    DIR/journal/computed.log        one line "<key>" appended per put (what was computed, when)
    DIR/journal/corrupt/<key>.<n>.json   entries that failed verification, kept for inspection
    DIR/journal/corrupt/reasons.log      one line "<key>.<n>.json<TAB><reason>" per entry moved

A run is addressed by its key (journal_entry.run_key): the sha256 of its canonical scene plus the
kernel version, so a changed input or changed numerics give a new key and an old entry is
simply never looked up again. Each entry is written to a temporary file and renamed
(`Journal.put`), so a crash leaves either no entry or a complete one; a reader still verifies
every entry (`Journal.get`) and treats anything that fails as absent, i.e. to be recomputed.

Integrity. An entry stores its run's full canonical scene (`inputs`); on read the
key is recomputed from them, so an entry filed under another run's key (a copy, a mix-up, an
edited input) is rejected. No symbolic link inside DIR is followed: the lock, the log and
every entry are opened with O_NOFOLLOW, and a linked journal folder is refused. Threat model:
this protects against corruption and mix-ups, not against a malicious writer to DIR, who can
always write a self-consistent entry.
"""

from __future__ import annotations

import collections
import contextlib
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from frictiondisk.store.files import TEMP_SUFFIX, atomic_write_bytes, fsync_directory
from frictiondisk.store.journal_audit import REASONS_LOG
from frictiondisk.store.journal_entry import KEY, check_key, encode, verify
from frictiondisk.store.journal_packs import (
    PACKS,
    count_lines,
    pack_bytes,
    pack_files,
    pack_lines,
    pack_name,
    pack_number,
)
from frictiondisk.store.paths import SymlinkRefused, open_nofollow, read_nofollow, refuse_symlink

__all__ = ["Journal"]


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
        # key -> (pack file name, start, end) of its line, read at first use (journal_packs)
        self._packs: dict[str, tuple[str, int, int]] | None = None
        self._pack_data: tuple[str, bytes] | None = None  # the pack read last, kept
        self._next_pack = 1

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
        check_key(key)
        shard = key[:2]
        if shard in self._shards:
            return self.path / shard / f"{key}.json"
        return refuse_symlink(self.path / shard) / f"{key}.json"

    # reading ------------------------------------------------------------------------------

    def get(self, key: str) -> dict[str, Any] | None:
        """The stored result of run `key`, or None if there is none or it is not trustworthy
        (`entry`)."""
        entry = self.entry(key)
        return None if entry is None else entry["result"]

    def entry(self, key: str) -> dict[str, Any] | None:
        """The stored entry of run `key` (its inputs and result), or None if there is none
        or it is not trustworthy.

        An entry is trusted only if it is a regular file (not a symbolic link) of UTF-8 JSON
        with the fields version (= 1), key, inputs, result and sha256, its key equals `key`,
        its sha256 matches the canonical JSON of {"key", "inputs", "result"} and its inputs
        give `key` again (`key_of_inputs`). Otherwise it is moved to
        `corrupt/<key>.<n>.json`, counted in `n_corrupt`, explained in `corrupt_reasons` and
        None is returned. A missing entry gives None and is not counted. An entry in a pack
        is checked the same way; one that fails is reported and left in its pack.
        """
        if key in self._pack_index():
            return self._get_packed(key)
        path = self.entry_path(key)
        try:
            raw = read_nofollow(path)
        except FileNotFoundError:
            return None
        except SymlinkRefused:
            return self._corrupt(key, path, "a symbolic link (never followed)")
        except OSError as err:
            return self._corrupt(key, path, f"unreadable ({err.strerror or err})")
        entry, reason = verify(key, raw)
        if reason is not None:
            return self._corrupt(key, path, reason)
        return entry

    def _pack_index(self) -> dict[str, tuple[str, int, int]]:
        """key -> where its line is, over every pack (a later pack wins), read once."""
        if self._packs is None:
            self._packs = {}
            for path in pack_files(self.path):
                self._next_pack = max(self._next_pack, (pack_number(path) or 0) + 1)
                try:
                    data = read_nofollow(path)
                except OSError as err:
                    self._note_corrupt(f"{PACKS}/{path.name}", f"unreadable ({err})")
                    continue
                for key, start, end in pack_lines(data):
                    self._packs[key] = (path.name, start, end)
        return self._packs

    def _get_packed(self, key: str) -> dict[str, Any] | None:
        """The verified entry of `key` from its pack's line; a line that fails is
        dropped from the index and reported (the pack stays: it holds other runs)."""
        name, start, end = self._packs[key]
        if self._pack_data is None or self._pack_data[0] != name:
            try:
                self._pack_data = (name, read_nofollow(self.path / PACKS / name))
            except OSError as err:
                del self._packs[key]
                return self._note_corrupt(key, f"its pack {name} is unreadable ({err})")
        entry, reason = verify(key, self._pack_data[1][start:end])
        if reason is not None:
            del self._packs[key]
            return self._note_corrupt(key, f"{reason} (in {PACKS}/{name})")
        return entry

    def _note_corrupt(self, what: str, reason: str) -> None:
        """Count and report a bad entry that cannot be moved aside (a line of a pack)."""
        self.n_corrupt += 1
        self.corrupt_reasons.append(f"{what}: {reason}")
        refuse_symlink(self.corrupt_dir).mkdir(exist_ok=True)
        append_to(self.corrupt_dir / REASONS_LOG, f"{what}\t{reason}\n")
        return None

    @classmethod
    def peek(cls, campaign_dir: str | os.PathLike[str], key: str) -> dict[str, Any] | None:
        """Read-only `get` for workers: the verified result of `key`, else None.

        Writes nothing (no folder is created, a bad entry stays where it is for the driver's
        `get` to deal with), so a worker may call it while the driver holds the lock. It
        reads single entries only (`put`: the runs of a search chain), not packs."""
        check_key(key)
        shard = Path(campaign_dir) / "journal" / key[:2]
        if shard.is_symlink() or shard.parent.is_symlink():
            return None
        try:
            raw = read_nofollow(shard / f"{key}.json")
        except OSError:
            return None
        entry, reason = verify(key, raw)
        return None if reason is not None else entry["result"]

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
            append_to(self.corrupt_dir / REASONS_LOG, f"{target.name}\t{reason}\n")
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
                if KEY.fullmatch(key) and key[:2] == shard.name:
                    found.append(key)
        return sorted(set(found) | set(self._pack_index()))

    def __len__(self) -> int:
        return len(self.keys())

    @staticmethod
    def count(campaign_dir: str | os.PathLike[str]) -> int:
        """Entries present in a campaign's journal, without creating anything (status)."""
        journal = Path(campaign_dir) / "journal"
        return sum(1 for _ in journal.glob("??/*.json")) + count_lines(journal)

    def __contains__(self, key: object) -> bool:
        """Whether an entry file for `key` exists (not verified)."""
        if not isinstance(key, str) or not KEY.fullmatch(key):
            return False
        return key in self._pack_index() or self.entry_path(key).exists()

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
            text for line in lines if KEY.fullmatch(text := line.decode("ascii", "replace"))
        )

    # writing ------------------------------------------------------------------------------

    def put(
        self,
        key: str,
        inputs: dict[str, Any],
        result: dict[str, Any],
        inputs_text: str | None = None,
    ) -> None:
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

        `inputs`, `result` and `inputs_text`: as journal_entry.encode takes them
        (ValueError, TypeError).
        """
        data = encode(key, inputs, result, inputs_text)

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

    def put_many(
        self,
        entries: list[tuple[str, dict[str, Any], dict[str, Any]]],
        inputs_texts: Mapping[str, str] | None = None,
    ) -> None:
        """Commit the runs (key, inputs, result) of one batch at once, as one pack
        (store/journal_packs.py): a temporary file renamed, so a killed process leaves
        all of them or none; then their keys in computed.log, in one write. Same entries,
        same checks and the same promise as `put`, at one file per batch. inputs_texts:
        key -> canonical_json of its inputs, where already written (encode)."""
        if not entries:
            return
        texts = inputs_texts or {}
        data = pack_bytes(
            [(key, encode(key, inputs, result, texts.get(key))) for key, inputs, result in entries]
        )
        index = self._pack_index()
        folder = refuse_symlink(self.path / PACKS)
        if PACKS not in self._shards:
            folder.mkdir(exist_ok=True)
            self._shards.add(PACKS)
        name = pack_name(self._next_pack)
        while os.path.lexists(folder / name):  # written by an earlier process
            self._next_pack += 1
            name = pack_name(self._next_pack)
        self._next_pack += 1
        atomic_write_bytes(folder / name, data, durable=False, make_parents=False)
        for key, start, end in pack_lines(data):
            index[key] = (name, start, end)
        self._pack_data = (name, data)
        if self._log_fd is None:
            self._log_fd = open_nofollow(self.log_path, os.O_RDWR | os.O_APPEND | os.O_CREAT)
        append_line(self._log_fd, "".join(f"{key}\n" for key, _, _ in entries))

    def _log(self, key: str) -> None:
        """Append `<key>\\n` to computed.log in one write (O_APPEND: atomic per line). The
        file stays open for the next put (see `close`): on slow file systems opening it by
        name cost more than the rest of a put."""
        if self._log_fd is None:
            self._log_fd = open_nofollow(self.log_path, os.O_RDWR | os.O_APPEND | os.O_CREAT)
        append_line(self._log_fd, f"{key}\n")

    def clean_temp_files(self) -> int:
        """Remove temporary files left by writers that died mid-put; returns how many.

        Call it only while holding the campaign's `CampaignLock`: it would also remove the
        temporary file of a live writer.
        """
        removed = 0
        for tmp in [
            *self.path.glob(f"??/.*{TEMP_SUFFIX}"),
            *self.path.glob(f"{PACKS}/.*{TEMP_SUFFIX}"),
        ]:
            if tmp.parent.is_symlink():  # never reach outside DIR through a linked shard
                continue
            with contextlib.suppress(FileNotFoundError):
                tmp.unlink()
                removed += 1
        return removed


def append_line(fd: int, text: str) -> None:
    """Append one line to the open file `fd` in one write."""
    line = text.encode()
    size = os.fstat(fd).st_size
    if size and os.pread(fd, 1, size - 1) != b"\n":
        # A previous append was cut short: end that line first, so it cannot
        # swallow this key (computed_counts ignores the fragment).
        line = b"\n" + line
    os.write(fd, line)


def append_to(path: Path, text: str) -> None:
    """Append one line to `path` in one write (O_APPEND, O_NOFOLLOW)."""
    fd = open_nofollow(path, os.O_RDWR | os.O_APPEND | os.O_CREAT)
    try:
        append_line(fd, text)
    finally:
        os.close(fd)
