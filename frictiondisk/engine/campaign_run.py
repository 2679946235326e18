"""One campaign inside the driver loop (engine/driver.py): its planner and journal, the
runs it answers from the journal, its status.json, its partial results.nc and, once its
last point is done, its results.nc and runs.nc (trajectory.nc for a trajectory task).

The loop may drive several of these on one Dask client (`run A.yaml B.yaml`); each keeps
its own directory, journal and files, and finishes the moment its own planner is done.
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path
from typing import Any

from frictiondisk.engine.directory import RESULTS_FILE, RUNS_FILE, write_status
from frictiondisk.engine.plan import planner_for
from frictiondisk.model.campaign import Campaign
from frictiondisk.store import basin_datasets, datasets, trace_datasets
from frictiondisk.store.files import atomic_write_netcdf
from frictiondisk.store.journal import Journal, run_key
from frictiondisk.store.partial import with_pending


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
        self.planner = planner_for(campaign)
        # a trajectory keeps no journal: its files are its record (engine/orbit.py)
        self.journal = Journal(out_dir) if campaign.kind != "trajectory" else None
        self.keys: dict[tuple[int, Any], str] = {}  # (point, request) -> run key
        self.inputs: dict[str, dict] = {}
        self.computed = 0
        # listed once: only this process writes the journal (it holds the lock), so a key
        # not in this set is not looked up on disk (on slow file systems a failed open of
        # each new run's entry cost the driver about 1 ms)
        self._present: set[str] = set(self.journal.keys()) if self.journal else set()
        self.runs_at_start = len(self._present)
        if self.journal is None:
            from frictiondisk.engine.orbit import outputs_valid

            if outputs_valid(out_dir, RESULTS_FILE):
                self.planner.already_written()
                self.runs_at_start = 1
        # keys looked up and absent; the journal only grows by our own put (which clears one)
        self._checked: set[str] = set()
        self.run_s_sum = 0.0  # kernel wall time of the runs computed so far [s]
        self.changed = True  # results came in since the last replay
        self.summary: RunSummary | None = None  # set once finished

    # ---- the journal ---------------------------------------------------------------------
    def replay(self) -> None:
        """Feed every run the journal already holds (no Dask)."""
        self.changed = False
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
                    self.planner.feed(point, request, cached)
                    progressed = True

    def complete(self, job: Any, value: Any) -> None:
        """A job came back: the planner takes it, every run it made is journaled."""
        self.changed = True
        for point, request, result in self.planner.complete(job, value):
            key = self.key(point, request)
            self.journal.put(key, self.inputs[key], result)
            self._present.add(key)
            self._checked.discard(key)  # another point may ask for the same run
            self.computed += 1
            self.run_s_sum += float(result.get("wall_s") or 0.0)

    def fail(self, job: Any, reason: str) -> None:
        """A job that never came back: nothing journaled for it (a resume tries again)."""
        self.changed = True
        self.planner.fail(job, reason)

    def key(self, point: int, request) -> str:
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

    def mean_run_s(self) -> float | None:
        return self.run_s_sum / self.computed if self.computed else None

    # ---- progress and status -------------------------------------------------------------
    def runs_done(self) -> int:
        return self.runs_at_start + self.computed

    def progress(self) -> tuple[int, int]:
        """(done, total) in the planner's unit: points, or what its `progress()` counts
        (a trace: curve points placed; its total grows as curves are found)."""
        progress = getattr(self.planner, "progress", None)
        if progress is not None:
            return progress()
        return len(self.planner.results), len(self.planner.points)

    def points_failed(self) -> int:
        results = self.planner.results.values()
        return sum(1 for r in results if getattr(r, "status", "converged") == "failed")

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
        done, total = self.progress()
        if self.planner.done or self.campaign.kind == "trajectory":
            return None
        try:
            pending = with_pending(self.campaign.kind, self.planner)
            ds = self._datasets().results_dataset(self.campaign, pending)
            ds.attrs.update(partial=1, points_done=done, points_total=total)
            atomic_write_netcdf(ds, self.out_dir / RESULTS_FILE)
        except Exception as exc:  # noqa: BLE001  a side file: never stop the campaign for it
            on_stderr(print, f"warning: partial results not written: {exc!r}", file=sys.stderr)
            return None
        return done

    # ---- the end -------------------------------------------------------------------------
    def finish(self, elapsed: float, task_overhead_s: float | None) -> RunSummary:
        """Write the campaign's final files and status; its summary (also kept)."""
        if self.campaign.kind == "trajectory":
            from frictiondisk.engine.orbit import TRAJECTORY_FILE, write_outputs

            result = self.planner.result
            if result is not None:
                write_outputs(self.campaign, self.out_dir, result, RESULTS_FILE)
            runs_total, results = 1, self.out_dir / RESULTS_FILE
            runs = self.out_dir / TRAJECTORY_FILE
            self.computed = int(result is not None)
        else:
            build = self._datasets()
            results_ds = build.results_dataset(self.campaign, self.planner)
            runs_ds = build.runs_dataset(self.campaign, self.planner, self.key)
            results = atomic_write_netcdf(results_ds, self.out_dir / RESULTS_FILE)
            runs = atomic_write_netcdf(runs_ds, self.out_dir / RUNS_FILE)
            runs_total = int(runs_ds.sizes["run"])
        self.write_status("complete", elapsed, 0)
        self.summary = RunSummary(
            points=self.progress()[1],
            points_failed=self.points_failed(),
            runs_total=runs_total,
            runs_computed=self.computed,
            runs_saved_by_warm_start=getattr(self.planner, "runs_saved", lambda: 0)(),
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


@dataclasses.dataclass(frozen=True)
class _Canonical:
    """A scene's canonical dict, as run_key takes it (anything with .canonical())."""

    value: dict

    def canonical(self) -> dict:
        return self.value
