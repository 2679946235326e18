"""What `frictiondisk status` and the end of `run` / `resume` report of a campaign
directory, as lines of text (the CLI prints them): its state (running, interrupted,
complete, damaged), progress, the journal's health, a hand edit of its campaign.yaml, and
the answer so far, which its task's entry writes (TaskEntry.status_lines, run_lines)."""

from __future__ import annotations

import json
import time
from pathlib import Path

from frictiondisk.engine.directory import record_differences
from frictiondisk.model.scene import ConfigError
from frictiondisk.store.files import netcdf_is_valid
from frictiondisk.store.journal import Journal
from frictiondisk.store.journal_audit import audit
from frictiondisk.store.layout import CAMPAIGN_FILE, RESULTS_FILE, STATUS_FILE
from frictiondisk.store.lock import CampaignLock
from frictiondisk.store.paths import refuse_symlink
from frictiondisk.tasks.campaign import load_campaign
from frictiondisk.tasks.registry import TASKS


class NotACampaign(Exception):
    """A directory that holds no campaign (no campaign.yaml)."""


def status_lines(out_dir: Path) -> list[str]:
    """The progress of the campaign in out_dir (NotACampaign if it holds none; OSError if
    its status cannot be read)."""
    if not (out_dir / CAMPAIGN_FILE).is_file():
        raise NotACampaign(f"{out_dir} is not a campaign directory (no {CAMPAIGN_FILE})")
    info, holder = _status_file(out_dir)
    # a task without a journal (a trajectory) counts its run in status.json
    runs_done = Journal.count(out_dir) or int(info.get("runs_done", 0))
    state = info.get("state", "not started")
    if holder is not None:
        state = f"running (pid {holder})"
    elif state == "running":
        state = "interrupted"
    results_ok = netcdf_is_valid(out_dir / RESULTS_FILE)
    if state == "complete" and not results_ok:
        state = "damaged"
    total = info.get("points_total", "?")
    lines = [
        f"campaign:  {info.get('campaign', '?')} in {out_dir}",
        f"state:     {state}",
        f"points:    {info.get('points_done', 0)} of {total} done, "
        f"{info.get('points_failed', 0)} failed",
        f"runs:      {runs_done} done; "
        f"{info.get('jobs_in_flight', 0) if holder else 0} tasks in flight",
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


def _status_file(out_dir: Path) -> tuple[dict, int | None]:
    """status.json (empty if missing or unreadable) and the pid holding the lock (None)."""
    status_file = out_dir / STATUS_FILE
    try:
        refuse_symlink(status_file)
        info = json.loads(status_file.read_text()) if status_file.is_file() else {}
        return info, CampaignLock.holder(out_dir)
    except ValueError:
        return {}, CampaignLock.holder(out_dir)


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
