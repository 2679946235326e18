"""Campaign commands: `run`, `resume`, `status` (thin; the work is in runner.py).

Exit codes: 0 done, 2 bad campaign file or a different campaign in DIR, 3 DIR is in use
by another run, 130 interrupted (Ctrl-C; resume continues).
"""

from __future__ import annotations

import json
import time
from pathlib import Path

import click

from frictiondisk.cli_options import fail

EXIT_LOCKED = 3
EXIT_INTERRUPTED = 130


def _execute(campaign, out_dir: Path, workers: int, scheduler: str | None, processes: bool):
    from frictiondisk.campaign.journal import CampaignLocked
    from frictiondisk.campaign.runner import CampaignChanged, CampaignInterrupted, run_campaign
    from frictiondisk.config import ConfigError

    try:
        summary = run_campaign(campaign, out_dir, workers, scheduler, processes)
    except CampaignChanged as exc:
        fail(f"{out_dir}: the campaign differs from the one this directory holds", exc.differences)
    except CampaignLocked as exc:
        fail(str(exc), [], EXIT_LOCKED)
    except CampaignInterrupted as exc:
        fail(str(exc), [], EXIT_INTERRUPTED)
    except ConfigError as exc:
        fail(f"{out_dir}/campaign.yaml", list(exc.problems))
    except FileNotFoundError as exc:
        fail(str(exc), [])
    click.echo(
        f"done: {summary.points} points ({summary.points_failed} failed), "
        f"{summary.runs_total} runs used, {summary.runs_computed} computed now, "
        f"{summary.runs_saved_by_warm_start} saved by warm starts, {summary.wall_s:.1f} s"
    )
    click.echo(f"results: {summary.results}")
    label = "trajectory:" if summary.runs.name == "trajectory.nc" else "runs:   "
    click.echo(f"{label} {summary.runs}")


_workers = click.option(
    "--workers",
    type=click.IntRange(1, 256),
    default=2,
    show_default=True,
    help="Local Dask workers (ignored with --scheduler).",
)
_scheduler = click.option(
    "--scheduler",
    metavar="ADDRESS",
    default=None,
    help="Use an existing Dask scheduler (e.g. tcp://host:8786) instead of a local cluster.",
)
_processes = click.option(
    "--processes/--threads",
    default=False,
    show_default=True,
    help="Local workers as processes or as threads (the kernel releases the GIL).",
)


@click.command()
@click.argument("campaign_file", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--out",
    "out_dir",
    type=click.Path(file_okay=False, path_type=Path),
    required=True,
    help="Campaign directory (journal, results.nc, runs.nc).",
)
@_workers
@_scheduler
@_processes
def run(campaign_file: Path, out_dir: Path, workers: int, scheduler, processes: bool) -> None:
    """Run CAMPAIGN_FILE into DIR; running it again on the same DIR resumes it."""
    from frictiondisk.campaign.spec import load_campaign
    from frictiondisk.config import ConfigError

    if not campaign_file.is_file():
        fail(str(campaign_file), [f"campaign file not found: {campaign_file}"])
    try:
        campaign = load_campaign(campaign_file)
    except ConfigError as exc:
        fail(str(campaign_file), list(exc.problems))
    _execute(campaign, out_dir, workers, scheduler, processes)


@click.command()
@click.argument("out_dir", type=click.Path(file_okay=False, path_type=Path))
@_workers
@_scheduler
@_processes
def resume(out_dir: Path, workers: int, scheduler, processes: bool) -> None:
    """Continue the campaign in DIR from its journal (no finished run is computed again)."""
    _execute(None, out_dir, workers, scheduler, processes)


@click.command()
@click.argument("out_dir", type=click.Path(file_okay=False, path_type=Path))
def status(out_dir: Path) -> None:
    """Report progress of the campaign in DIR: points, runs, failures, time left."""
    from frictiondisk.campaign.journal import CampaignLock, Journal
    from frictiondisk.campaign.runner import CAMPAIGN_FILE, RESULTS_FILE, STATUS_FILE
    from frictiondisk.files import netcdf_is_valid

    if not (out_dir / CAMPAIGN_FILE).is_file():
        fail(f"{out_dir} is not a campaign directory (no {CAMPAIGN_FILE})", [])
    info = {}
    status_file = out_dir / STATUS_FILE
    if status_file.is_file():
        try:
            info = json.loads(status_file.read_text())
        except ValueError:
            info = {}
    holder = CampaignLock.holder(out_dir)
    # a trajectory campaign keeps no journal: its one run is counted in status.json
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
    if state == "complete":
        lines.append(f"results:   {out_dir / RESULTS_FILE}")
    elif state == "damaged":
        lines.append(f"results.nc is missing or damaged; rebuild it: frictiondisk resume {out_dir}")
    elif state in ("interrupted", "not started"):
        lines.append(f"continue with: frictiondisk resume {out_dir}")
    click.echo("\n".join(lines))
