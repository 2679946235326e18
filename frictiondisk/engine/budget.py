"""A campaign's size before it starts: points, runs and driver memory.

`estimate` counts without building a single point, so a campaign of 10^8 points is refused
in milliseconds instead of growing until memory runs out. `check` returns one line per
limit exceeded, naming the field that makes the campaign that big; `run --force` skips it.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

from frictiondisk.tasks.campaign import Campaign

__all__ = ["MAX_POINTS", "MAX_RUNS", "Estimate", "check", "estimate", "memory_limit"]

MAX_POINTS = 100_000  # grid points of one campaign (building 10^5 points takes ~30 s)
MAX_RUNS = 1_000_000  # runs of one campaign, retries not counted
# Driver memory, measured (tracemalloc, 2000-point line): 5.0 kB per point (its scene and
# planner state); a run's journal inputs, result and key add about as much again.
BYTES_PER_POINT = 5_000
BYTES_PER_RUN = 8_000


@dataclass(frozen=True)
class Estimate:
    """points: grid points; runs: runs without retries (a lower bound when jumps are
    prescanned); memory: bytes the driver holds for them."""

    points: int
    runs: int
    memory: int
    fields: str  # the fields that set the size, e.g. "find_jump.along.params.x_ms"

    def describe(self) -> str:
        return (
            f"{self.points} points, at least {self.runs} runs, "
            f"about {_bytes(self.memory)} of driver memory"
        )


def estimate(campaign: Campaign) -> Estimate:
    """Size of `campaign` from its axes alone (no point is built)."""
    points = math.prod(campaign.shape) if campaign.shape else 1
    per_point, fields = campaign.entry.size(campaign.task)
    runs = points * per_point
    return Estimate(points, runs, points * BYTES_PER_POINT + runs * BYTES_PER_RUN, fields)


def memory_limit() -> int:
    """Half of this machine's physical memory [bytes]."""
    try:
        return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE") // 2
    except (ValueError, OSError):
        return 4 << 30


def check(campaign: Campaign) -> list[str]:
    """One line per limit the campaign exceeds (empty: it fits)."""
    size = estimate(campaign)
    problems = []
    if size.points > MAX_POINTS:
        problems.append(
            f"{size.fields}: {size.points} points; the limit is {MAX_POINTS} per campaign"
        )
    if size.runs > MAX_RUNS:
        problems.append(
            f"{size.fields}: at least {size.runs} runs; the limit is {MAX_RUNS} per campaign"
        )
    if size.memory > memory_limit():
        problems.append(
            f"{size.fields}: needs about {_bytes(size.memory)} of driver memory; the limit "
            f"is half of this machine's memory, {_bytes(memory_limit())}"
        )
    return problems


def _bytes(n: int) -> str:
    for unit, scale in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= scale:
            return f"{n / scale:.3g} {unit}"
    return f"{n} B"
