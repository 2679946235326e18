"""Which runs a `basin` campaign needs: sampled initial states per point, in batches.

The planner contract of frictiondisk.tasks.protocol (`requests`/`feed` answered from the
journal, `jobs`/`complete`/`fail` on Dask), and its promise: the result does not depend on
worker count, job order or timing.

Samples: frictiondisk.tasks.sampling.draws fixes what sample j of a point is.

Adaptive sampling (`target_se`). Samples are taken in batches of `batch`; only when every
sample of a batch is known is the stop rule checked (basin_stats.stopping_error of the
not-stick fraction <= target_se, or max_samples reached), so the number of samples a point
ends with depends on outcomes only.

A basin map (`basin.grid`) is the same with one unsampled run per grid cell.

Bookkeeping is linear in the runs: wanted samples wait in one queue in the order they were
asked for, a job takes the next ones from it, and `new_requests` names each sample once.
"""

from __future__ import annotations

import collections
from typing import Any

import numpy as np

from frictiondisk.tasks.basin import stats as basin_stats
from frictiondisk.tasks.basin.results import BasinResults
from frictiondisk.tasks.basin.sampling import STICK, UNDETERMINED, BasinPointResult
from frictiondisk.tasks.jobs import RunScenes, Sizing
from frictiondisk.tasks.protocol import Planner
from frictiondisk.tasks.sampling.draws import sample_values
from frictiondisk.tasks.sampling.runs import SampleRequest

JOB_RUNS = 16  # runs per job without the driver's sizing (tests, a direct use)


class BasinPlanner(Planner):
    """basin: sampled initial states at every point (or one run per cell of a map)."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.task = campaign.task
        self.points = campaign.points()
        self.results: dict[int, BasinPointResult] = {}
        self.known: list[dict[int, dict[str, Any]]] = [{} for _ in self.points]
        first = self.task.sample_limit
        if self.task.target_se is not None:
            first = min(self.task.batch, self.task.max_samples)
        self.target = [first] * len(self.points)  # samples wanted so far, per point
        self.todo = [set(range(first)) for _ in self.points]  # wanted, neither known nor out
        self.out = [0] * len(self.points)  # samples of each point out on a worker
        self.stop_reason: dict[int, str] = {}
        self.failed: dict[int, str] = {}  # point -> why a job of it never came back
        self._jobs: dict[tuple[int, int], list[tuple[int, int]]] = {}
        self._blocks: dict[int, dict[tuple[str, int], np.ndarray]] = {}  # point -> its draws
        self._configs: dict[tuple[int, int], Any] = {}
        # (point, sample) wanted, in the order asked; entries already known are skipped
        self._queue = collections.deque(
            (i, j) for i in range(len(self.points)) for j in range(first)
        )
        self._fresh = list(self._queue)  # wanted, not yet named by new_requests
        self._canonicals: dict[tuple[int, int], dict] = {}  # until sent to a worker

    # ---- samples ----------------------------------------------------------------------
    def sample_values(self, i: int, j: int) -> dict[str, float]:
        """The sampled initial-state values of sample j at point i."""
        blocks = self._blocks.setdefault(i, {})
        return sample_values(self.task, self.points[i].coords, j, blocks)

    def config_for(self, i: int, request: SampleRequest):
        cached = self._configs.get((i, request.index))
        if cached is None:
            values = self.sample_values(i, request.index)
            point = self.points[i].config
            cached = point.with_overrides(values) if values else point
            self._configs[(i, request.index)] = cached
        return cached

    # ---- planner protocol -------------------------------------------------------------
    @property
    def done(self) -> bool:
        return len(self.results) == len(self.points)

    def progress(self) -> tuple[int, int]:
        """(points finished, points)."""
        return len(self.results), len(self.points)

    def snapshot(self) -> BasinResults:
        """What the planner has found so far (every point not finished: None)."""
        results = tuple(self.results.get(i) for i in range(len(self.points)))
        return BasinResults(self.campaign, tuple(self.points), results)

    def requests(self) -> list[tuple[int, SampleRequest]]:
        return [(i, SampleRequest(j)) for i, todo in enumerate(self.todo) for j in sorted(todo)]

    def new_requests(self) -> list[tuple[int, SampleRequest]]:
        """The samples asked for since the last call (each once), still wanted."""
        fresh, self._fresh = self._fresh, []
        return [(i, SampleRequest(j)) for i, j in fresh if j in self.todo[i]]

    def remember_canonical(self, i: int, request: SampleRequest, canonical: dict) -> None:
        if request.index in self.todo[i]:
            self._canonicals[(i, request.index)] = canonical

    def feed(self, i: int, request: SampleRequest, result: dict[str, Any]) -> None:
        """Take a result; one the point no longer waits for is ignored."""
        j = request.index
        if j not in self.todo[i]:
            return
        self._take(i, j, result)
        self._advance(i)

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[tuple[int, int], RunScenes]]:
        """Requested samples not yet out, in the order asked: sizing.batch_runs to a job
        (no more than an equal share of the queue for each of sizing.workers), at most
        sizing.max_jobs jobs (without sizing: JOB_RUNS to a job, all of them)."""
        per_job = JOB_RUNS if sizing is None else max(1, sizing.batch_runs)
        workers = 1 if sizing is None else max(1, sizing.workers)
        limit = None if sizing is None else sizing.max_jobs
        out = []
        while self._queue and (limit is None or len(out) < limit):
            size = max(1, min(per_job, -(-len(self._queue) // workers)))
            items = []
            while self._queue and len(items) < size:
                i, j = self._queue.popleft()
                if j in self.todo[i]:  # else known meanwhile (the journal)
                    items.append((i, j))
            if not items:
                break
            job = items[0]
            self._jobs[job] = items
            for i, j in items:
                self.todo[i].discard(j)
                self.out[i] += 1
            scenes = [
                self._canonicals.pop((i, j), None)
                or self.config_for(i, SampleRequest(j)).canonical()
                for i, j in items
            ]
            out.append((job, RunScenes(tuple(scenes))))
        return out

    def complete(self, job, value) -> list[tuple[int, SampleRequest, dict[str, Any]]]:
        """Take a finished job back; returns its runs, for the journal."""
        items = self._jobs.pop(job)
        made = []
        for (i, j), result in zip(items, value, strict=True):
            self.out[i] -= 1
            self._take(i, j, result)
            made.append((i, SampleRequest(j), result))
        for i in sorted({i for i, _ in items}):
            self._advance(i)
        return made

    def fail(self, job, reason: str) -> None:
        """A job that never came back: its samples are `undetermined` with that reason and
        the point is marked failed (nothing is journaled, so a resume runs them again)."""
        items = self._jobs.pop(job)
        for i, j in items:
            self.out[i] -= 1
            self._take(i, j, {"outcome": UNDETERMINED, "reason": reason})
            self.failed[i] = reason
        for i in sorted({i for i, _ in items}):
            self._advance(i)

    # ---- stop rule --------------------------------------------------------------------
    def _take(self, i: int, j: int, result: dict[str, Any]) -> None:
        self.known[i][j] = result
        self.todo[i].discard(j)

    def _advance(self, i: int) -> None:
        n = self.target[i]
        if i in self.results or self.todo[i] or self.out[i]:
            return
        if self.task.target_se is None:
            why = "one run per grid cell" if self.task.is_map else f"{n} samples, as asked"
            return self._finish(i, why)
        results = [self.known[i][j] for j in range(n)]
        large = sum(1 for r in results if r["outcome"] not in (STICK, UNDETERMINED))
        error = basin_stats.stopping_error(large, n)
        if error <= self.task.target_se:
            return self._finish(
                i, f"target_se reached: error {error:.3g} <= {self.task.target_se:g} at n = {n}"
            )
        if n >= self.task.max_samples:
            return self._finish(
                i, f"max_samples {n} reached with error {error:.3g} > {self.task.target_se:g}"
            )
        self.target[i] = min(n + self.task.batch, self.task.max_samples)
        self.todo[i] = set(range(n, self.target[i]))
        self._queue.extend((i, j) for j in range(n, self.target[i]))
        self._fresh.extend((i, j) for j in range(n, self.target[i]))

    def _finish(self, i: int, why: str) -> None:
        n = self.target[i]
        results = tuple(self.known[i][j] for j in range(n))
        failed = self.failed.get(i)
        status = "failed" if failed else "converged"
        reason = f"{why}; some runs failed: {failed}" if failed else why
        self.results[i] = BasinPointResult(status=status, reason=reason, results=results)
        for j in range(n):
            self._configs.pop((i, j), None)
            self._canonicals.pop((i, j), None)
        self._blocks.pop(i, None)
