"""What `frictiondisk status` and the end of `run` / `resume` report of a campaign
directory, as lines of text (the CLI prints them): its state (running, interrupted,
complete, damaged), progress, the journal's health, a hand edit of its campaign.yaml, and
the answer so far, which its task's entry writes (TaskEntry.status_lines, run_lines)."""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np

from frictiondisk.engine.directory import record_differences
from frictiondisk.model.scene import ConfigError
from frictiondisk.store.files import netcdf_is_valid
from frictiondisk.store.journal_audit import audit
from frictiondisk.store.journal_entry import KEY
from frictiondisk.store.layout import CAMPAIGN_FILE, JOURNAL_DIR, RESULTS_FILE, STATUS_FILE
from frictiondisk.store.lock import CampaignLock
from frictiondisk.store.paths import refuse_symlink
from frictiondisk.tasks.campaign import load_campaign
from frictiondisk.tasks.registry import TASKS


class NotACampaign(Exception):
    """A directory that holds no campaign (no campaign.yaml)."""


def status_lines(out_dir: Path) -> list[str]:
    """The progress of the campaign in out_dir (NotACampaign if it holds none; OSError if
    its status cannot be read). It answers from the moment a run holds out_dir's lock
    (`starting`); without status.json (not yet written, or lost) the campaign's name and
    size come from campaign.yaml and the finished points from results.nc."""
    if not out_dir.exists():
        raise NotACampaign(f"{out_dir} does not exist")
    if not out_dir.is_dir():
        raise NotACampaign(f"{out_dir} is not a directory")
    holder = CampaignLock.holder(out_dir)
    if not (out_dir / CAMPAIGN_FILE).is_file():
        if holder is None:
            raise NotACampaign(f"{out_dir} is not a campaign directory (no {CAMPAIGN_FILE})")
        return [f"campaign:  ? in {out_dir}", f"state:     starting (pid {holder})"]
    info = _status_file(out_dir)
    results_ok = netcdf_is_valid(out_dir / RESULTS_FILE)
    info = {**_from_files(out_dir, results_ok), **info}
    # a task without a journal (a trajectory) counts its run in status.json
    runs_done = journal_count(out_dir) or int(info.get("runs_done", 0))
    state = info.get("state", "not started")
    if holder is not None:
        state = f"{'running' if info.get('written') else 'starting'} (pid {holder})"
    elif state == "running" or (state == "not started" and runs_done):
        state = "interrupted"
    if state == "complete" and not results_ok:
        state = "damaged"
    total = info.get("points_total", "?")
    lines = [
        f"campaign:  {info.get('campaign', '?')} in {out_dir}",
        f"state:     {state}",
        f"points:    {info.get('points_done', 0)} of {total} done, "
        f"{info.get('points_failed', 0)} failed",
        f"runs:      {runs_done} done; "
        f"{info.get('jobs_in_flight', 0) if holder else 0} {_tasks(info, holder)} in flight",
    ]
    eta = info.get("eta_s")
    if holder is not None and eta is not None:
        age = time.time() - info.get("updated", time.time())
        lines.append(f"time left: about {max(0.0, eta - age):.0f} s")
    if results_ok:  # a complete state always has them (else it is "damaged")
        lines += results_lines(out_dir / RESULTS_FILE, complete=state == "complete")
    if state == "damaged":
        lines.append(f"results.nc is missing or damaged; rebuild it: frictiondisk resume {out_dir}")
    elif state in ("interrupted", "not started"):
        lines.append(f"continue with: frictiondisk resume {out_dir}")
    return lines + journal_lines(out_dir) + edit_lines(out_dir)


def _tasks(info: dict, holder: int | None) -> str:
    return "task" if holder and info.get("jobs_in_flight", 0) == 1 else "tasks"


def journal_count(out_dir: Path) -> int:
    """The journal's entries, by name (journal/<kk>/<key>.json, kk = key[:2]; not verified:
    journal_lines reports those that fail); stray files are not counted. Creates nothing."""
    journal = out_dir / JOURNAL_DIR
    if not journal.is_dir() or journal.is_symlink():
        return 0
    count = 0
    for shard in journal.iterdir():
        if len(shard.name) != 2 or shard.is_symlink() or not shard.is_dir():
            continue
        count += sum(
            1
            for entry in shard.glob("*.json")
            if KEY.fullmatch(entry.stem) and entry.stem[:2] == shard.name
        )
    return count


def _status_file(out_dir: Path) -> dict:
    """status.json, marked `written` (empty if missing or unreadable)."""
    status_file = out_dir / STATUS_FILE
    try:
        refuse_symlink(status_file)
        if not status_file.is_file():
            return {}
        info = json.loads(status_file.read_text())
        return {**info, "written": True} if isinstance(info, dict) else {}
    except ValueError:
        return {}


def _from_files(out_dir: Path, results_ok: bool) -> dict:
    """What status.json would say, read from campaign.yaml (name, points) and a valid
    results.nc (finished points; complete unless marked partial); {} where unreadable."""
    found: dict = {}
    try:
        campaign = load_campaign(out_dir / CAMPAIGN_FILE)
        found["campaign"] = campaign.name
        found["points_total"] = int(np.prod(campaign.shape, dtype=np.int64))
    except ConfigError:
        return found
    if results_ok:
        import xarray as xr

        with xr.open_dataset(out_dir / RESULTS_FILE) as results:
            partial = bool(results.attrs.get("partial"))
            done = results.attrs.get("points_done", found["points_total"])
            found["points_done"] = int(done) if partial else found["points_total"]
            if not partial:
                found["state"] = "complete"
    return found


def edit_lines(out_dir: Path) -> list[str]:
    """Lines saying that DIR/campaign.yaml was edited by hand (resume refuses it)."""
    try:
        differences = record_differences(out_dir, load_campaign(out_dir / CAMPAIGN_FILE))
    except ConfigError as exc:
        differences = [f"{out_dir / CAMPAIGN_FILE} no longer validates:", *exc.problems]
    if not differences:
        return []
    return [f"campaign:  resume will refuse: {differences[0]}"] + [
        f"  {line}" for line in differences[1:]
    ]


def journal_lines(out_dir: Path, shown: int = 10) -> list[str]:
    """Lines on journal entries that fail verification now, and those moved aside before."""
    failing, moved = audit(out_dir)
    lines = []
    if failing:
        lines.append(
            f"journal:   {len(failing)} entries fail verification and will not be used "
            "(resume moves each one it needs to journal/corrupt/ and recomputes it):"
        )
        lines += [f"  {line}" for line in failing[:shown]]
        lines += [f"  ... and {len(failing) - shown} more"] if len(failing) > shown else []
    if moved:
        lines.append(f"journal:   {len(moved)} entries were moved aside to journal/corrupt/:")
        lines += [f"  {line}" for line in moved[-shown:]]
    return lines


def results_lines(results_file: Path, complete: bool) -> list[str]:
    """What results.nc says: the answer of a complete campaign, or what a stopped or
    running campaign has found so far (its partial results.nc; [] if none), in its task's
    words."""
    import xarray as xr

    with xr.open_dataset(results_file) as results:
        if complete:
            head = f"results:   {results_file}"
        elif results.attrs.get("partial"):
            head = (
                f"results:   {results_file} (partial: {results.attrs.get('points_done')} of "
                f"{results.attrs.get('points_total')} points finished)"
            )
        else:
            return []
        entry = TASKS.get(results.attrs.get("task"))
        return [head, *(entry.status_lines(results, complete) if entry else [])]


def answer_lines(results_path: Path) -> list[str]:
    """What a finished `run` or `resume` prints under a campaign, read from its results.nc
    once: its task's answer (a find_jump's mu* table, a scan's outcome per point, a basin's
    fractions...); [] without a readable results.nc."""
    import xarray as xr

    if results_path.name != RESULTS_FILE or not results_path.is_file():
        return []
    with xr.open_dataset(results_path) as results:
        entry = TASKS.get(results.attrs.get("task"))
        return entry.run_lines(results) if entry else []
