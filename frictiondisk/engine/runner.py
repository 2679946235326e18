"""Run a campaign: replay the journal, compute what is missing on Dask, write results.

The driver is the only writer of DIR. It holds DIR/lock for the whole run, commits every
finished run to the journal at once, and replays the planner from the journal first, so
an interrupted campaign resumes without computing a finished run again and loses at most
the runs that were in flight.

DIR layout: campaign.yaml (the campaign as first run), campaign.record.json (its sha256
and canonical form: a hand-edited campaign.yaml is refused), journal/ (one file per run),
status.json (progress, rewritten while running), results.nc, runs.nc, lock. None of these
may be a symbolic link (issue 14): the driver refuses to start rather than follow one.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import json
import os
import sys
import time
import uuid
from pathlib import Path
from typing import Any

from frictiondisk.engine.plan import Sizing, planner_for
from frictiondisk.engine.tasks import Sealed, noop, run_sealed, warm_up
from frictiondisk.model.campaign import Campaign, campaign_from_dict, load_campaign
from frictiondisk.model.scene import ConfigError
from frictiondisk.store import basin_datasets, datasets
from frictiondisk.store.files import atomic_write_bytes, atomic_write_netcdf, atomic_write_text
from frictiondisk.store.journal import CampaignLock, Journal, run_key
from frictiondisk.store.partial import with_pending
from frictiondisk.store.paths import refuse_symlink

CAMPAIGN_FILE = "campaign.yaml"
RECORD_FILE = "campaign.record.json"  # sha256 and canonical form of campaign.yaml
STATUS_FILE = "status.json"
RESULTS_FILE = "results.nc"
RUNS_FILE = "runs.nc"
STATUS_EVERY = 0.5  # [s] between status.json rewrites
PARTIAL_EVERY = 30.0  # [s] between partial results.nc rewrites of a running campaign
BAR_EVERY = 0.2  # [s] between progress-bar repaints
MAX_WORKER_FAILURES = 3  # resubmissions of a run whose worker died
SCHEDULER_TIMEOUT = 10.0  # [s] for the client to connect to --scheduler
WORKER_WAIT = 60.0  # [s] default wait for a live worker (--worker-wait)
POLL = 5.0  # [s] between checks for live workers while waiting on --scheduler
# Every name the driver reads or writes in DIR: none may be a symbolic link.
_DIR_NAMES = (
    "lock",
    CAMPAIGN_FILE,
    RECORD_FILE,
    STATUS_FILE,
    RESULTS_FILE,
    RUNS_FILE,
    "trajectory.nc",
    "journal",
    "journal/computed.log",
    "journal/corrupt",
)
TASK_OVERHEAD_SHARE = 0.05  # a task should last long enough that its scheduling costs <= 5 %
MAX_TASK_S = 2.0  # [s] ... but no longer: an interrupt waits for (or loses) the tasks in flight
TASKS_PER_WORKER = 2  # tasks in flight per worker thread: one running, one queued behind it
OVERHEAD_PROBES = 5  # round trips of an empty task timed (median): 8 cost 30 ms more, same value
DRAIN_TIMEOUT_S = 30.0  # [s] Ctrl-C waits this long for the tasks in flight, then drops them


class CampaignChanged(Exception):
    """The campaign file differs from the one DIR was started with."""

    def __init__(self, out_dir: Path, differences: list[str]):
        self.differences = differences
        super().__init__(
            f"{out_dir} holds a different campaign; refusing to mix results "
            f"(start a new directory, or resume with the original file):\n  "
            + "\n  ".join(differences)
        )


class SchedulerFailed(Exception):
    """--scheduler cannot be used: unreachable, or no worker alive for too long."""


class CampaignInterrupted(Exception):
    """Stopped by Ctrl-C or SIGTERM; the journal holds every finished run and results.nc
    the finished points (marked partial). `exit_code`: 130 (Ctrl-C) or 143 (SIGTERM)."""

    def __init__(self, message: str, exit_code: int = 130):
        super().__init__(message)
        self.exit_code = exit_code


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so that it stops a campaign like Ctrl-C."""


_stop_requested: list[type[KeyboardInterrupt]] = []


def request_stop(stop: type[KeyboardInterrupt]) -> None:
    """Note a stop (KeyboardInterrupt or Terminated) asked for by a signal. The handler
    raises it too, but an exception raised while the main thread runs a finalizer (Dask's
    Future.__del__) is printed and lost; the campaign loop then raises it from this note."""
    _stop_requested.append(stop)


def _raise_if_stop_requested() -> None:
    if _stop_requested:
        raise _stop_requested[-1]()


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


def _refuse_links(out_dir: Path) -> None:
    """SymlinkRefused (an OSError naming the path) if any name the driver uses in DIR, or
    any journal shard folder, is a symbolic link."""
    for name in _DIR_NAMES:
        refuse_symlink(out_dir / name)
    journal = out_dir / "journal"
    if journal.is_dir():
        for shard in journal.iterdir():
            if len(shard.name) == 2:
                refuse_symlink(shard)


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
    _refuse_links(out_dir)
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
            terminated = isinstance(stop, Terminated)
            what = "terminated (SIGTERM)" if terminated else "interrupted"
            written = driver.write_partial()
            raise CampaignInterrupted(
                f"{what}; {driver.runs_done()} finished runs are in the journal"
                + (
                    f", the {written} finished points in {RESULTS_FILE} (partial)"
                    if written
                    else ""
                )
                + f". Continue with: frictiondisk resume {out_dir}",
                143 if terminated else 130,
            ) from None
        finally:
            driver.journal.close()


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
    # a running campaign rewrites it every STATUS_EVERY seconds: no fsync (two per rewrite
    # cost ~2 ms here); the final state is made durable
    data = json.dumps(status, indent=1).encode()
    atomic_write_bytes(out_dir / STATUS_FILE, data, durable=state != "running")


def _run_trajectory(campaign: Campaign, out_dir: Path) -> RunSummary:
    """A trajectory campaign: one recorded run in this process (no Dask, no journal)."""
    from frictiondisk.engine.orbit import run_trajectory

    t0 = time.perf_counter()
    done = run_trajectory(campaign, out_dir, RESULTS_FILE)
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
        import dask
        from distributed import Client, LocalCluster

        warm_up()  # compile once here, so workers load the cache instead of racing on it
        if scheduler:
            try:
                client, cluster = Client(scheduler, timeout=SCHEDULER_TIMEOUT), None
            except (OSError, TimeoutError, ValueError) as err:
                raise SchedulerFailed(
                    f"--scheduler {scheduler}: cannot connect within {SCHEDULER_TIMEOUT:g} s "
                    f"({type(err).__name__}: {err})"
                ) from None
            self.scheduled = True
        else:
            # Dask's statistical profiler samples every worker thread every 10 ms: 3-4 % of
            # the CPU that two workers on two cores need for themselves (a dashboard tab).
            with dask.config.set({"distributed.worker.profile.enabled": False}):
                cluster = LocalCluster(
                    n_workers=workers,
                    threads_per_worker=1,
                    processes=processes,
                    # a free port: never clashes with another run; None: no dashboard
                    dashboard_address=":0" if self.serve_dashboard else None,
                )
            client = Client(cluster)
            if not processes:
                _send_without_batching_delay(client, cluster)
        try:  # from here on the client (and a local cluster) is always closed
            if self.serve_dashboard or self.scheduled:
                self.dashboard = _dashboard_link(client)
                print(f"Dask dashboard: {self.dashboard}", file=sys.stderr)
            if self.scheduled:
                self._await_a_worker(client)  # the overhead probe below needs one
            self.worker_threads = max(1, sum(client.nthreads().values()))
            self.task_overhead_s = measure_task_overhead(client)
            self._open_bar()
            try:
                self._loop(client)
            except KeyboardInterrupt:
                self._drain(client)
                raise
        finally:
            for *_, future in self.in_flight.values():
                future.cancel()
            client.close()
            if cluster is not None:
                cluster.close()
            if self._bar is not None:
                self._bar.n = self._points_done()
                self._bar.set_postfix(runs=self.runs_done(), in_flight=0, refresh=False)
                self._bar.close()

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
            print(
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

    def _drain(self, client) -> None:
        """After Ctrl-C: journal the runs of the tasks in flight as they finish (at most
        DRAIN_TIMEOUT_S; a second Ctrl-C drops them), submitting nothing new."""
        if not self.in_flight:
            return
        self._draining = True
        print(
            f"\nstopping: journaling the runs of {len(self.in_flight)} tasks in flight, for at "
            f"most {DRAIN_TIMEOUT_S:.0f} s (Ctrl-C again to drop them)",
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

        self._bar = progress_bar(
            len(self.planner.points), self.campaign.name, "point", initial=self._points_done()
        )

    def interrupted(self) -> None:
        self._write_status(state="interrupted")

    def runs_done(self) -> int:
        return self.runs_at_start + self.computed

    def _points_done(self) -> int:
        return len(self.planner.results)

    def _tick(self) -> None:
        now = time.perf_counter()
        if self._bar is not None and now - self._last_bar >= BAR_EVERY:
            self._last_bar = now
            self._bar.n = self._points_done()
            self._bar.set_postfix(
                runs=self.runs_done(), in_flight=len(self.in_flight), refresh=False
            )
            self._bar.refresh()
        if now - self._last_status >= STATUS_EVERY:
            self._write_status(state="running")
            self._last_status = now
        if now - self._last_partial >= PARTIAL_EVERY:
            self._last_partial = now
            self.write_partial()

    def _datasets(self):
        """The module that builds this campaign's results.nc and runs.nc."""
        return basin_datasets if self.campaign.kind == "basin" else datasets

    def write_partial(self) -> int:
        """Write results.nc from the finished points, the rest pending, marked `partial`
        (frictiondisk.store.partial); returns the points it holds (0: nothing written,
        as for a trajectory or when no point is finished). Never raises: a failure is
        reported on stderr, the journal keeps every run, and the final write of results.nc
        raises as usual."""
        done = self._points_done()
        if done == 0 or self.planner.done or self.campaign.kind == "trajectory":
            return 0
        try:
            pending = with_pending(self.campaign.kind, self.planner)
            ds = self._datasets().results_dataset(self.campaign, pending)
            ds.attrs.update(partial=1, points_done=done, points_total=len(self.planner.points))
            atomic_write_netcdf(ds, self.out_dir / RESULTS_FILE)
        except Exception as exc:  # noqa: BLE001  a side file: never stop the campaign for it
            print(f"warning: partial results not written: {exc!r}", file=sys.stderr)
            return 0
        return done

    def _write_status(self, state: str) -> None:
        done = self._points_done()
        total = len(self.planner.points)
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
            points=len(self.planner.points),
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


@dataclasses.dataclass(frozen=True)
class _Canonical:
    """A scene's canonical dict, as run_key takes it (anything with .canonical())."""

    value: dict

    def canonical(self) -> dict:
        return self.value


def task_sizing(
    overhead_s: float, mean_run_s: float | None, worker_threads: int, in_flight: int
) -> Sizing:
    """Cut work into tasks that last task_s = overhead / 5 % (at most MAX_TASK_S): a batch
    holds task_s / mean_run_s independent runs (1 while no run time is known yet), a chain
    runs for task_s; TASKS_PER_WORKER tasks per worker thread are in flight."""
    task_s = min(MAX_TASK_S, overhead_s * (1 - TASK_OVERHEAD_SHARE) / TASK_OVERHEAD_SHARE)
    batch = max(1, int(task_s / mean_run_s)) if mean_run_s else 1
    return Sizing(
        batch_runs=batch,
        chain_s=task_s,
        max_jobs=max(0, TASKS_PER_WORKER * worker_threads - in_flight),
        workers=worker_threads,
    )


def measure_task_overhead(client, probes: int = OVERHEAD_PROBES) -> float:
    """Median round trip [s] of an empty task through this client's scheduler: the cost
    per task that a batch must amortize (the first, cold, round trip is not counted)."""
    client.submit(noop, pure=False).result()
    times = []
    for _ in range(probes):
        t0 = time.perf_counter()
        client.submit(noop, pure=False).result()
        times.append(time.perf_counter() - t0)
    return sorted(times)[len(times) // 2]


def _has_dashboard() -> bool:
    """Whether the Dask dashboard can be served here (it needs bokeh)."""
    import importlib.util

    return importlib.util.find_spec("bokeh") is not None


def _dashboard_link(client) -> str:
    """The scheduler's dashboard address, or why there is none."""
    try:
        link = client.dashboard_link  # a scheduler without a dashboard lists no such service
    except (KeyError, AttributeError, TypeError):
        link = None
    if link and (client.cluster is None or _has_dashboard()):
        return link
    return "not available (the Dask dashboard needs bokeh: pip install 'bokeh>=3.1')"


def _send_without_batching_delay(client, cluster) -> None:
    """Dask batches messages for 2-10 ms per hop (hard-coded BatchedSend intervals), which
    made a job's round trip 10.7 ms here; in our own in-process cluster every hop is
    reachable, and sending at once brings it to 3.0 ms. A pure latency setting: if a Dask
    release renames these attributes, the campaign runs the same, only slower."""
    comms = [getattr(client, "scheduler_comm", None)]
    comms += list(getattr(cluster.scheduler, "stream_comms", {}).values())
    comms += list(getattr(cluster.scheduler, "client_comms", {}).values())
    comms += [getattr(w, "batched_stream", None) for w in cluster.workers.values()]
    for comm in comms:
        if comm is not None and hasattr(comm, "interval"):
            comm.interval = 0
