"""Run a campaign: replay the journal, compute what is missing on Dask, write results.

The driver is the only writer of DIR. It holds DIR/lock for the whole run, commits every
finished run to the journal at once, and replays the planner from the journal first, so
an interrupted campaign resumes without computing a finished run again and loses at most
the runs that were in flight.

DIR layout: campaign.yaml (the campaign as first run), campaign.record.json (its sha256
and canonical form: a hand-edited campaign.yaml is refused), journal/ (one file per run),
status.json (progress, rewritten while running), results.nc, runs.nc, lock. None of these
may be a symbolic link (issue 14): the driver refuses to start rather than follow one.

This module runs a campaign (run_campaign); the work is in directory.py (DIR),
driver.py (the campaign loop), cluster.py (Dask) and signals.py (Ctrl-C and SIGTERM).
"""

from __future__ import annotations

import contextlib
import time
from pathlib import Path

from frictiondisk.engine.cluster import WORKER_WAIT, SchedulerFailed
from frictiondisk.engine.directory import (
    RESULTS_FILE,
    prepare_directory,
    refuse_links,
    write_status,
)
from frictiondisk.engine.driver import RunSummary, _Driver
from frictiondisk.engine.signals import (
    CampaignInterrupted,
    _stop_requested,
    describe_stop,
    wait_interruptibly,
)
from frictiondisk.model.campaign import Campaign
from frictiondisk.store.journal import Journal
from frictiondisk.store.lock import CampaignLock


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
    out_dir.mkdir(parents=True, exist_ok=True)
    refuse_links(out_dir)
    _stop_requested.clear()
    with CampaignLock(out_dir):
        campaign = prepare_directory(out_dir, campaign)
        if campaign.kind == "trajectory":
            return _run_trajectory(campaign, out_dir)
        Journal(out_dir).clean_temp_files()  # left by a put that was killed mid-write
        driver = _Driver(campaign, out_dir, progress)
        driver.worker_wait = worker_wait
        driver.serve_dashboard = dashboard
        try:
            return driver.run(workers, scheduler, processes)
        except (SchedulerFailed, OSError):
            with contextlib.suppress(OSError):  # a full disk may refuse this too
                driver.interrupted()
            raise
        except KeyboardInterrupt as stop:
            _stop_requested.clear()
            driver.interrupted()
            what, code = describe_stop(stop)
            written = driver.write_partial()
            if written is None:
                results = ""
            elif written:
                results = f", the {written} finished points in {RESULTS_FILE} (partial)"
            else:
                results = f"; no point is finished yet ({RESULTS_FILE}: every point pending)"
            raise CampaignInterrupted(
                f"{what}; {driver.runs_done()} finished runs are in the journal{results}. "
                f"Continue with: frictiondisk resume {out_dir}",
                code,
            ) from None
        finally:
            driver.journal.close()


def _run_trajectory(campaign: Campaign, out_dir: Path) -> RunSummary:
    """A trajectory campaign: one recorded run in this process (no Dask, no journal)."""
    from frictiondisk.engine.orbit import run_trajectory

    t0 = time.perf_counter()
    done = wait_interruptibly(run_trajectory, campaign, out_dir, RESULTS_FILE)
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
        runs_computed_now=done["computed"],
        elapsed_s=wall,
        eta_s=None,
    )
    return RunSummary(
        points=1,
        points_failed=0,
        runs_total=1,
        runs_computed=done["computed"],
        runs_saved_by_warm_start=0,
        wall_s=wall,
        results=Path(done["results"]),
        runs=Path(done["trajectory"]),
    )
