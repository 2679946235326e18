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

from typing import Any

from frictiondisk.tasks.jobs import RunScenes, Sizing
from frictiondisk.tasks.map.cells import CellRefinement
from frictiondisk.tasks.map.motions import MapCellResult, leading_motion
from frictiondisk.tasks.map.results import MapResults
from frictiondisk.tasks.protocol import Planner
from frictiondisk.tasks.sampling.run_book import RunBook
from frictiondisk.tasks.sampling.runs import SampleRequest

JOB_RUNS = 1  # runs per job without the driver's sizing (tests, a direct use)


class MapPlanner(Planner):
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

    def start_values(self, i: int, j: int) -> dict[str, float]:
        """The sampled initial state of run j of cell i ({} from the scene's own start)."""
        return self.book.sample_values(i, j)

    def config_for(self, i: int, request: SampleRequest):
        return self.book.config_for(i, request)

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

    def requests(self) -> list[tuple[int, SampleRequest]]:
        return self.book.requests()

    def new_requests(self) -> list[tuple[int, SampleRequest]]:
        """The runs asked for since the last call (each once), still wanted."""
        return self.book.new_requests()

    def remember_canonical(self, i: int, request: SampleRequest, canonical: dict) -> None:
        self.book.remember_canonical(i, request, canonical)

    def feed(self, i: int, request: SampleRequest, result: dict[str, Any]) -> None:
        """Take a result; one the cell no longer waits for is ignored."""
        if self.book.take(i, request.index, result):
            self._advance([i])

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[tuple[int, int], RunScenes]]:
        """Requested runs not yet out, in the order asked (RunBook.jobs)."""
        return self.book.jobs(sizing)

    def complete(self, job, value) -> list[tuple[int, SampleRequest, dict[str, Any]]]:
        """Take a finished job back; returns its runs, for the journal."""
        made, points = self.book.complete(job, value)
        self._advance(points)
        return made

    def fail(self, job, reason: str) -> None:
        """A job that never came back: its runs are `undetermined` with that reason and its
        cells failed (nothing is journaled, so a resume runs them again)."""
        self._advance(self.book.fail(job, reason))

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
