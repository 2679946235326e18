"""The contracts between a task and the shared machinery (typing.Protocol):

* `Search`: an ask/tell state machine over runs (a Bisection, CertifiedBisection,
  JumpSearch, Tracer): `pending()` names the runs it needs now, `feed()` takes their
  summaries back in the order of `pending()`, `result()` is its answer once `done`. It
  knows nothing of simulation, files or Dask, so the same object drives a live campaign,
  its replay from the journal and a chain on a worker (engine/worker.py).
* `Planner`: which runs a whole campaign needs (requests answered from the journal, jobs
  for the rest), and its results as a public snapshot with the netCDF files they make
  (tasks/results.py). Its decisions depend on outcomes only, never on the order they
  arrive in, the worker count or the job sizes: 1 and 16 workers give identical files.

A planner subclasses `Planner` for the defaults of the optional methods."""

from __future__ import annotations

from collections.abc import Hashable
from typing import Any, Protocol

from frictiondisk.tasks.jobs import Job, Sizing
from frictiondisk.tasks.results import TaskResults


class Search(Protocol):
    """One search over runs (ask/tell); requests are hashable values (a RunRequest...)."""

    @property
    def done(self) -> bool: ...

    def pending(self) -> list[Any]:
        """The runs needed before the search can move on (empty when done)."""
        ...

    def feed(self, request: Any, result: dict[str, Any]) -> None:
        """Take the summary of a run it asked for."""
        ...

    def abort(self, reason: str) -> None:
        """End as failed without more runs (e.g. its worker kept dying)."""
        ...

    def result(self) -> Any:
        """The answer (once done)."""
        ...


class Planner(Protocol):
    """Which runs one campaign needs, and what they found.

    The driver (engine/driver.py) first answers `requests()` from the journal (`feed`),
    then hands out `jobs(sizing)` (frictiondisk.tasks.jobs) and gives each back to
    `complete`, which returns the runs the job made for the journal (a job that never
    came back: `fail`). `points[i]` is point i of the campaign; `results` maps each
    finished point to its result."""

    campaign: Any
    points: list[Any]
    results: dict[int, Any]

    @property
    def done(self) -> bool: ...

    def config_for(self, point: int, request: Hashable) -> Any:
        """The scene (SceneConfig) of a requested run: its journal key's input."""
        ...

    def requests(self) -> list[tuple[int, Hashable]]:
        """(point, request) of every run needed now that nobody is computing."""
        ...

    def feed(self, point: int, request: Hashable, result: dict[str, Any]) -> None:
        """Take a run's summary the journal held."""
        ...

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[Hashable, Job]]:
        """(job id, job) of the work the journal could not answer, cut as `sizing` asks."""
        ...

    def complete(self, job: Hashable, value: Any) -> list[tuple[int, Any, dict[str, Any]]]:
        """Take a finished job back; returns (point, request, summary) of the runs it made."""
        ...

    def fail(self, job: Hashable, reason: str) -> None:
        """A job that never came back (its worker kept dying): its points fail with that
        reason; no run is invented, nothing is journaled (a resume tries again)."""
        ...

    def progress(self) -> tuple[int, int]:
        """(done, total) in the planner's own unit (points; a trace: curve points)."""
        ...

    def snapshot(self) -> TaskResults:
        """What is found so far, as a public record with its netCDF files."""
        ...

    # ---- optional: the defaults ------------------------------------------------------
    def points_failed(self) -> int:
        """Finished points that failed (their result's status)."""
        return sum(1 for r in self.results.values() if getattr(r, "status", "") == "failed")

    def runs_saved(self) -> int:
        """Runs saved by warm starts (0: the task has none)."""
        return 0

    def new_requests(self) -> list[tuple[int, Hashable]] | None:
        """(point, request) of the runs needed that no earlier call named, each once
        (None: the planner does not track them; the driver lists `requests()` again).
        A planner that names them lets the driver's replay cost O(1) per run instead of a
        pass over every pending request after each finished job."""
        return None

    def split(self, job: Hashable, work: Job) -> list[tuple[Hashable, Job]] | None:
        """A failed batch of two or more runs (`work`, a RunScenes) as the jobs of its
        halves, each under a new id, the old id forgotten; the driver submits them so that
        a run that keeps failing fails alone (None: not split, the job is retried whole)."""
        return None

    def remember_canonical(self, point: int, request: Hashable, canonical: dict) -> None:
        """A run's canonical scene the driver built for its key (a planner may keep it)."""

    def canonical_for(self, point: int, request: Hashable) -> dict:
        """A requested run's canonical scene (`config_for(...).canonical()`), which the
        driver keys and journals; a planner that made it for the run's job hands that
        one over (each run's scene is made once)."""
        return self.config_for(point, request).canonical()

    def already_written(self) -> None:
        """A task without a journal: its files are current, nothing to run."""
