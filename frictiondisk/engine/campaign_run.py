"""One campaign inside the driver loop (engine/driver.py): its planner and journal, the
runs it answers from the journal, its status.json, its partial results.nc and, once its
last point is done, its files (results.nc and runs.nc; a task without a journal writes its
own: a trajectory's trajectory.nc). The task is reached through its entry
(frictiondisk.tasks.registry) and its planner's snapshot, never by its name.

The loop may drive several of these on one Dask client (`run A.yaml B.yaml`); each keeps
its own directory, journal and files, and finishes the moment its own planner is done.
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path
from typing import Any

from frictiondisk.engine.directory import write_status
from frictiondisk.store.files import atomic_write_netcdf
from frictiondisk.store.journal import Journal
from frictiondisk.store.journal_entry import canonical_json, scene_key
from frictiondisk.store.layout import RESULTS_FILE
from frictiondisk.store.partial import mark_partial
from frictiondisk.tasks.campaign import Campaign


@dataclasses.dataclass
class RunSummary:
    points: int
    points_failed: int
    runs_total: int  # runs the planner used (journal hits + computed)
    runs_computed: int  # runs computed in this invocation
    runs_saved_by_warm_start: int
    wall_s: float  # from the start of the invocation to this campaign's last point [s]
    results: Path
    runs: Path
    moved_aside: list[str] = dataclasses.field(default_factory=list)  # rejected entries
    task_overhead_s: float | None = None  # measured round trip of an empty Dask task [s]


class CampaignRun:
    """A campaign's state in the driver loop (holds no lock: the runner does)."""

    def __init__(self, campaign: Campaign, out_dir: Path):
        self.campaign = campaign
        self.out_dir = out_dir
        self.dir_text = str(out_dir.resolve())  # what worker chains read the journal from
        entry = campaign.entry
        self.planner = entry.planner(campaign)
        # a task without a journal (a trajectory) keeps its files as its record
        self.journal = Journal(out_dir) if entry.journaled else None
        self.keys: dict[tuple[int, Any], str] = {}  # (point, request) -> run key
        self.inputs: dict[str, dict] = {}
        # key -> its inputs' canonical JSON, written for the key, until journaled or found
        self._texts: dict[str, str] = {}
        self.computed = 0
        # listed once: only this process writes the journal (it holds the lock), so a key
        # not in this set is not looked up on disk (on slow file systems a failed open of
        # each new run's entry cost the driver about 1 ms)
        self._present: set[str] = set(self.journal.keys()) if self.journal else set()
        self.runs_at_start = len(self._present)
        if self.journal is None and entry.files_current(out_dir):
            self.planner.already_written()
            self.runs_at_start = 1
        # keys looked up and absent; the journal only grows by our own put (which clears one)
        self._checked: set[str] = set()
        self.run_s_sum = 0.0  # kernel wall time of the runs computed so far [s]
        self.replayed_s = (0.0, 0)  # (kernel time [s], runs) of the runs the journal held
        # requests the planner named once (new_requests) and the journal lacked, by key:
        # a run journaled later answers them too (another point asking for the same run)
        self._absent: dict[str, list[tuple[int, Any]]] = {}
        self.changed = True  # results came in since the last replay
        self.summary: RunSummary | None = None  # set once finished

    # ---- the journal ---------------------------------------------------------------------
    def replay(self) -> None:
        """Feed every run the journal already holds (no Dask). A planner that names its
        new requests (`new_requests`) is asked only for those: O(1) per run; one that does
        not lists all its pending requests again."""
        self.changed = False
        fresh = self.planner.new_requests()
        if fresh is None:
            return self._replay_all()
        if not self._present:
            # an empty journal answers nothing: the keys wait until the runs are journaled
            # (complete), computed beside the workers instead of before the first job
            return
        while fresh and not self.planner.done:
            for point, request in fresh:
                key = self.key(point, request)
                cached = self.journal.get(key) if key in self._present else None
                if cached is None:
                    self._present.discard(key)  # a bad entry was moved aside
                    self._absent.setdefault(key, []).append((point, request))
                else:
                    self._texts.pop(key, None)
                    self._feed(point, request, cached)
            fresh = self.planner.new_requests()

    def _feed(self, point: int, request, result: dict) -> None:
        self.planner.feed(point, request, result)
        wall_s, runs = self.replayed_s
        self.replayed_s = (wall_s + float(result.get("wall_s") or 0.0), runs + 1)

    def _replay_all(self) -> None:
        progressed = True
        while progressed and not self.planner.done:
            progressed = False
            for point, request in self.planner.requests():
                key = self.key(point, request)
                if key in self._checked:
                    continue
                cached = self.journal.get(key) if key in self._present else None
                if cached is None:
                    self._present.discard(key)  # a bad entry was moved aside
                    self._checked.add(key)
                else:
                    self._texts.pop(key, None)
                    self._feed(point, request, cached)
                    progressed = True

    def complete(self, job: Any, value: Any, batch: bool = False) -> None:
        """A job came back: the planner takes it, every run it made is journaled before
        this returns (a batch's runs as one pack, Journal.put_many; a search chain's
        one by one, where a later chain on a worker can peek them)."""
        self.changed = True
        made = self.planner.complete(job, value)
        if self.journal is None:  # its files are its record (written by finish)
            self.computed += len(made)
            return
        entries = []
        for point, request, result in made:
            key = self.key(point, request)
            entries.append((key, self.inputs[key], result))
            self.computed += 1
            self.run_s_sum += float(result.get("wall_s") or 0.0)
        texts = {key: self._texts.pop(key, None) for key, _, _ in entries}
        if batch:
            self.journal.put_many(entries, texts)
        else:
            for key, inputs, result in entries:
                self.journal.put(key, inputs, result, texts[key])
        for key, _, result in entries:
            self._present.add(key)
            self._checked.discard(key)  # another point may ask for the same run
            for point, request in self._absent.pop(key, ()):
                self.planner.feed(point, request, result)  # ignored if no longer wanted

    def fail(self, job: Any, reason: str) -> None:
        """A job that never came back: nothing journaled for it (a resume tries again)."""
        self.changed = True
        self.planner.fail(job, reason)

    def key(self, point: int, request) -> str:
        cached = self.keys.get((point, request))
        if cached is None:
            canonical = self.planner.canonical_for(point, request)
            text = canonical_json(canonical)  # written once, for the key and the entry
            cached = scene_key(canonical, text)
            self.keys[(point, request)] = cached
            self.inputs[cached] = canonical
            self._texts[cached] = text
            self.planner.remember_canonical(point, request, canonical)
        return cached

    def mean_run_s(self) -> float | None:
        """The mean kernel time of a run [s]: of those computed now, else of those the
        journal held (None before any)."""
        if self.computed:
            return self.run_s_sum / self.computed
        wall_s, runs = self.replayed_s
        return wall_s / runs if runs and wall_s > 0 else None

    # ---- progress and status -------------------------------------------------------------
    def runs_done(self) -> int:
        return self.runs_at_start + self.computed

    def progress(self) -> tuple[int, int]:
        """(done, total) in the planner's unit: points, or what its `progress()` counts
        (a trace: curve points placed; its total grows as curves are found)."""
        return self.planner.progress()

    def points_failed(self) -> int:
        return self.planner.points_failed()

    def write_status(self, state: str, elapsed: float, jobs_in_flight: int) -> None:
        done, total = self.progress()
        rate = done / elapsed if done and elapsed > 0 else 0.0
        write_status(
            self.out_dir,
            state,
            self.campaign,
            points_total=total,
            points_done=done,
            points_failed=self.points_failed(),
            runs_done=self.runs_done(),
            jobs_in_flight=jobs_in_flight,
            runs_computed_now=self.computed,
            elapsed_s=elapsed,
            eta_s=(total - done) / rate if rate > 0 else None,
        )

    def write_partial(self) -> int | None:
        """Write results.nc from the finished points, the rest pending, marked `partial`
        (frictiondisk.store.partial), also before the first point is finished; returns the
        finished points it holds (None: nothing written, as for a finished campaign or a
        task whose snapshot has no results.nc yet, a trajectory). Never raises: a failure
        is reported on stderr, the journal keeps every run, and the final write of
        results.nc raises as usual."""
        done, total = self.progress()
        if self.planner.done:
            return None
        try:
            ds = self.planner.snapshot().to_dataset()
            if ds is None:
                return None
            atomic_write_netcdf(mark_partial(ds, done, total), self.out_dir / RESULTS_FILE)
        except Exception as exc:  # noqa: BLE001  a side file: never stop the campaign for it
            on_stderr(print, f"warning: partial results not written: {exc!r}", file=sys.stderr)
            return None
        return done

    # ---- the end -------------------------------------------------------------------------
    def finish(self, elapsed: float, task_overhead_s: float | None) -> RunSummary:
        """Write the campaign's final files and status; its summary (also kept)."""
        results, runs, runs_total = self.planner.snapshot().write(self.out_dir, self.key)
        self.write_status("complete", elapsed, 0)
        self.summary = RunSummary(
            points=self.progress()[1],
            points_failed=self.points_failed(),
            runs_total=runs_total,
            runs_computed=self.computed,
            runs_saved_by_warm_start=self.planner.runs_saved(),
            wall_s=elapsed,
            results=Path(results),
            runs=Path(runs),
            moved_aside=list(self.journal.corrupt_reasons) if self.journal else [],
            task_overhead_s=task_overhead_s,
        )
        return self.summary


def on_stderr(action, *args, **kwargs):
    """action(*args, **kwargs), which writes progress or a notice on stderr; None if
    stderr is gone (a closed terminal: EIO; a closed pipe: EPIPE). Losing them must never
    stop a campaign or its graceful stop."""
    try:
        return action(*args, **kwargs)
    except OSError:
        return None
