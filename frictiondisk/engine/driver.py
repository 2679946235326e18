"""The campaign loop (_Driver): replay the journal, submit the missing runs to Dask,
journal each finished run, rewrite status.json and the partial results.nc, drain the tasks
in flight on a stop, and write results.nc and runs.nc at the end."""

from __future__ import annotations

import dataclasses
import sys
import time
import uuid
from pathlib import Path
from typing import Any

from frictiondisk.engine.cluster import (
    WORKER_WAIT,
    SchedulerFailed,
    dashboard_link,
    measure_task_overhead,
    start_client,
    task_sizing,
)
from frictiondisk.engine.directory import RESULTS_FILE, RUNS_FILE, write_status
from frictiondisk.engine.plan import Sizing, planner_for
from frictiondisk.engine.signals import _raise_if_stop_requested, drop_hint
from frictiondisk.engine.tasks import Sealed, run_sealed, warm_up
from frictiondisk.model.campaign import Campaign
from frictiondisk.store import basin_datasets, datasets, trace_datasets
from frictiondisk.store.files import atomic_write_netcdf
from frictiondisk.store.journal import Journal, run_key
from frictiondisk.store.partial import with_pending

STATUS_EVERY = 0.5  # [s] between status.json rewrites
PARTIAL_EVERY = 30.0  # [s] between partial results.nc rewrites of a running campaign
BAR_EVERY = 0.2  # [s] between progress-bar repaints
MAX_WORKER_FAILURES = 3  # resubmissions of a run whose worker died
POLL = 5.0  # [s] between checks for live workers while waiting on --scheduler
DRAIN_TIMEOUT_S = 30.0  # [s] Ctrl-C waits this long for the tasks in flight, then drops them


@dataclasses.dataclass
class RunSummary:
    points: int
    points_failed: int
    runs_total: int  # runs the planner used (journal hits + computed)
    runs_computed: int  # runs computed in this invocation
    runs_saved_by_warm_start: int
    wall_s: float
    results: Path
    runs: Path
    moved_aside: list[str] = dataclasses.field(default_factory=list)  # rejected entries
    task_overhead_s: float | None = None  # measured round trip of an empty Dask task [s]


class _Driver:
    """One run or resume of a campaign: replay, compute, write results (holds no lock)."""

    def __init__(self, campaign: Campaign, out_dir: Path, progress: bool):
        self.campaign = campaign
        self.out_dir = out_dir
        self.journal = Journal(out_dir)
        self.planner = planner_for(campaign)
        self.progress = progress
        self.keys: dict[tuple[int, Any], str] = {}  # (point, request) -> run key
        self.computed = 0
        # listed once: only this driver writes the journal (it holds the lock), so a key not
        # in this set is not looked up on disk (on slow file systems a failed open of each
        # new run's entry cost the driver about 1 ms)
        self._present: set[str] = set(self.journal.keys())
        self.runs_at_start = len(self._present)
        self._task_prefix = uuid.uuid4().hex[:12]  # Dask keys: unique on a shared scheduler
        self._submitted = 0
        self.in_flight: dict[str, tuple] = {}  # future key -> (job, function, args, future)
        self.inputs: dict[str, dict] = {}
        self.failures: dict[int, int] = {}  # job (point) -> failed attempts
        self.t0 = time.perf_counter()
        self._last_status = 0.0
        self._last_partial = time.perf_counter()  # the first partial file after PARTIAL_EVERY
        self._last_bar = 0.0
        self._bar = None
        self.scheduled = False  # True with --scheduler: watch for live workers
        self.worker_wait = WORKER_WAIT
        # keys looked up and absent; the journal only grows by our own put (which clears one)
        self._checked: set[str] = set()
        self.task_overhead_s: float | None = None  # measured round trip of an empty task
        self.worker_threads = 1
        self._run_s_sum = 0.0  # kernel wall time of the runs computed so far [s]
        self._draining = False
        self.dashboard: str | None = None
        self.serve_dashboard = False  # serve the local cluster's Dask dashboard

    # ---- the loop -----------------------------------------------------------------------
    def run(self, workers: int, scheduler: str | None, processes: bool) -> RunSummary:
        self._replay()
        if not self.planner.done:
            self._compute(workers, scheduler, processes)
        return self._finish()

    def _replay(self) -> None:
        """Feed every run the journal already holds (no Dask)."""
        progressed = True
        while progressed and not self.planner.done:
            progressed = False
            for point, request in self.planner.requests():
                key = self._key(point, request)
                if key in self._checked:
                    continue
                cached = self.journal.get(key) if key in self._present else None
                if cached is None:
                    self._present.discard(key)  # a bad entry was moved aside
                    self._checked.add(key)
                else:
                    self.planner.feed(point, request, cached)
                    progressed = True

    def _compute(self, workers: int, scheduler: str | None, processes: bool) -> None:
        warm_up()  # compile once here, so workers load the cache instead of racing on it
        client, cluster = start_client(workers, scheduler, processes, self.serve_dashboard)
        if scheduler:
            self.scheduled = True
        try:  # from here on the client (and a local cluster) is always closed
            if self.serve_dashboard or self.scheduled:
                self.dashboard = dashboard_link(client)
                _on_stderr(print, f"Dask dashboard: {self.dashboard}", file=sys.stderr)
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
            for *_, future in self.in_flight.values():
                future.cancel()
            client.close()
            if cluster is not None:
                cluster.close()
            if self._bar is not None:
                self._bar.n, self._bar.total = self._progress()
                self._bar.set_postfix(runs=self.runs_done(), in_flight=0, refresh=False)
                _on_stderr(self._bar.close)

    def _loop(self, client) -> None:
        from distributed import as_completed

        # Results come back gathered, in batches: no blocking round trip per future.
        self._done_queue = as_completed(with_results=True, raise_errors=False)
        campaign_dir = str(self.out_dir.resolve())
        while not self.planner.done:
            self._replay()
            for job, function, args in self.planner.jobs(campaign_dir, self._sizing()):
                self._submit(client, job, function, args)
            if self.planner.done:
                break
            if not self.in_flight:
                raise RuntimeError("campaign stalled: no job in flight and none to submit")
            if self.scheduled:
                self._wait_with_workers(client)
            for future, value in self._done_queue.next_batch(block=True):
                self._collect(client, future, value)
            self._tick()
            _raise_if_stop_requested()

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
            alone_since = self._no_worker_since(client, alone_since)

    def _await_a_worker(self, client) -> None:
        """Return once some worker is alive at --scheduler (same warning and limit)."""
        alone_since = self._no_worker_since(client, None)
        while alone_since is not None:
            time.sleep(min(POLL, self.worker_wait))
            alone_since = self._no_worker_since(client, alone_since)

    def _no_worker_since(self, client, alone_since: float | None) -> float | None:
        """None if a worker is alive; else since when none is [monotonic s]: warns at the
        start and raises SchedulerFailed after `worker_wait` seconds."""
        if client.scheduler_info().get("workers"):
            return None
        now = time.monotonic()
        if alone_since is None:
            _on_stderr(
                print,
                f"warning: no worker is alive at the scheduler; waiting up to "
                f"{self.worker_wait:g} s for one (--worker-wait)",
                file=sys.stderr,
            )
            return now
        if now - alone_since >= self.worker_wait:
            raise SchedulerFailed(
                f"no worker alive at the scheduler for {self.worker_wait:g} s; "
                "start workers and resume (the journal keeps every finished run)"
            )
        return alone_since

    def _submit(self, client, job: int, function, args: tuple) -> None:
        # our own unique key: Dask would draw a random one (pure=False) from os.urandom
        self._submitted += 1
        key = f"{function.__name__}-{self._task_prefix}-{self._submitted}"
        future = client.submit(run_sealed, Sealed(function, args), key=key)
        self.in_flight[future.key] = (job, function, args, future)
        self._done_queue.add(future)

    def _sizing(self) -> Sizing:
        mean_run = self._run_s_sum / self.computed if self.computed else None
        return task_sizing(
            self.task_overhead_s or 0.0, mean_run, self.worker_threads, len(self.in_flight)
        )

    def _drain(self, client, stop: KeyboardInterrupt) -> None:
        """After a stop (Ctrl-C, SIGTERM, SIGHUP): journal the runs of the tasks in flight as
        they finish (at most DRAIN_TIMEOUT_S; a second stop drops them), submitting nothing
        new."""
        if not self.in_flight:
            return
        self._draining = True
        _on_stderr(
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
        job, function, args, _ = self.in_flight.pop(future.key)
        if future.status != "finished" and self._draining:
            return  # not journaled: a resume computes it
        if future.status != "finished":  # a worker died or the job raised: bounded retries
            self.failures[job] = self.failures.get(job, 0) + 1
            if self.failures[job] <= MAX_WORKER_FAILURES:
                self._submit(client, job, function, args)
                return
            error = value[1] if isinstance(value, tuple) and len(value) == 3 else value
            # nothing journaled for it: a resume tries the point again
            self.planner.fail(job, f"worker failed {self.failures[job]} times: {error!r}")
            return
        self.failures.pop(job, None)
        for point, request, result in self.planner.complete(job, value):
            key = self._key(point, request)
            self.journal.put(key, self.inputs[key], result)
            self._present.add(key)
            self._checked.discard(key)  # another point may ask for the same run
            self.computed += 1
            self._run_s_sum += float(result.get("wall_s") or 0.0)

    def _key(self, point: int, request) -> str:
        cached = self.keys.get((point, request))
        if cached is None:
            canonical = self.planner.config_for(point, request).canonical()
            cached = run_key(_Canonical(canonical))  # canonical() once: it costs ~0.4 ms
            self.keys[(point, request)] = cached
            self.inputs[cached] = canonical
            remember = getattr(self.planner, "remember_canonical", None)
            if remember is not None:
                remember(point, request, canonical)
        return cached

    # ---- progress and status ------------------------------------------------------------
    def _open_bar(self) -> None:
        if not self.progress:
            return
        from frictiondisk.engine.progress import progress_bar

        self._bar = _on_stderr(
            progress_bar,
            self._points_total(),
            self.campaign.name,
            "point",
            initial=self._points_done(),
        )

    def interrupted(self) -> None:
        self._write_status(state="interrupted")

    def runs_done(self) -> int:
        return self.runs_at_start + self.computed

    def _points_done(self) -> int:
        return self._progress()[0]

    def _points_total(self) -> int:
        return self._progress()[1]

    def _progress(self) -> tuple[int, int]:
        """(done, total) in the planner's unit: points, or what its `progress()` counts
        (a trace: curve points placed; its total grows as curves are found)."""
        progress = getattr(self.planner, "progress", None)
        if progress is not None:
            return progress()
        return len(self.planner.results), len(self.planner.points)

    def _tick(self) -> None:
        now = time.perf_counter()
        if self._bar is not None and now - self._last_bar >= BAR_EVERY:
            self._last_bar = now
            self._bar.n, self._bar.total = self._progress()
            self._bar.set_postfix(
                runs=self.runs_done(), in_flight=len(self.in_flight), refresh=False
            )
            _on_stderr(self._bar.refresh)
        if now - self._last_status >= STATUS_EVERY:
            self._write_status(state="running")
            self._last_status = now
        if now - self._last_partial >= PARTIAL_EVERY:
            self._last_partial = now
            self.write_partial()

    def _datasets(self):
        """The module that builds this campaign's results.nc and runs.nc."""
        builders = {"basin": basin_datasets, "trace": trace_datasets}
        return builders.get(self.campaign.kind, datasets)

    def write_partial(self) -> int | None:
        """Write results.nc from the finished points, the rest pending, marked `partial`
        (frictiondisk.store.partial), also before the first point is finished; returns the
        finished points it holds (None: nothing written, as for a trajectory or a finished
        campaign). Never raises: a failure is reported on stderr, the journal keeps every
        run, and the final write of results.nc raises as usual."""
        done = self._points_done()
        if self.planner.done or self.campaign.kind == "trajectory":
            return None
        try:
            pending = with_pending(self.campaign.kind, self.planner)
            ds = self._datasets().results_dataset(self.campaign, pending)
            ds.attrs.update(partial=1, points_done=done, points_total=self._points_total())
            atomic_write_netcdf(ds, self.out_dir / RESULTS_FILE)
        except Exception as exc:  # noqa: BLE001  a side file: never stop the campaign for it
            _on_stderr(print, f"warning: partial results not written: {exc!r}", file=sys.stderr)
            return None
        return done

    def _write_status(self, state: str) -> None:
        done, total = self._progress()
        elapsed = time.perf_counter() - self.t0
        rate = done / elapsed if done and elapsed > 0 else 0.0
        write_status(
            self.out_dir,
            state,
            self.campaign,
            points_total=total,
            points_done=done,
            points_failed=self._points_failed(),
            runs_done=self.runs_done(),
            jobs_in_flight=len(self.in_flight),
            runs_computed_now=self.computed,
            elapsed_s=elapsed,
            eta_s=(total - done) / rate if rate > 0 else None,
        )

    def _points_failed(self) -> int:
        results = self.planner.results.values()
        return sum(1 for r in results if getattr(r, "status", "converged") == "failed")

    # ---- the end ------------------------------------------------------------------------
    def _finish(self) -> RunSummary:
        build = self._datasets()
        results_ds = build.results_dataset(self.campaign, self.planner)
        runs_ds = build.runs_dataset(self.campaign, self.planner, self._key)
        results = atomic_write_netcdf(results_ds, self.out_dir / RESULTS_FILE)
        runs = atomic_write_netcdf(runs_ds, self.out_dir / RUNS_FILE)
        self._write_status(state="complete")
        return RunSummary(
            points=self._points_total(),
            points_failed=self._points_failed(),
            runs_total=int(runs_ds.sizes["run"]),
            runs_computed=self.computed,
            runs_saved_by_warm_start=getattr(self.planner, "runs_saved", lambda: 0)(),
            wall_s=time.perf_counter() - self.t0,
            results=Path(results),
            runs=Path(runs),
            moved_aside=list(self.journal.corrupt_reasons),
            task_overhead_s=self.task_overhead_s,
        )


def _on_stderr(action, *args, **kwargs):
    """action(*args, **kwargs), which writes progress or a notice on stderr; None if
    stderr is gone (a closed terminal: EIO; a closed pipe: EPIPE). Losing them must never
    stop a campaign or its graceful stop."""
    try:
        return action(*args, **kwargs)
    except OSError:
        return None


@dataclasses.dataclass(frozen=True)
class _Canonical:
    """A scene's canonical dict, as run_key takes it (anything with .canonical())."""

    value: dict

    def canonical(self) -> dict:
        return self.value
