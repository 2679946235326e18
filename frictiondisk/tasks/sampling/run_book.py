"""The bookkeeping of a task whose points each take several runs from sampled starts (a
basin point's samples, a map cell's runs): which runs are wanted, out on a worker or known,
the jobs that carry them, and each run's scene.

Run j of point i is fixed by the campaign alone (frictiondisk.tasks.sampling.draws), so the
book never depends on worker count, job size or the order results arrive in. Linear in the
runs: wanted runs wait in one queue in the order they were asked for, a job takes the next
ones from it, `new_requests` names each run once, and a finished job touches only its own
points. What a point's runs mean (a stop rule, a cell's motion) is the planner's.
"""

from __future__ import annotations

import collections
from collections.abc import Iterable
from typing import Any

import numpy as np

from frictiondisk.tasks.canonical_scenes import CanonicalScenes
from frictiondisk.tasks.jobs import RunScenes, Sizing, halves
from frictiondisk.tasks.protocol import Planner
from frictiondisk.tasks.sampling.draws import sample_values
from frictiondisk.tasks.sampling.runs import SampleRequest
from frictiondisk.verdict.outcomes import UNDETERMINED

Run = tuple[int, int]  # (point, run index)


class RunBook:
    """The runs of every point of a sampled task; `task` has `seed` and `sample` ({} for a
    run from the scene's own start), `points` are the campaign's points."""

    def __init__(self, task, points, job_runs: int):
        self.task = task
        self.points = points
        self.job_runs = job_runs  # runs per job without the driver's sizing
        self.known: dict[int, dict[int, dict[str, Any]]] = collections.defaultdict(dict)
        self.todo: dict[int, set[int]] = collections.defaultdict(set)  # neither known nor out
        self.out: dict[int, int] = collections.defaultdict(int)  # runs out on a worker
        self.failed: dict[int, str] = {}  # point -> why a job of it never came back
        self._jobs: dict[Run, list[Run]] = {}
        self._blocks: dict[int, dict[tuple[str, int], np.ndarray]] = {}  # point -> its draws
        self._configs: dict[Run, Any] = {}
        self._queue: collections.deque[Run] = collections.deque()  # wanted, in the order asked
        self._fresh: list[Run] = []  # wanted, not yet named by new_requests
        self._scenes = CanonicalScenes()  # a run's canonical scene, made once
        self.open_runs = 0  # runs wanted and not yet known (out on a worker or not)

    # ---- what is wanted -----------------------------------------------------------------
    def want(self, runs: Iterable[Run]) -> None:
        """Ask for `runs` (none asked before), in this order."""
        runs = list(runs)
        for i, j in runs:
            self.todo[i].add(j)
        self.open_runs += len(runs)
        self._queue.extend(runs)
        self._fresh.extend(runs)

    def busy(self, i: int) -> bool:
        """Point i still has runs wanted or out on a worker."""
        return bool(self.todo[i]) or self.out[i] > 0

    def results_of(self, i: int, n: int) -> tuple[dict[str, Any], ...]:
        """The results of runs 0 .. n-1 of point i (every one known)."""
        return tuple(self.known[i][j] for j in range(n))

    def forget(self, i: int, n: int) -> None:
        """Drop the scenes and draws of a finished point's runs 0 .. n-1."""
        for j in range(n):
            self._configs.pop((i, j), None)
            self._scenes.forget((i, j))
        self._blocks.pop(i, None)

    # ---- a run's scene --------------------------------------------------------------------
    def sample_values(self, i: int, j: int) -> dict[str, float]:
        """The sampled initial-state values of run j of point i ({} from the scene's own
        start)."""
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

    # ---- the planner protocol's run side ----------------------------------------------
    def requests(self) -> list[tuple[int, SampleRequest]]:
        return [(i, SampleRequest(j)) for i in sorted(self.todo) for j in sorted(self.todo[i])]

    def new_requests(self) -> list[tuple[int, SampleRequest]]:
        """The runs asked for since the last call (each once), still wanted."""
        fresh, self._fresh = self._fresh, []
        return [(i, SampleRequest(j)) for i, j in fresh if j in self.todo[i]]

    def remember_canonical(self, i: int, request: SampleRequest, canonical: dict) -> None:
        if request.index in self.todo[i]:
            self._scenes.remember((i, request.index), canonical)

    def canonical_for(self, i: int, request: SampleRequest) -> dict:
        return self._scenes.for_key(
            (i, request.index), lambda: self.config_for(i, request).canonical()
        )

    def _scene(self, i: int, j: int) -> dict:
        """Run j of point i's canonical scene for its job (CanonicalScenes.for_job)."""
        return self._scenes.for_job(
            (i, j), lambda: self.config_for(i, SampleRequest(j)).canonical()
        )

    def take(self, i: int, j: int, result: dict[str, Any]) -> bool:
        """Take a result from the journal; False (ignored) where the run is not wanted."""
        if j not in self.todo[i]:
            return False
        self.known[i][j] = result
        self.todo[i].discard(j)
        self.open_runs -= 1
        return True

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[Run, RunScenes]]:
        """Wanted runs not yet out, in the order asked: sizing.batch_runs to a job (no more
        than an equal share of the queue for each of sizing.workers), at most
        sizing.max_jobs jobs (without sizing: job_runs to a job, all of them)."""
        per_job = self.job_runs if sizing is None else max(1, sizing.batch_runs)
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
            scenes = [self._scene(i, j) for i, j in items]
            out.append((job, RunScenes(tuple(scenes))))
        return out

    def complete(self, job: Run, value) -> tuple[list[tuple[int, SampleRequest, dict]], list[int]]:
        """Take a finished job back: (its runs, for the journal; the points it touched)."""
        items = self._jobs.pop(job)
        self.open_runs -= len(items)
        made = []
        for (i, j), result in zip(items, value, strict=True):
            self.out[i] -= 1
            self.known[i][j] = result
            made.append((i, SampleRequest(j), result))
        return made, sorted({i for i, _ in items})

    def split(self, job: Run, work: RunScenes) -> list[tuple[Run, RunScenes]]:
        """A failed batch in halves, each named by its first run (as `jobs` names one)."""
        parts = []
        for items, half in halves(self._jobs.pop(job), work):
            self._jobs[items[0]] = items
            parts.append((items[0], half))
        return parts

    def fail(self, job: Run, reason: str) -> list[int]:
        """A job that never came back: its runs are `undetermined` with that reason and
        their points failed (nothing is journaled, so a resume runs them again); returns
        the points it touched."""
        items = self._jobs.pop(job)
        self.open_runs -= len(items)
        for i, j in items:
            self.out[i] -= 1
            self._scenes.forget((i, j))  # not journaled: never keyed
            self.known[i][j] = {"outcome": UNDETERMINED, "reason": reason}
            self.failed[i] = reason
        return sorted({i for i, _ in items})


class RunBookPlanner(Planner):
    """A planner whose runs a `RunBook` keeps (self.book): the protocol's run side handed
    to the book; a subclass says what finished runs mean in `_advance(points)`, called with
    the points a result touched."""

    book: RunBook

    def config_for(self, i: int, request: SampleRequest):
        return self.book.config_for(i, request)

    def requests(self) -> list[tuple[int, SampleRequest]]:
        return self.book.requests()

    def new_requests(self) -> list[tuple[int, SampleRequest]]:
        """The runs asked for since the last call (each once), still wanted."""
        return self.book.new_requests()

    def remember_canonical(self, i: int, request: SampleRequest, canonical: dict) -> None:
        self.book.remember_canonical(i, request, canonical)

    def canonical_for(self, i: int, request: SampleRequest) -> dict:
        return self.book.canonical_for(i, request)

    def feed(self, i: int, request: SampleRequest, result: dict[str, Any]) -> None:
        """Take a result; one the point no longer waits for is ignored."""
        if self.book.take(i, request.index, result):
            self._advance([i])

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[Run, RunScenes]]:
        """Requested runs not yet out, in the order asked (RunBook.jobs)."""
        return self.book.jobs(sizing)

    def complete(self, job: Run, value) -> list[tuple[int, SampleRequest, dict[str, Any]]]:
        """Take a finished job back; returns its runs, for the journal."""
        made, points = self.book.complete(job, value)
        self._advance(points)
        return made

    def split(self, job: Run, work: RunScenes) -> list[tuple[Run, RunScenes]]:
        return self.book.split(job, work)

    def fail(self, job: Run, reason: str) -> None:
        """A job that never came back: its runs are `undetermined` with that reason and
        their points failed (nothing is journaled, so a resume runs them again)."""
        self._advance(self.book.fail(job, reason))

    def _advance(self, points: list[int]) -> None:
        raise NotImplementedError
