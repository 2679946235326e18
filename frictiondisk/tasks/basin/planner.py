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

Which samples are wanted, out or known, and the jobs that carry them, are the run book's
(frictiondisk.tasks.sampling.run_book, shared with the map task): linear in the runs.
"""

from __future__ import annotations

from typing import Any

from frictiondisk.tasks.basin import stats as basin_stats
from frictiondisk.tasks.basin.results import BasinResults
from frictiondisk.tasks.basin.sampling import STICK, UNDETERMINED, BasinPointResult
from frictiondisk.tasks.jobs import RunScenes, Sizing
from frictiondisk.tasks.protocol import Planner
from frictiondisk.tasks.sampling.run_book import RunBook
from frictiondisk.tasks.sampling.runs import SampleRequest

JOB_RUNS = 16  # runs per job without the driver's sizing (tests, a direct use)


class BasinPlanner(Planner):
    """basin: sampled initial states at every point (or one run per cell of a map)."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.task = campaign.task
        self.points = campaign.points()
        self.results: dict[int, BasinPointResult] = {}
        self.book = RunBook(self.task, self.points, JOB_RUNS)
        first = self.task.sample_limit
        if self.task.target_se is not None:
            first = min(self.task.batch, self.task.max_samples)
        self.target = [first] * len(self.points)  # samples wanted so far, per point
        self.stop_reason: dict[int, str] = {}
        self.book.want((i, j) for i in range(len(self.points)) for j in range(first))

    # ---- samples ----------------------------------------------------------------------
    def sample_values(self, i: int, j: int) -> dict[str, float]:
        """The sampled initial-state values of sample j at point i."""
        return self.book.sample_values(i, j)

    def config_for(self, i: int, request: SampleRequest):
        return self.book.config_for(i, request)

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
        return self.book.requests()

    def new_requests(self) -> list[tuple[int, SampleRequest]]:
        """The samples asked for since the last call (each once), still wanted."""
        return self.book.new_requests()

    def remember_canonical(self, i: int, request: SampleRequest, canonical: dict) -> None:
        self.book.remember_canonical(i, request, canonical)

    def feed(self, i: int, request: SampleRequest, result: dict[str, Any]) -> None:
        """Take a result; one the point no longer waits for is ignored."""
        if self.book.take(i, request.index, result):
            self._advance(i)

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[tuple[int, int], RunScenes]]:
        """Requested samples not yet out, in the order asked (RunBook.jobs)."""
        return self.book.jobs(sizing)

    def complete(self, job, value) -> list[tuple[int, SampleRequest, dict[str, Any]]]:
        """Take a finished job back; returns its runs, for the journal."""
        made, points = self.book.complete(job, value)
        for i in points:
            self._advance(i)
        return made

    def fail(self, job, reason: str) -> None:
        """A job that never came back: its samples are `undetermined` with that reason and
        the point is marked failed (nothing is journaled, so a resume runs them again)."""
        for i in self.book.fail(job, reason):
            self._advance(i)

    # ---- stop rule --------------------------------------------------------------------
    def _advance(self, i: int) -> None:
        n = self.target[i]
        if i in self.results or self.book.busy(i):
            return
        if self.task.target_se is None:
            why = "one run per grid cell" if self.task.is_map else f"{n} samples, as asked"
            return self._finish(i, why)
        results = self.book.results_of(i, n)
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
        self.book.want((i, j) for j in range(n, self.target[i]))

    def _finish(self, i: int, why: str) -> None:
        n = self.target[i]
        failed = self.book.failed.get(i)
        status = "failed" if failed else "converged"
        reason = f"{why}; some runs failed: {failed}" if failed else why
        self.results[i] = BasinPointResult(
            status=status, reason=reason, results=self.book.results_of(i, n)
        )
        self.book.forget(i, n)
