"""The campaign loop (Driver): replay the journals, submit the missing runs of one or more
campaigns to one Dask client, journal each finished run, rewrite status.json and the
partial results.nc, drain the tasks in flight on a stop, and write each campaign's
results.nc and runs.nc as soon as its last point is done.

Several campaigns share the workers (`run A.yaml B.yaml`): each round offers the free
task slots to the campaigns in the order given, so a campaign's tail, when its few last
points cannot keep every worker busy, overlaps the next campaign's start. Which runs a
campaign makes never depends on this: its planner alone decides (tasks/protocol.py)."""

from __future__ import annotations

import concurrent.futures
import sys
import time
import uuid
from typing import Any

from frictiondisk.engine.campaign_run import CampaignRun, RunSummary, on_stderr
from frictiondisk.engine.cluster import (
    WORKER_WAIT,
    SchedulerFailed,
    dashboard_link,
    measure_task_overhead,
    start_client,
    task_sizing,
)
from frictiondisk.engine.signals import drop_hint, raise_if_stop_requested, stops_noted_only
from frictiondisk.engine.worker import Sealed, run_job, run_sealed, warm_up
from frictiondisk.tasks.jobs import RunScenes

STATUS_EVERY = 0.5  # [s] between status.json rewrites
PARTIAL_EVERY = 30.0  # [s] between partial results.nc rewrites of a running campaign
# ... and at least this many times the last rewrite's own time: a checkpoint of a large
# campaign (seconds on a busy machine) stays a small share of the driver's time
PARTIAL_COST_FACTOR = 20.0
BAR_EVERY = 0.2  # [s] between progress-bar repaints
MAX_WORKER_FAILURES = 3  # resubmissions of a run whose worker died
POLL = 5.0  # [s] between checks for live workers while waiting on --scheduler
DRAIN_TIMEOUT_S = 30.0  # [s] Ctrl-C waits this long for the tasks in flight, then drops them


class Driver:
    """One run or resume of one or more campaigns on one Dask client (holds no lock)."""

    def __init__(self, runs: list[CampaignRun], progress: bool):
        self.runs = runs
        self.progress = progress
        self._task_prefix = uuid.uuid4().hex[:12]  # Dask keys: unique on a shared scheduler
        self._submitted = 0
        # future key -> (campaign, job id, job, future)
        self.in_flight: dict[str, tuple[CampaignRun, Any, Any, Any]] = {}
        self.failures: dict[tuple[int, Any], int] = {}  # (campaign index, job) -> failures
        self.t0 = time.perf_counter()
        self._last_status = 0.0
        self._last_partial = time.perf_counter()  # the first partial file after PARTIAL_EVERY
        self._partial_every = PARTIAL_EVERY
        self._last_bar = 0.0
        self._bar = None
        self.scheduled = False  # True with --scheduler: watch for live workers
        self.worker_wait = WORKER_WAIT
        self.task_overhead_s: float | None = None  # measured round trip of an empty task
        self.worker_threads = 1
        self._draining = False
        self.dashboard: str | None = None
        self.serve_dashboard = False  # serve the local cluster's Dask dashboard
        # Where a finished job is taken and journaled (_collect): a stop is raised in the
        # main thread only, so it cannot land between the planner taking a job and the
        # journal holding its runs (a batch's runs would be lost to a graceful stop).
        self._journaling: concurrent.futures.ThreadPoolExecutor | None = None

    # ---- the loop -----------------------------------------------------------------------
    def run(self, workers: int, scheduler: str | None, processes: bool) -> list[RunSummary]:
        """Every campaign's summary, in the order given."""
        for run in self.runs:
            run.replay()
        if any(not run.planner.done for run in self.runs):
            self._compute(workers, scheduler, processes)
        for run in self.runs:
            if run.summary is None:
                self._finish(run)
        return [run.summary for run in self.runs]

    def _compute(self, workers: int, scheduler: str | None, processes: bool) -> None:
        warm_up()  # compile once here, so workers load the cache instead of racing on it
        client, cluster = start_client(workers, scheduler, processes, self.serve_dashboard)
        self._journaling = concurrent.futures.ThreadPoolExecutor(1, "frictiondisk-journal")
        if scheduler:
            self.scheduled = True
        try:  # from here on the client (and a local cluster) is always closed
            if self.serve_dashboard or self.scheduled:
                self.dashboard = dashboard_link(client)
                on_stderr(print, f"Dask dashboard: {self.dashboard}", file=sys.stderr)
            if self.scheduled:
                self._await_a_worker(client)  # the overhead probe below needs one
            self.worker_threads = max(1, sum(client.nthreads().values()))
            self.task_overhead_s = measure_task_overhead(client)
            self._open_bar()
            try:
                self._loop(client)
            except KeyboardInterrupt as stop:
                self._drain(client, stop)
                raise
        finally:
            with stops_noted_only():  # a stop raised inside Dask's close can hang it
                self._journaling.shutdown(wait=True)  # a job being journaled finishes first
                for *_, future in self.in_flight.values():
                    future.cancel()
                client.close()
                if cluster is not None:
                    cluster.close()
            if self._bar is not None:
                self._bar.n, self._bar.total = self._progress()
                self._bar.set_postfix(runs=self.runs_done(), in_flight=0, refresh=False)
                on_stderr(self._bar.close)

    def _loop(self, client) -> None:
        from distributed import as_completed

        # Results come back gathered, in batches: no blocking round trip per future.
        self._done_queue = as_completed(with_results=True, raise_errors=False)
        while True:
            for run in self.runs:
                if run.summary is not None:
                    continue
                if run.changed:
                    run.replay()
                if not run.planner.done:
                    for job_id, job in run.planner.jobs(self._sizing(run)):
                        self._submit(client, run, job_id, job)
                if run.planner.done:
                    self._finish(run)
            if all(run.summary is not None for run in self.runs):
                break
            if not self.in_flight:
                raise RuntimeError("campaign stalled: no job in flight and none to submit")
            if self.scheduled:
                self._wait_with_workers(client)
            for future, value in self._done_queue.next_batch(block=True):
                self._collect(client, future, value)
            self._tick()
            raise_if_stop_requested()

    def _wait_with_workers(self, client) -> None:
        """Wait for a job to finish on --scheduler, checking every POLL seconds that some
        worker is alive: warn at once when none is, raise SchedulerFailed after
        `worker_wait` seconds without one."""
        from distributed import wait

        futures = [entry[-1] for entry in self.in_flight.values()]
        alone_since = None
        while True:
            try:
                wait(futures, timeout=POLL, return_when="FIRST_COMPLETED")
                return
            except TimeoutError:
                pass
            alone_since = no_worker_since(client, alone_since, self.worker_wait)

    def _await_a_worker(self, client) -> None:
        """Return once some worker is alive at --scheduler (same warning and limit)."""
        alone_since = no_worker_since(client, None, self.worker_wait)
        while alone_since is not None:
            time.sleep(min(POLL, self.worker_wait))
            alone_since = no_worker_since(client, alone_since, self.worker_wait)

    def _submit(self, client, run: CampaignRun, job_id, job) -> None:
        """Hand one job of `run`'s planner to Dask (engine/worker.py executes it)."""
        # our own unique key: Dask would draw a random one (pure=False) from os.urandom
        self._submitted += 1
        key = f"{type(job).__name__}-{self._task_prefix}-{self._submitted}"
        future = client.submit(run_sealed, Sealed(run_job, (job, run.dir_text)), key=key)
        self.in_flight[future.key] = (run, job_id, job, future)
        self._done_queue.add(future)

    def _sizing(self, run: CampaignRun):
        """How to cut `run`'s work now: its own mean run time, and the task slots the
        campaigns before it in this round left free."""
        return task_sizing(
            self.task_overhead_s or 0.0, run.mean_run_s(), self.worker_threads, len(self.in_flight)
        )

    def _drain(self, client, stop: KeyboardInterrupt) -> None:
        """After a stop (Ctrl-C, SIGTERM, SIGHUP): journal the runs of the tasks in flight as
        they finish (at most DRAIN_TIMEOUT_S; a second stop drops them), submitting nothing
        new."""
        self._draining = True
        try:  # the job a stop found being journaled: the journaling thread's queue is FIFO
            self._journaling.submit(time.monotonic).result()
        except KeyboardInterrupt:
            return
        if not self.in_flight:
            return
        on_stderr(
            print,
            f"\nstopping: journaling the runs of {len(self.in_flight)} tasks in flight, for at "
            f"most {DRAIN_TIMEOUT_S:.0f} s ({drop_hint(stop)})",
            file=sys.stderr,
        )
        deadline = time.monotonic() + DRAIN_TIMEOUT_S
        try:
            while self.in_flight and time.monotonic() < deadline:
                for *_, future in list(self.in_flight.values()):
                    if future.status in ("finished", "error", "cancelled", "lost"):
                        value = future.result() if future.status == "finished" else None
                        self._collect(client, future, value)
                time.sleep(0.01)
        except KeyboardInterrupt:
            pass

    def _collect(self, client, future, value) -> None:
        """Take a finished job (or a failed one) in the journaling thread and wait for it."""
        self._journaling.submit(self._take, client, future, value).result()

    def _take(self, client, future, value) -> None:
        run, job_id, job, _ = self.in_flight.pop(future.key)
        if future.status != "finished" and self._draining:
            return  # not journaled: a resume computes it
        failure = (self.runs.index(run), job_id)
        parts = failed_halves(run, job_id, job) if future.status != "finished" else None
        if parts:
            self.failures.pop(failure, None)
            for part_id, part in parts:
                self._submit(client, run, part_id, part)
            return
        if future.status != "finished":  # a worker died or the job raised: bounded retries
            self.failures[failure] = self.failures.get(failure, 0) + 1
            if self.failures[failure] <= MAX_WORKER_FAILURES:
                self._submit(client, run, job_id, job)
                return
            error = value[1] if isinstance(value, tuple) and len(value) == 3 else value
            # nothing journaled for it: a resume tries the point again
            run.fail(job_id, f"worker failed {self.failures[failure]} times: {error!r}")
            return
        self.failures.pop(failure, None)
        run.complete(job_id, value, batch=isinstance(job, RunScenes))

    def _finish(self, run: CampaignRun) -> None:
        run.finish(time.perf_counter() - self.t0, self.task_overhead_s)

    # ---- progress and status ------------------------------------------------------------
    def _open_bar(self) -> None:
        if not self.progress:
            return
        from frictiondisk.engine.progress import progress_bar

        label = self.runs[0].campaign.name if len(self.runs) == 1 else f"{len(self.runs)} campaigns"
        done, total = self._progress()
        self._bar = on_stderr(progress_bar, total, label, "point", initial=done)

    def interrupted(self) -> None:
        """After a stop: a campaign whose last point came back meanwhile writes its final
        files; every other unfinished one's status says `interrupted`."""
        for run in self.runs:
            if run.summary is None and run.planner.done:
                self._finish(run)
            elif run.summary is None:
                self._write_status(run, "interrupted")

    def write_partial(self) -> dict[str, int]:
        """The partial results.nc of every unfinished campaign: {campaign name: finished
        points written (0: every point pending)} for those that got one (never raises)."""
        written = {}
        for run in self.runs:
            if run.summary is None:
                points = run.write_partial()
                if points is not None:
                    written[run.campaign.name] = points
        return written

    def runs_done(self) -> int:
        return sum(run.runs_done() for run in self.runs)

    def runs_journaled(self) -> int:
        """Entries in the campaigns' journals, counted on disk: what a stop leaves (the
        stop's exception can land between a run's journal entry and the count of runs
        made, so runs_done may be one short)."""
        return sum(
            len(run.journal) if run.journal is not None else run.runs_done() for run in self.runs
        )

    def _progress(self) -> tuple[int, int]:
        """(done, total) over every campaign, each in its planner's unit (engine/campaign_run.py)."""
        done, total = zip(*(run.progress() for run in self.runs), strict=True)
        return sum(done), sum(total)

    def _write_status(self, run: CampaignRun, state: str) -> None:
        in_flight = sum(1 for entry in self.in_flight.values() if entry[0] is run)
        run.write_status(state, time.perf_counter() - self.t0, in_flight)

    def _tick(self) -> None:
        now = time.perf_counter()
        if self._bar is not None and now - self._last_bar >= BAR_EVERY:
            self._last_bar = now
            self._bar.n, self._bar.total = self._progress()
            self._bar.set_postfix(
                runs=self.runs_done(), in_flight=len(self.in_flight), refresh=False
            )
            on_stderr(self._bar.refresh)
        if now - self._last_status >= STATUS_EVERY:
            for run in self.runs:
                if run.summary is None:
                    self._write_status(run, "running")
            self._last_status = now
        if now - self._last_partial >= self._partial_every:
            self.write_partial()
            self._last_partial = time.perf_counter()
            cost = self._last_partial - now
            self._partial_every = max(PARTIAL_EVERY, PARTIAL_COST_FACTOR * cost)


def no_worker_since(client, alone_since: float | None, worker_wait: float) -> float | None:
    """None if a worker is alive; else since when none is [monotonic s]: warns at the
    start and raises SchedulerFailed after `worker_wait` [s]."""
    if client.scheduler_info().get("workers"):
        return None
    now = time.monotonic()
    if alone_since is None:
        on_stderr(
            print,
            f"warning: no worker is alive at the scheduler; waiting up to "
            f"{worker_wait:g} s for one (--worker-wait)",
            file=sys.stderr,
        )
        return now
    if now - alone_since >= worker_wait:
        raise SchedulerFailed(
            f"no worker alive at the scheduler for {worker_wait:g} s; "
            "start workers and resume (the journal keeps every finished run)"
        )
    return alone_since


def failed_halves(run: CampaignRun, job_id, job) -> list | None:
    """A failed batch of several runs as the jobs of its halves (the planner's `split`),
    so that a run whose worker keeps failing ends up alone and fails alone, after at most
    log2(runs) more rounds; None: not a batch, or a planner that retries it whole."""
    if not isinstance(job, RunScenes) or len(job.scenes) < 2:
        return None
    return run.planner.split(job_id, job)
