"""Which runs a `map` campaign needs: the cells of a coarse lattice, then the cells where
neighbours differ (cells.py), each run once from the scene's start or `samples` times from
sampled starts (frictiondisk.tasks.sampling.draws, as the basin task draws them). Which
runs are wanted, out or known, and the jobs that carry them, are the run book's
(frictiondisk.tasks.sampling.run_book, shared with the basin task): linear in the runs.

The planner contract of frictiondisk.tasks.protocol: the cells asked for depend on the
motions found only (a refinement round starts once every wanted cell is known), never on
worker count, job size or the order results arrive in.
"""

from __future__ import annotations

from frictiondisk.tasks.map.cells import CellRefinement
from frictiondisk.tasks.map.motions import MapCellResult, leading_motion
from frictiondisk.tasks.map.results import MapResults
from frictiondisk.tasks.sampling.run_book import RunBook, RunBookPlanner

JOB_RUNS = 1  # runs per job without the driver's sizing (tests, a direct use)


class MapPlanner(RunBookPlanner):
    """map: a motion per cell of 1 or 2 keys, refined where neighbouring cells differ."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.task = campaign.task
        self.points = campaign.points()
        self.cell_index = {p.index: i for i, p in enumerate(self.points)}
        self.results: dict[int, MapCellResult] = {}
        self.cells = CellRefinement(campaign.shape, self.task.strides())
        self.book = RunBook(self.task, self.points, JOB_RUNS)
        self._want(self.cells.wanted)

    # ---- cells and their runs ----------------------------------------------------------
    def _want(self, cells) -> None:
        points = sorted(self.cell_index[cell] for cell in cells)
        self.book.want((i, j) for i in points for j in range(self.task.runs_per_cell))

    # ---- planner protocol -------------------------------------------------------------
    @property
    def done(self) -> bool:
        return self.book.open_runs == 0 and not self.cells.waiting

    def progress(self) -> tuple[int, int]:
        """(cells known: run, or inferred once the map is complete; cells)."""
        inferred = len(self.cells.inferred()) if self.done else 0
        return len(self.results) + inferred, len(self.points)

    def snapshot(self) -> MapResults:
        """What the planner has found so far: every cell run, and (once the map is
        complete) the cells inferred from uniform blocks."""
        results = tuple(self.results.get(i) for i in range(len(self.points)))
        inferred = {}
        if self.done:
            inferred = {self.cell_index[c]: m for c, m in self.cells.inferred().items()}
        return MapResults(self.campaign, tuple(self.points), results, inferred)

    # ---- a cell's motion, and the refinement -------------------------------------------
    def _advance(self, points: list[int]) -> None:
        """Finish every cell of `points` whose runs are all known; once no cell waits, the
        next refinement round."""
        n = self.task.runs_per_cell
        for i in points:
            if i in self.results or self.book.busy(i) or len(self.book.known[i]) < n:
                continue
            results = self.book.results_of(i, n)
            failed = self.book.failed.get(i)
            self.results[i] = MapCellResult(
                status="failed" if failed else "converged",
                reason=f"a job failed: {failed}" if failed else "every run of the cell ran",
                results=results,
            )
            self.cells.settle(self.points[i].index, leading_motion(results))
            self.book.forget(i, n)
        if not self.cells.waiting:
            self._want(self.cells.refine())
