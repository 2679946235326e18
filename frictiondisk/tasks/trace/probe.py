"""One run at a point (key, mu) of the plane, retried with longer horizons until its
outcome lies on a side of the boundary searched (or the retries run out): the probes of
fold.py and the tracer. Pure Python."""

from __future__ import annotations

from typing import Any

from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK, Between
from frictiondisk.tasks.trace.plane import PlaneRequest
from frictiondisk.verdict.outcomes import UNDETERMINED


class Probe:
    """One run at (key, mu), retried with longer horizons while undetermined."""

    def __init__(
        self,
        key: float,
        mu: float,
        max_retries: int,
        strict: int = 0,
        between: Between = NOT_STICK_STICK,
    ):
        self.key, self.mu = key, mu
        self.between = between  # a run on neither side is retried like an undetermined one
        self.max_retries = max_retries
        self.strict = strict
        self.level = 0
        self.outcome: str | None = None
        self.made: list[PlaneRequest] = []

    @property
    def done(self) -> bool:
        return self.outcome is not None

    def pending(self) -> list[PlaneRequest]:
        if self.done:
            return []
        return [PlaneRequest(self.key, self.mu, self.level, self.strict)]

    def feed(self, request: PlaneRequest, result: dict[str, Any]) -> None:
        self.made.append(request)
        if self.between.side(result["outcome"]) is not None or self.level >= self.max_retries:
            self.outcome = result["outcome"]
        else:
            self.level += 1

    def abort(self, reason: str) -> None:
        if not self.done:
            self.outcome = UNDETERMINED

    def requests_made(self) -> list[PlaneRequest]:
        return list(self.made)

    @property
    def sticks(self) -> bool | None:
        if self.outcome is None or self.between.side(self.outcome) is None:
            return None
        return self.between.is_high(self.outcome)
