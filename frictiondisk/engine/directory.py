"""The campaign directory DIR (its file names: frictiondisk.store.layout): the campaign
record check, the refusal of symbolic links, and status.json (see
frictiondisk.engine.runner for the layout); and a
folder of several campaigns (`run A.yaml B.yaml -o DIR`): DIR/campaigns.json names its
campaigns, each in DIR/<name>/."""

from __future__ import annotations

import hashlib
import json
import os
import re
import time
from pathlib import Path

from frictiondisk.model.scene import ConfigError
from frictiondisk.store.files import atomic_write_bytes, atomic_write_text
from frictiondisk.store.layout import (
    CAMPAIGN_FILE,
    DIR_NAMES,
    MANIFEST_FILE,
    RECORD_FILE,
    STATUS_FILE,
)
from frictiondisk.store.paths import refuse_symlink
from frictiondisk.tasks.campaign import Campaign, campaign_from_dict, load_campaign

_NAME = re.compile(r"[A-Za-z0-9_-]+")  # a campaign's name (tasks/campaign_file.py)


class CampaignChanged(Exception):
    """The campaign file differs from the one DIR was started with."""

    def __init__(self, out_dir: Path, differences: list[str]):
        self.out_dir = out_dir
        self.differences = differences
        super().__init__(
            f"{out_dir} holds a different campaign; refusing to mix results "
            f"(start a new directory, or resume with the original file):\n  "
            + "\n  ".join(differences)
        )


def prepare_directory(out_dir: Path, campaign: Campaign | None) -> Campaign:
    """Check DIR against the campaign (or load the stored one when campaign is None)."""
    stored_file = out_dir / CAMPAIGN_FILE
    if stored_file.exists():
        stored = load_campaign(stored_file)
        _check_record(out_dir, stored)
        if campaign is None:
            return stored
        differences = stored.diff(campaign)
        if differences:
            raise CampaignChanged(out_dir, differences)
        return stored
    if campaign is None:
        raise FileNotFoundError(f"{out_dir} is not a campaign directory (no {CAMPAIGN_FILE})")
    out_dir.mkdir(parents=True, exist_ok=True)
    atomic_write_text(stored_file, campaign.text)
    _write_record(out_dir, campaign)
    return campaign


def _text_digest(campaign: Campaign) -> str:
    return hashlib.sha256(campaign.text.encode()).hexdigest()


def _write_record(out_dir: Path, campaign: Campaign) -> None:
    record = {"sha256": _text_digest(campaign), "canonical": campaign.canonical()}
    atomic_write_text(out_dir / RECORD_FILE, json.dumps(record, indent=1) + "\n")


def _check_record(out_dir: Path, stored: Campaign) -> None:
    """Refuse a DIR/campaign.yaml edited since the campaign started, naming each change.
    A DIR from before the record existed gets one now."""
    if not (out_dir / RECORD_FILE).exists():
        _write_record(out_dir, stored)
        return
    differences = record_differences(out_dir, stored)
    if differences:
        raise CampaignChanged(out_dir, differences)


def record_differences(out_dir: Path, stored: Campaign) -> list[str]:
    """Read-only: how DIR/campaign.yaml (`stored`) differs from its record, one line per
    changed field after a header line; [] if unedited or if there is no record.

    Its text matching the recorded sha256 is the fast path. Otherwise the recorded
    canonical form decides, like a changed campaign file: an edit that changes nothing
    (a comment) is accepted, anything else is a difference."""
    path = out_dir / RECORD_FILE
    if not path.exists():
        return []
    try:
        record = json.loads(refuse_symlink(path).read_text(encoding="utf-8"))
        if record["sha256"] == _text_digest(stored):
            return []
        original = campaign_from_dict(record["canonical"], source=str(path))
    except (ValueError, KeyError, TypeError, ConfigError) as err:
        return [
            f"{path} is damaged ({type(err).__name__}); cannot tell whether "
            f"{CAMPAIGN_FILE} was edited"
        ]
    differences = original.diff(stored)
    if not differences:
        return []
    return [f"{out_dir / CAMPAIGN_FILE} was edited after the campaign started:", *differences]


def refuse_links(out_dir: Path) -> None:
    """SymlinkRefused (an OSError naming the path) if any name the driver uses in DIR, or
    any journal shard folder, is a symbolic link."""
    for name in DIR_NAMES:
        refuse_symlink(out_dir / name)
    journal = out_dir / "journal"
    if journal.is_dir():
        for shard in journal.iterdir():
            if len(shard.name) == 2:
                refuse_symlink(shard)


def write_status(
    out_dir: Path,
    state: str,
    campaign: Campaign,
    *,
    points_total: int,
    points_done: int,
    points_failed: int,
    runs_done: int,
    jobs_in_flight: int,
    runs_computed_now: int,
    elapsed_s: float,
    eta_s: float | None,
) -> None:
    """Rewrite DIR/status.json (read by `frictiondisk status`), atomically."""
    status = {
        "state": state,
        "pid": os.getpid(),
        "campaign": campaign.name,
        "points_total": points_total,
        "points_done": points_done,
        "points_failed": points_failed,
        "runs_done": runs_done,
        "jobs_in_flight": jobs_in_flight,  # Dask tasks: batches of runs, or chains of a point
        "runs_computed_now": runs_computed_now,
        "elapsed_s": elapsed_s,
        "eta_s": eta_s,
        "updated": time.time(),
    }
    # a running campaign rewrites it every driver.STATUS_EVERY s: no fsync (two per rewrite
    # cost ~2 ms here); the final state is made durable
    data = json.dumps(status, indent=1).encode()
    atomic_write_bytes(out_dir / STATUS_FILE, data, durable=state != "running")


class FolderDamaged(ValueError):
    """DIR/campaigns.json cannot be read as a list of campaign names."""


def is_campaign_folder(out_dir: Path) -> bool:
    """Whether DIR holds several campaigns (DIR/campaigns.json), not one."""
    return (out_dir / MANIFEST_FILE).is_file()


def read_manifest(out_dir: Path) -> list[str]:
    """The campaign names DIR/campaigns.json lists, in order (FolderDamaged if it cannot
    be read as such)."""
    path = out_dir / MANIFEST_FILE
    try:
        names = json.loads(refuse_symlink(path).read_text(encoding="utf-8"))["campaigns"]
    except (ValueError, KeyError, TypeError) as err:
        raise FolderDamaged(f"{path} is damaged ({type(err).__name__}: {err})") from None
    if not isinstance(names, list) or not all(
        isinstance(name, str) and _NAME.fullmatch(name) for name in names
    ):
        raise FolderDamaged(f"{path}: `campaigns` must be a list of campaign names")
    return names


def write_manifest(out_dir: Path, names: list[str]) -> list[str]:
    """Add `names` to DIR/campaigns.json (kept in order, each once); returns them all.
    The caller holds DIR's lock."""
    known = read_manifest(out_dir) if (out_dir / MANIFEST_FILE).exists() else []
    names = known + [name for name in names if name not in known]
    text = json.dumps({"campaigns": names}, indent=1) + "\n"
    atomic_write_text(out_dir / MANIFEST_FILE, text)
    return names
