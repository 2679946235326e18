"""Packs: the journal entries of one finished batch of runs in one file (store/journal.py).

A batch of short runs comes back from a worker at once; writing its entries as one file
costs one create and one rename instead of one per run (on this file system about 1 ms a
run, as much as a short run's kernel). The promise is the journal's: the pack is written
to a temporary file and renamed, so a killed process leaves the whole batch or none of it.

Layout: `journal/packs/<n>.pack`, n = 1, 2, ... (zero-padded). Each line is one entry:
its 64-digit key, a space, and the entry's JSON exactly as a single entry file holds it
(journal_entry.encode), so every line verifies on its own; a line that fails is treated as
absent (its run is computed again and lands in a later pack, which wins)."""

from __future__ import annotations

import os
from pathlib import Path

from frictiondisk.store.journal_entry import KEY

PACKS = "packs"
SUFFIX = ".pack"


def pack_name(number: int) -> str:
    return f"{number:08d}{SUFFIX}"


def pack_number(path: Path) -> int | None:
    """n of `<n>.pack`, else None (a temporary file, or another name)."""
    stem = path.name[: -len(SUFFIX)] if path.name.endswith(SUFFIX) else ""
    return int(stem) if stem.isdigit() else None


def pack_files(journal: Path) -> list[Path]:
    """The packs of a journal folder, oldest first (none if the folder is a link)."""
    folder = journal / PACKS
    if folder.is_symlink() or not folder.is_dir():
        return []
    found = [(pack_number(path), path) for path in folder.iterdir()]
    return [path for number, path in sorted((n, p) for n, p in found if n is not None)]


def pack_lines(data: bytes) -> list[tuple[str, int, int]]:
    """(key, start, end) of each complete line of a pack's bytes: the entry's JSON is
    data[start:end]."""
    out = []
    start = 0
    while True:
        end = data.find(b"\n", start)
        if end < 0:
            return out
        key = data[start : start + 64].decode("ascii", "replace")
        if KEY.fullmatch(key) and data[start + 64 : start + 65] == b" ":
            out.append((key, start + 65, end))
        start = end + 1


def pack_bytes(entries: list[tuple[str, bytes]]) -> bytes:
    """A pack's content from (key, encoded entry) pairs."""
    return b"".join(key.encode() + b" " + encoded for key, encoded in entries)


def count_lines(journal: str | os.PathLike[str]) -> int:
    """Entries held in a journal folder's packs (not verified)."""
    total = 0
    for path in pack_files(Path(journal)):
        try:
            total += len(pack_lines(path.read_bytes()))
        except OSError:
            continue
    return total
