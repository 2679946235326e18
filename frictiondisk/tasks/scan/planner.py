"""Which runs a `scan` campaign needs: one run per grid point (pure Python; the planner
contract is frictiondisk.tasks.protocol.Planner)."""

from __future__ import annotations

import math
from typing import Any

from frictiondisk.tasks.jobs import RunScenes, Sizing
from frictiondisk.tasks.jump_search.runs import RunRequest
from frictiondisk.tasks.protocol import Planner
from frictiondisk.tasks.scan.results import ScanResults


class ScanPlanner(Planner):
    """scan: one run per grid point (mu and at most one more parameter), no bisection."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.points = campaign.points()
        self.results: dict[int, dict[str, Any]] = {}
        self.busy: set[int] = set()

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

    def requests(self) -> list[tuple[int, RunRequest]]:
        return [
            (i, RunRequest(p.config.params.mu))
            for i, p in enumerate(self.points)
            if i not in self.results and i not in self.busy
        ]

    def feed(self, i: int, request: RunRequest, result: dict[str, Any]) -> None:
        self.results.setdefault(i, result)

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[int, RunScenes]]:
        """One job per point not yet known: a single (long, converge-mode) run; at most
        sizing.max_jobs of them."""
        limit = math.inf if sizing is None or sizing.max_jobs is None else sizing.max_jobs
        out = []
        for i, point in enumerate(self.points):
            if len(out) >= limit:
                break
            if i in self.results or i in self.busy:
                continue
            self.busy.add(i)
            out.append((i, RunScenes((point.config.canonical(),))))
        return out

    def complete(self, i: int, value) -> list[tuple[int, RunRequest, dict[str, Any]]]:
        (result,) = value
        self.busy.discard(i)
        self.results[i] = result
        return [(i, RunRequest(self.points[i].config.params.mu), result)]

    def fail(self, i: int, reason: str) -> None:
        """A run whose worker kept dying: reported `undetermined` with that reason (it is
        not journaled, so a resume tries again)."""
        self.busy.discard(i)
        self.results[i] = {"outcome": "undetermined", "reason": reason}
