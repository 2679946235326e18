"""Which runs a `trace` campaign needs: the plane's tracer, behind the planner protocol.

The planner contract of frictiondisk.tasks.protocol (`requests`/`feed` answered from the
journal, `jobs`/`complete`/`fail` on Dask) and its promise: the result does not depend on
worker count, job order or timing. The tracer (frictiondisk.tasks.trace.tracer) advances
in rounds whose decisions depend on outcomes only; every run of a round that is not in
the journal goes out at once, in batches (jobs.RunScenes), so the corrections of
different curves and fold locators, and the points of a multisection round (`split`), run
in parallel.

A trace campaign has one point, its base scene; a run is a `PlaneRequest` (key value, mu,
retry and certification level), its scene the base scene with the key and mu set.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from frictiondisk.model.varied import scene_value
from frictiondisk.tasks.in_order import feed_in_order
from frictiondisk.tasks.jobs import JobTable, RunScenes, Sizing
from frictiondisk.tasks.jump_search.prescan import default_stride
from frictiondisk.tasks.jump_search.requests import run_config
from frictiondisk.tasks.protocol import Planner
from frictiondisk.tasks.trace.plane import PlaneRequest
from frictiondisk.tasks.trace.results import TraceResults
from frictiondisk.tasks.trace.steps import Plane
from frictiondisk.tasks.trace.tracer import Tracer, TraceSettings


def trace_settings(task, stick_rule: str) -> TraceSettings:
    """The tracer's settings from a campaign's `trace` task."""
    look = task.first_look
    low, high = task.range
    keys = (0.5 * (low + high),) if look.keys == 1 else np.linspace(low, high, look.keys)
    mus = tuple(float(mu) for mu in np.linspace(task.mu[0], task.mu[1], look.mu))
    stride = (
        look.stride
        if look.stride is not None
        else default_stride(len(mus), "decide", stick_rule, task.sides)
    )
    min_step = task.smallest_step
    return TraceSettings(
        plane=Plane(task.key, tuple(task.range), tuple(task.mu), task.tol),
        look_keys=tuple(float(k) for k in keys),
        look_mus=mus,
        stride=min(stride, len(mus) - 1),
        max_step=task.resolution,
        min_step=min_step,
        first_step=max(min_step, task.first_step),
        max_points=task.max_points,
        max_retries=task.max_retries,
        split=task.split,
        certify=task.certify,
        root_finder=task.root_finder,
        between=task.sides,
    )


class TracePlanner(Planner):
    """trace: one tracer over the plane of the campaign's base scene."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.task = campaign.task
        self.points = campaign.points()  # one: the base scene
        self.tracer = Tracer(trace_settings(self.task, campaign.base.numerics.stick_rule))
        self.results: dict[int, Any] = {}
        self.out: set[PlaneRequest] = set()
        self.arrived: dict[PlaneRequest, dict[str, Any]] = {}  # back, not taken yet
        self._jobs = JobTable()  # job id -> its requests (PlaneRequest)
        self._scenes: dict[float, Any] = {}  # key value -> the base scene with it set

    def config_for(self, i: int, request: PlaneRequest):
        scene = self._scenes.get(request.key)
        if scene is None:
            key = self.task.key
            scene = self.campaign.base.with_overrides({key: scene_value(key, request.key)})
            self._scenes[request.key] = scene
        return run_config(scene, request.mu_request(), self.task.horizon_factor, self.task.certify)

    @property
    def done(self) -> bool:
        return self.tracer.done

    def progress(self) -> tuple[int, int]:
        """(curve points placed, the same plus one for every search in flight): the unit
        of a trace's progress bar and status; the total grows as curves are found."""
        placed = sum(len(curve.points) for curve in self.tracer.curves)
        return placed, placed + (0 if self.done else len(self.tracer.searching()))

    def snapshot(self) -> TraceResults:
        """The trace: its result once done, else what is known so far (partial)."""
        trace = self.results[0] if self.tracer.done else self.tracer.partial()
        return TraceResults(self.campaign, tuple(self.points), trace)

    def requests(self) -> list[tuple[int, PlaneRequest]]:
        return [
            (0, r) for r in self.tracer.pending() if r not in self.out and r not in self.arrived
        ]

    def feed(self, i: int, request: PlaneRequest, result: dict[str, Any]) -> None:
        """Take a result, fed in the tracer's own order (tasks/in_order.py); one it no
        longer waits for is dropped."""
        if self.tracer.done or request not in self.tracer.pending():
            return
        feed_in_order(self.tracer, self.arrived, request, result, self._settle)

    def _settle(self) -> None:
        if not self.tracer.done:
            self.tracer.pending()  # a round whose runs the tracer knew may end here
        if self.tracer.done and 0 not in self.results:
            self.results[0] = self.tracer.result()

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[int, RunScenes]]:
        """Every run of this round nobody is computing, in batches sized like the find_jump
        planner's (None: one run per job)."""
        max_jobs = getattr(sizing, "max_jobs", None)
        limit = math.inf if max_jobs is None else max_jobs
        ready = [request for _, request in self.requests()]
        batch_runs, workers = getattr(sizing, "batch_runs", 1), getattr(sizing, "workers", 1)
        size = max(1, min(batch_runs, -(-len(ready) // max(1, workers))))
        out = []
        for start in range(0, len(ready), size):
            if len(out) >= limit:
                break
            batch = ready[start : start + size]
            self.out.update(batch)
            job = self._jobs.add(batch)
            configs = [self.config_for(0, request).canonical() for request in batch]
            out.append((job, RunScenes(tuple(configs))))
        return out

    def complete(self, job: int, value) -> list[tuple[int, PlaneRequest, dict[str, Any]]]:
        """Take a finished job back; returns the runs it made, for the journal."""
        batch = self._jobs.pop(job)
        made = []
        for request, result in zip(batch, value, strict=True):
            self.out.discard(request)
            self.feed(0, request, result)
            made.append((0, request, result))
        return made

    def split(self, job: int, work: RunScenes) -> list[tuple[int, RunScenes]]:
        return self._jobs.halve(job, work)

    def fail(self, job: int, reason: str) -> None:
        """A job that never came back (its worker kept dying): the trace ends with what
        it has, and that reason; no run is invented (a resume tries again)."""
        for request in self._jobs.pop(job):
            self.out.discard(request)
        self.tracer.abort(reason)
        self._settle()
