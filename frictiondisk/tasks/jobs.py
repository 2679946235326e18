"""The work a planner hands out, as descriptions (what to run, never how): independent runs
(`RunScenes`), a search advanced run after run on one worker (`RunSearch`) and a recorded
run (`RunRecorded`); and `Sizing`, how the driver wants work cut. frictiondisk.engine.worker
executes them (on Dask or in this process) and returns what each job's docstring names."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import Any


@dataclasses.dataclass(frozen=True)
class Sizing:
    """How the driver wants work cut into jobs (performance only: results never depend
    on it). batch_runs: independent runs per job; chain_s: time budget [s] of a job that
    advances one search step after step (None: no chains, every run is its own unit);
    max_jobs: most jobs to hand out now; workers: how many share the runs out now."""

    batch_runs: int = 1
    chain_s: float | None = None
    max_jobs: int | None = None
    workers: int = 1


@dataclasses.dataclass(frozen=True)
class RunScenes:
    """Simulate each scene (`SceneConfig.canonical()`), in order. Returns the list of their
    result summaries (`SimulationResult.summary()`)."""

    scenes: tuple[dict[str, Any], ...]


@dataclasses.dataclass(frozen=True)
class RunSearch:
    """Advance `search` (a frictiondisk.tasks.protocol.Search) one run after the other:
    its first pending run, whose scene is `scene_of(request)`, fed back before the next;
    to its end, or until it has run for `budget_s` seconds. A run the campaign's journal
    already holds is read, not computed. Returns (search, [(request, summary), ...] of the
    runs computed)."""

    search: Any
    scene_of: Callable[[Any], Any]  # request -> SceneConfig; picklable
    budget_s: float | None = None


@dataclasses.dataclass(frozen=True)
class RunRecorded:
    """Simulate the scene with its trajectory recorded every `dt_out` [s]. Returns the
    SimulationResult."""

    scene: dict[str, Any]
    dt_out: float


Job = RunScenes | RunSearch | RunRecorded


def halves(items: Sequence[Any], job: RunScenes) -> list[tuple[list[Any], RunScenes]]:
    """A batch of two or more runs cut in two: (its items, the batch of their scenes) for
    each half; `items` (what a planner keeps of each run) are parallel to job.scenes."""
    if len(items) != len(job.scenes) or len(items) < 2:
        raise ValueError(f"cannot halve {len(items)} items of a batch of {len(job.scenes)}")
    half = len(items) // 2
    return [
        (list(items[:half]), RunScenes(job.scenes[:half])),
        (list(items[half:]), RunScenes(job.scenes[half:])),
    ]


class JobTable:
    """The jobs a planner has out: job id -> what it keeps of each job (its points, its
    requests), ids counted up from 0 in the order the jobs are made."""

    def __init__(self) -> None:
        self._kept: dict[int, Any] = {}
        self._next = 0

    def add(self, kept: Any) -> int:
        """A new job keeping `kept`; its id."""
        job, self._next = self._next, self._next + 1
        self._kept[job] = kept
        return job

    def __getitem__(self, job: int) -> Any:
        return self._kept[job]

    def pop(self, job: int) -> Any:
        """What job `job` kept; the job is forgotten."""
        return self._kept.pop(job)

    def halve(self, job: int, work: RunScenes) -> list[tuple[int, RunScenes]]:
        """A failed batch whose kept items are parallel to work.scenes, as the jobs of its
        halves under new ids (`halves`); the old id is forgotten."""
        return [(self.add(items), half) for items, half in halves(self.pop(job), work)]
