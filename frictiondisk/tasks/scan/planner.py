"""Which runs a `scan` campaign needs: one run per grid point (pure Python; the planner
contract is frictiondisk.tasks.protocol.Planner).

Bookkeeping is linear in the points: they are handed out in index order from a cursor,
a finished job updates its points in O(1) each, and `new_requests` names each point once,
so the driver's replay never lists the pending points again."""

from __future__ import annotations

import math
from typing import Any

from frictiondisk.tasks.canonical_scenes import CanonicalScenes
from frictiondisk.tasks.jobs import JobTable, RunScenes, Sizing
from frictiondisk.tasks.jump_search.runs import RunRequest
from frictiondisk.tasks.protocol import Planner
from frictiondisk.tasks.scan.results import ScanResults
from frictiondisk.verdict.outcomes import UNDETERMINED


class ScanPlanner(Planner):
    """scan: one run per grid point (mu and at most one more parameter), no bisection."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.points = campaign.points()
        self.results: dict[int, dict[str, Any]] = {}
        self.busy: set[int] = set()
        self._cursor = 0  # every point below it is known or out on a worker
        self._jobs = JobTable()  # job id -> its points
        self._listed = False  # new_requests has named every point
        self._scenes = CanonicalScenes()  # point -> its canonical scene, made once

    def config_for(self, i: int, request: RunRequest):
        return self.points[i].config

    @property
    def done(self) -> bool:
        return len(self.results) == len(self.points)

    def progress(self) -> tuple[int, int]:
        """(points run, points)."""
        return len(self.results), len(self.points)

    def snapshot(self) -> ScanResults:
        """What the planner has found so far (every point not run: None)."""
        results = tuple(self.results.get(i) for i in range(len(self.points)))
        return ScanResults(self.campaign, tuple(self.points), results)

    def _request(self, i: int) -> RunRequest:
        return RunRequest(self.points[i].config.params.mu)

    def requests(self) -> list[tuple[int, RunRequest]]:
        return [
            (i, self._request(i))
            for i in range(self._cursor, len(self.points))
            if i not in self.results and i not in self.busy
        ]

    def new_requests(self) -> list[tuple[int, RunRequest]]:
        """Every point's run on the first call, nothing after: a scan's runs are all
        known from the start."""
        if self._listed:
            return []
        self._listed = True
        return self.requests()

    def remember_canonical(self, i: int, request: RunRequest, canonical: dict) -> None:
        if i not in self.results:
            self._scenes.remember(i, canonical)

    def canonical_for(self, i: int, request: RunRequest) -> dict:
        return self._scenes.for_key(i, self.points[i].config.canonical)

    def feed(self, i: int, request: RunRequest, result: dict[str, Any]) -> None:
        self.results.setdefault(i, result)
        self._scenes.forget(i)

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[int, RunScenes]]:
        """Batches of points not yet known, in index order: sizing.batch_runs to a job, but
        no more than an equal share for each of sizing.workers of what is left (so the last
        batches shrink and the workers end together), at most sizing.max_jobs of them
        (without sizing: one point per job, all of them)."""
        sizing = sizing or Sizing()
        limit = math.inf if sizing.max_jobs is None else sizing.max_jobs
        out = []
        while len(out) < limit:
            self._skip_known()
            left = len(self.points) - self._cursor  # an upper bound: fine for a share
            if left <= 0:
                break
            size = max(1, min(sizing.batch_runs, -(-left // max(1, sizing.workers))))
            batch = []
            while len(batch) < size and self._cursor < len(self.points):
                i = self._cursor
                self._cursor += 1
                if i not in self.results:
                    batch.append(i)
            if not batch:
                break
            job = self._jobs.add(tuple(batch))
            self.busy.update(batch)
            scenes = tuple(self._scenes.for_job(i, self.points[i].config.canonical) for i in batch)
            out.append((job, RunScenes(scenes)))
        return out

    def _skip_known(self) -> None:
        while self._cursor < len(self.points) and self._cursor in self.results:
            self._cursor += 1

    def complete(self, job: int, value) -> list[tuple[int, RunRequest, dict[str, Any]]]:
        made = []
        for i, result in zip(self._jobs.pop(job), value, strict=True):
            self.busy.discard(i)
            self.results[i] = result
            made.append((i, self._request(i), result))
        return made

    def split(self, job: int, work: RunScenes) -> list[tuple[int, RunScenes]]:
        return self._jobs.halve(job, work)

    def fail(self, job: int, reason: str) -> None:
        """Runs whose worker kept dying: reported `undetermined` with that reason (they are
        not journaled, so a resume tries again)."""
        for i in self._jobs.pop(job):
            self.busy.discard(i)
            self._scenes.forget(i)  # not journaled: never keyed
            self.results[i] = {"outcome": UNDETERMINED, "reason": reason}
