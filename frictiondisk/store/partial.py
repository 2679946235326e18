"""Partial results: a planner's finished points, with placeholders for the rest.

A campaign that is stopped (Ctrl-C, SIGTERM) or still running writes results.nc from what
it has: `with_pending(kind, planner)` gives the dataset builders a view of the planner in
which every unfinished point has a `pending` result (status "pending", NaN mu*, no
runs). The file says so in its attributes: `partial` = 1 and `points_done`. Pure Python.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

PENDING = "pending"
PENDING_REASON = "not finished yet: partial results (frictiondisk resume DIR continues)"


@dataclasses.dataclass(frozen=True)
class PendingJump:
    """The placeholder of an unfinished find_jump point (reads like a JumpSearchResult)."""

    status: str = PENDING
    reason: str = PENDING_REASON
    mu_lo: float = math.nan
    mu_hi: float = math.nan
    monotone: bool = False
    certification: str = PENDING
    runs: tuple = ()
    jumps: tuple = ()
    scan: tuple = ()
    checks: tuple = ()
    windows: tuple = ()
    grid_below: None = None
    primary: None = None
    strict: int = 0

    def end_result(self, which: str) -> None:
        return None

    def role(self, request) -> str:
        return "search"


def pending_result(kind: str) -> Any:
    """The placeholder result of an unfinished point of a `kind` campaign."""
    if kind == "find_jump":
        return PendingJump()
    if kind == "basin":
        from frictiondisk.search.basin_sampling import BasinPointResult

        return BasinPointResult(status=PENDING, reason=PENDING_REASON, results=[])
    return {"outcome": "", "reason": PENDING_REASON}


class _Results(dict):
    def __init__(self, finished: dict, placeholder: Any):
        super().__init__(finished)
        self.placeholder = placeholder

    def __missing__(self, key):
        return self.placeholder


class PendingView:
    """`planner` with a pending result for every point it has not finished."""

    def __init__(self, kind: str, planner):
        self._planner = planner
        self.results = _Results(planner.results, pending_result(kind))

    def __getattr__(self, name: str) -> Any:
        return getattr(self._planner, name)


def with_pending(kind: str, planner) -> PendingView:
    return PendingView(kind, planner)
