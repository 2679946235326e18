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

from frictiondisk.tasks.basin import stats as basin_stats
from frictiondisk.tasks.basin.results import BasinResults
from frictiondisk.tasks.basin.sampling import STICK, UNDETERMINED, BasinPointResult
from frictiondisk.tasks.sampling.run_book import RunBook, RunBookPlanner

JOB_RUNS = 16  # runs per job without the driver's sizing (tests, a direct use)


class BasinPlanner(RunBookPlanner):
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
        self.book.want((i, j) for i in range(len(self.points)) for j in range(first))

    # ---- samples ----------------------------------------------------------------------
    def sample_values(self, i: int, j: int) -> dict[str, float]:
        """The sampled initial-state values of sample j at point i."""
        return self.book.sample_values(i, j)

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

    # ---- stop rule --------------------------------------------------------------------
    def _advance(self, points: list[int]) -> None:
        for i in points:
            self._advance_point(i)

    def _advance_point(self, i: int) -> None:
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
