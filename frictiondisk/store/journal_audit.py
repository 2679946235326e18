"""A read-only check of a campaign's journal, for `status`: which entries fail verification
now (`audit`), and which were moved aside before (`moved_aside`). Nothing is created,
moved or repaired (frictiondisk.store.journal does that when a run asks for its key)."""

from __future__ import annotations

import os
from pathlib import Path

from frictiondisk.store.journal_entry import KEY, verify
from frictiondisk.store.journal_packs import PACKS, pack_files, pack_lines
from frictiondisk.store.paths import SymlinkRefused, read_nofollow

REASONS_LOG = "reasons.log"  # in journal/corrupt/: why each entry was moved there


def audit(campaign_dir: str | os.PathLike[str]) -> tuple[list[str], list[str]]:
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
            if not KEY.fullmatch(key):
                continue
            try:
                raw = read_nofollow(path)
            except SymlinkRefused:
                problems.append(f"{key}: a symbolic link (never followed)")
                continue
            except OSError as err:
                problems.append(f"{key}: unreadable ({err.strerror or err})")
                continue
            _, reason = verify(key, raw)
            if reason is not None:
                problems.append(f"{key}: {reason}")
    return problems + _audit_packs(journal), moved_aside(campaign_dir)


def _audit_packs(journal: Path) -> list[str]:
    """The problems of the entries held in packs (store/journal_packs.py)."""
    if (journal / PACKS).is_symlink():
        return [f"{PACKS}/: a symbolic link; refusing to follow it"]
    problems = []
    for path in pack_files(journal):
        try:
            data = read_nofollow(path)
        except OSError as err:
            problems.append(f"{PACKS}/{path.name}: unreadable ({err})")
            continue
        for key, start, end in pack_lines(data):
            _, reason = verify(key, data[start:end])
            if reason is not None:
                problems.append(f"{key}: {reason} (in {PACKS}/{path.name})")
    return problems


def moved_aside(campaign_dir: str | os.PathLike[str]) -> list[str]:
    """Lines "<file>: <reason>" of every entry moved to corrupt/ so far (reasons.log)."""
    log = Path(campaign_dir) / "journal" / "corrupt" / REASONS_LOG
    try:
        data = read_nofollow(log)
    except OSError:
        return []
    lines = data.decode("utf-8", "replace").splitlines()
    return [line.replace("\t", ": ", 1) for line in lines if "\t" in line]
