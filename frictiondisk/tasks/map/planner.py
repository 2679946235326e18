"""Which runs a `map` campaign needs: the cells of a coarse lattice, then the cells where
neighbours differ (cells.py), each run once from the scene's start or `samples` times from
sampled starts (frictiondisk.tasks.sampling.draws, as the basin task draws them).

The planner contract of frictiondisk.tasks.protocol: the cells asked for depend on the
motions found only (a refinement round starts once every wanted cell is known), never on
worker count, job size or the order results arrive in.
"""

from __future__ import annotations

from typing import Any

from frictiondisk.tasks.jobs import RunScenes, Sizing
from frictiondisk.tasks.map.cells import CellRefinement
from frictiondisk.tasks.map.motions import UNDETERMINED, MapCellResult, leading_motion
from frictiondisk.tasks.map.results import MapResults
from frictiondisk.tasks.protocol import Planner
from frictiondisk.tasks.sampling.draws import sample_values
from frictiondisk.tasks.sampling.runs import SampleRequest


class MapPlanner(Planner):
    """map: a motion per cell of 1 or 2 keys, refined where neighbouring cells differ."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.task = campaign.task
        self.points = campaign.points()
        self.cell_index = {p.index: i for i, p in enumerate(self.points)}
        self.results: dict[int, MapCellResult] = {}
        self.cells = CellRefinement(campaign.shape, self.task.strides())
        self.known: dict[int, dict[int, dict[str, Any]]] = {}  # point -> sample -> summary
        self.todo: set[tuple[int, int]] = set()  # (point, sample) wanted, not known, not out
        self.out: dict[int, int] = {}  # point -> its runs out on a worker
        self.failed: dict[int, str] = {}  # point -> why a job of it never came back
        self._jobs: dict[tuple[int, int], list[tuple[int, int]]] = {}
        self._blocks: dict[int, dict] = {}  # point -> its draw blocks (a sampled start)
        self._want(self.cells.wanted)

    # ---- cells and their runs ----------------------------------------------------------
    def _want(self, cells) -> None:
        for cell in cells:
            i = self.cell_index[cell]
            self.todo |= {(i, j) for j in range(self.task.runs_per_cell)}

    def start_values(self, i: int, j: int) -> dict[str, float]:
        """The sampled initial state of run j of cell i ({} from the scene's own start)."""
        if not self.task.sampled:
            return {}
        blocks = self._blocks.setdefault(i, {})
        return sample_values(self.task, self.points[i].coords, j, blocks)

    def config_for(self, i: int, request: SampleRequest):
        values = self.start_values(i, request.index)
        point = self.points[i].config
        return point.with_overrides(values) if values else point

    # ---- planner protocol -------------------------------------------------------------
    @property
    def done(self) -> bool:
        return not self.todo and not any(self.out.values()) and not self.cells.waiting

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
        return [(i, SampleRequest(j)) for i, j in sorted(self.todo)]

    def feed(self, i: int, request: SampleRequest, result: dict[str, Any]) -> None:
        """Take a result; one the cell no longer waits for is ignored."""
        if (i, request.index) not in self.todo:
            return
        self._take(i, request.index, result)
        self._advance([i])

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[tuple[int, int], RunScenes]]:
        """Every requested run not yet out, sizing.batch_runs to a job (1 without)."""
        per_job = max(1, sizing.batch_runs) if sizing is not None else 1
        wanted = sorted(self.todo)
        out = []
        for start in range(0, len(wanted), per_job):
            items = wanted[start : start + per_job]
            self._jobs[items[0]] = items
            for i, j in items:
                self.todo.discard((i, j))
                self.out[i] = self.out.get(i, 0) + 1
            scenes = [self.config_for(i, SampleRequest(j)).canonical() for i, j in items]
            out.append((items[0], RunScenes(tuple(scenes))))
        return out

    def complete(self, job, value) -> list[tuple[int, SampleRequest, dict[str, Any]]]:
        """Take a finished job back; returns its runs, for the journal."""
        items = self._jobs.pop(job)
        made = []
        for (i, j), result in zip(items, value, strict=True):
            self.out[i] -= 1
            self._take(i, j, result)
            made.append((i, SampleRequest(j), result))
        self._advance(sorted({i for i, _ in items}))
        return made

    def fail(self, job, reason: str) -> None:
        """A job that never came back: its runs are `undetermined` with that reason and its
        cells failed (nothing is journaled, so a resume runs them again)."""
        items = self._jobs.pop(job)
        for i, j in items:
            self.out[i] -= 1
            self._take(i, j, {"outcome": UNDETERMINED, "reason": reason})
            self.failed[i] = reason
        self._advance(sorted({i for i, _ in items}))

    # ---- a cell's motion, and the refinement -------------------------------------------
    def _take(self, i: int, j: int, result: dict[str, Any]) -> None:
        self.known.setdefault(i, {})[j] = result
        self.todo.discard((i, j))

    def _advance(self, points: list[int]) -> None:
        """Finish every cell of `points` whose runs are all known; once no cell waits, the
        next refinement round."""
        n = self.task.runs_per_cell
        for i in points:
            runs = self.known.get(i, {})
            if i in self.results or len(runs) < n or self.out.get(i):
                continue
            results = tuple(runs[j] for j in range(n))
            failed = self.failed.get(i)
            self.results[i] = MapCellResult(
                status="failed" if failed else "converged",
                reason=f"a job failed: {failed}" if failed else "every run of the cell ran",
                results=results,
            )
            self.cells.settle(self.points[i].index, leading_motion(results))
        if not self.cells.waiting:
            self._want(self.cells.refine())
