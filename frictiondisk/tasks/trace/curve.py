"""A traced jump curve: its certified points in loop order (the sticking side on the
left), why each of its two ends stopped, and how near a point lies to the curves traced
so far (`clearance`). Branches (branch.py) extend a curve; joins.py and the tracer close
and join them. Pure Python."""

from __future__ import annotations

import dataclasses
import math

from frictiondisk.tasks.trace.plane import LineBracket
from frictiondisk.tasks.trace.steps import Vec, norm, sub


@dataclasses.dataclass(frozen=True)
class CurvePoint:
    """A certified point of a curve: its bracket and where it lies (scaled)."""

    bracket: LineBracket
    position: Vec


class Curve:
    """A jump curve: points in loop order (sticking side on the left), and why each end
    stopped (`ends[+1]` the last point's end, `ends[-1]` the first's)."""

    def __init__(self, ident: int, seed: CurvePoint):
        self.id = ident
        self.points: list[CurvePoint] = [seed]
        self.ends: dict[int, str] = {+1: "", -1: ""}
        self.closed = False

    def add(self, end: int, point: CurvePoint) -> None:
        if end > 0:
            self.points.append(point)
        else:
            self.points.insert(0, point)

    def travel(self, end: int, count: int) -> list[CurvePoint]:
        """The last `count` points towards `end`, in the order that end travels."""
        if end > 0:
            return self.points[-count:]
        return list(reversed(self.points[:count]))

    def head(self, end: int) -> CurvePoint:
        return self.points[-1] if end > 0 else self.points[0]

    def arclength_from(self, end: int) -> list[float]:
        """Arclength (scaled) from the end `end` to each point."""
        points = [p.position for p in self.points]
        order = range(len(points) - 1, -1, -1) if end > 0 else range(len(points))
        out = [0.0] * len(points)
        total, last = 0.0, None
        for j in order:
            if last is not None:
                total += norm(sub(points[j], points[last]))
            out[j] = total
            last = j
        return out


def clearance(point: Vec, curves: list[Curve], own: Curve, end: int, behind: float) -> float:
    """Distance (scaled) from `point` to the nearest point of a curve, not counting the
    points of `own` within arclength `behind` of its end `end`: how far a correction near
    `point` may reach without meeting another jump."""
    nearest = math.inf
    for curve in curves:
        skip = curve.arclength_from(end) if curve is own else None
        for j, other in enumerate(curve.points):
            if skip is None or skip[j] > behind:
                nearest = min(nearest, norm(sub(other.position, point)))
    return nearest
