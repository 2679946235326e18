"""Run campaigns: replay the journal, compute what is missing on Dask, write results.

The driver is the only writer of DIR. It holds DIR/lock for the whole run, commits every
finished run to the journal at once, and replays the planner from the journal first, so
an interrupted campaign resumes without computing a finished run again and loses at most
the runs that were in flight.

DIR layout: campaign.yaml (the campaign as first run), campaign.record.json (its sha256
and canonical form: a hand-edited campaign.yaml is refused), journal/ (one file per run),
status.json (progress, rewritten while running), results.nc, runs.nc, lock. None of these
may be a symbolic link: the driver refuses to start rather than follow one.

Several campaigns in one process (run_campaigns): DIR/campaigns.json names them, each
campaign has a DIR/<name>/ of the layout above, with its own lock, and DIR/lock is held
too. Their runs share one Dask client and one driver loop (engine/driver.py).

This module runs campaigns (run_campaign, run_campaigns); the work is in directory.py
(DIR), driver.py (the loop), campaign_run.py (one campaign in it), cluster.py (Dask) and
signals.py (Ctrl-C, SIGTERM and SIGHUP).
"""

from __future__ import annotations

import contextlib
import time
from collections import Counter
from pathlib import Path

from frictiondisk.engine.campaign_run import CampaignRun, RunSummary
from frictiondisk.engine.cluster import WORKER_WAIT, SchedulerFailed
from frictiondisk.engine.directory import (
    is_campaign_folder,
    prepare_directory,
    read_manifest,
    refuse_links,
    write_manifest,
    write_status,
)
from frictiondisk.engine.driver import Driver
from frictiondisk.engine.signals import (
    CampaignInterrupted,
    clear_stop_requests,
    describe_stop,
    wait_interruptibly,
)
from frictiondisk.store.journal import Journal
from frictiondisk.store.layout import CAMPAIGN_FILE, RESULTS_FILE
from frictiondisk.store.lock import CampaignLock
from frictiondisk.store.paths import refuse_symlink
from frictiondisk.tasks.campaign import Campaign


class CampaignsClash(ValueError):
    """Campaigns that cannot run together into one folder (the same name twice, or a
    folder that holds a single campaign); `problems` names each."""

    def __init__(self, problems: list[str]):
        super().__init__("; ".join(problems))
        self.problems = problems


def run_campaign(
    campaign: Campaign | None,
    out_dir: Path,
    workers: int = 2,
    scheduler: str | None = None,
    processes: bool = False,
    progress: bool = True,
    worker_wait: float = WORKER_WAIT,
    dashboard: bool = False,
) -> RunSummary:
    """Run (or resume, with campaign=None) the campaign in out_dir.

    worker_wait: with `scheduler`, how long [s] to wait for a live worker before giving up
    (SchedulerFailed); a warning goes to stderr as soon as none is alive. dashboard: serve
    the Dask dashboard of the local cluster (bokeh; its address goes to stderr); off by
    default, since starting it costs about 0.35 s of imports. A --scheduler's own
    dashboard is named either way."""
    out_dir = Path(out_dir)
    if is_campaign_folder(out_dir):
        raise CampaignsClash(
            [
                f"{out_dir} holds several campaigns (campaigns.json): run one of them into "
                "its own folder, <folder>/<name>/, or several files into the folder"
            ]
        )
    out_dir.mkdir(parents=True, exist_ok=True)
    refuse_links(out_dir)
    clear_stop_requests()
    with CampaignLock(out_dir):
        campaign = prepare_directory(out_dir, campaign)
        if campaign.entry.runs_alone:
            return _run_alone(campaign, out_dir)
        run = _open(campaign, out_dir)
        driver = Driver([run], progress)
        return _drive(driver, out_dir, workers, scheduler, processes, worker_wait, dashboard)[0]


def run_campaigns(
    campaigns: list[Campaign] | None,
    out_dir: Path,
    workers: int = 2,
    scheduler: str | None = None,
    processes: bool = False,
    progress: bool = True,
    worker_wait: float = WORKER_WAIT,
    dashboard: bool = False,
) -> list[RunSummary]:
    """Run (or resume) several campaigns in this process, each into out_dir/<its name>/,
    their runs scheduled together on one Dask client (options as run_campaign).

    campaigns=None resumes every campaign out_dir/campaigns.json names. Given campaigns
    are added to that list; each one already in its folder must be the same campaign
    (CampaignChanged, before anything is written). CampaignsClash: two campaigns of the
    same name, or an out_dir that holds a single campaign. Returns their summaries in the
    order given (for a resume: the order of campaigns.json)."""
    out_dir = Path(out_dir)
    _refuse_clashes(campaigns, out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    refuse_links(out_dir)
    clear_stop_requests()
    with CampaignLock(out_dir), contextlib.ExitStack() as locks:
        if campaigns is None:
            named = [(name, None) for name in read_manifest(out_dir)]
        else:
            named = [(campaign.name, campaign) for campaign in campaigns]
        folders = [refuse_symlink(out_dir / name) for name, _ in named]
        for folder in folders:
            folder.mkdir(exist_ok=True)
            refuse_links(folder)
            locks.enter_context(CampaignLock(folder))
        # every campaign already in its folder is checked before a new one is written
        order = sorted(range(len(named)), key=lambda k: not (folders[k] / CAMPAIGN_FILE).exists())
        prepared: dict[int, Campaign] = {}
        for k in order:
            prepared[k] = prepare_directory(folders[k], named[k][1])
        write_manifest(out_dir, [name for name, _ in named])
        runs = [_open(prepared[k], folders[k]) for k in range(len(named))]
        driver = Driver(runs, progress)
        return _drive(driver, out_dir, workers, scheduler, processes, worker_wait, dashboard)


def _refuse_clashes(campaigns: list[Campaign] | None, out_dir: Path) -> None:
    problems = []
    if (out_dir / CAMPAIGN_FILE).exists():
        problems.append(
            f"{out_dir} holds a single campaign ({CAMPAIGN_FILE}); several campaigns go "
            "into a folder of their own, each into <folder>/<name>/"
        )
    if campaigns is not None:
        counts = Counter(campaign.name for campaign in campaigns)
        problems += [
            f"name: {name!r} is the name of {count} of the campaigns; each campaign of one "
            "run needs a name of its own (it names its folder)"
            for name, count in counts.items()
            if count > 1
        ]
    elif not is_campaign_folder(out_dir):
        problems.append(f"{out_dir} is not a folder of campaigns (no campaigns.json)")
    if problems:
        raise CampaignsClash(problems)


def _open(campaign: Campaign, out_dir: Path) -> CampaignRun:
    if campaign.entry.journaled:
        Journal(out_dir).clean_temp_files()  # left by a put that was killed mid-write
    return CampaignRun(campaign, out_dir)


def _drive(
    driver: Driver,
    out_dir: Path,
    workers: int,
    scheduler: str | None,
    processes: bool,
    worker_wait: float,
    dashboard: bool,
) -> list[RunSummary]:
    """driver.run, turning a stop into CampaignInterrupted once every campaign's finished
    runs are journaled and its partial results written."""
    driver.worker_wait = worker_wait
    driver.serve_dashboard = dashboard
    try:
        return driver.run(workers, scheduler, processes)
    except (SchedulerFailed, OSError):
        with contextlib.suppress(OSError):  # a full disk may refuse this too
            driver.interrupted()
        raise
    except KeyboardInterrupt as stop:
        clear_stop_requests()
        driver.interrupted()
        what, code = describe_stop(stop)
        written = driver.write_partial()
        journals = (
            "journal" if len(driver.runs) == 1 else f"journals of the {len(driver.runs)} campaigns"
        )
        raise CampaignInterrupted(
            f"{what}; {driver.runs_journaled()} finished runs are in the {journals}"
            + _partial_note(written, len(driver.runs))
            + f". Continue with: frictiondisk resume {out_dir}",
            code,
        ) from None
    finally:
        for run in driver.runs:
            if run.journal is not None:
                run.journal.close()


def _partial_note(written: dict[str, int], campaigns: int) -> str:
    """Where the finished points of a stopped run are (their partial results.nc, written
    also before the first point is finished: every point pending)."""
    if not written:
        return ""
    finished = sum(written.values())
    where = RESULTS_FILE if campaigns == 1 else f"each campaign's {RESULTS_FILE}"
    if finished == 0:
        return f"; no point is finished yet ({where}: every point pending)"
    if campaigns == 1:
        return f", the {finished} finished points in {RESULTS_FILE} (partial)"
    each = ", ".join(f"{name} {points}" for name, points in written.items())
    return f", the finished points in {where} (partial: {each})"


def _run_alone(campaign: Campaign, out_dir: Path) -> RunSummary:
    """A campaign whose task runs alone in this process (a trajectory: one recorded run; no
    Dask, no journal): its entry runs it and writes its files."""
    t0 = time.perf_counter()
    computed, runs = wait_interruptibly(campaign.entry.run_alone, campaign, out_dir)
    wall = time.perf_counter() - t0
    write_status(
        out_dir,
        "complete",
        campaign,
        points_total=1,
        points_done=1,
        points_failed=0,
        runs_done=1,
        jobs_in_flight=0,
        runs_computed_now=computed,
        elapsed_s=wall,
        eta_s=None,
    )
    return RunSummary(
        points=1,
        points_failed=0,
        runs_total=1,
        runs_computed=computed,
        runs_saved_by_warm_start=0,
        wall_s=wall,
        results=out_dir / RESULTS_FILE,
        runs=Path(runs),
    )
