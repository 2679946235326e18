"""Where traced pieces of one curve meet: joins and closed curves. Pure Python.

Every seed of a trace grows a piece of curve at both ends, so a curve that crosses several
first-look keys is traced from several seeds at once, towards each other. An end that has
come within one step (`max_step`, scaled) of a point of a piece, heading the same way
along the curve (directions in loop order within 60 degrees; loop order keeps the sticking
side on the left, so a nearby curve with the other orientation is a different jump), is
joined to it: the two pieces become one, and the part of the other piece beyond the
meeting point, which retraces what this end has just traced, is dropped. An end that
meets its own piece far enough behind closes the curve.

Two ends heading towards each other get their steps capped so that they stop about half a
step apart and join in the next round, rather than pass each other.
"""

from __future__ import annotations

import math

from frictiondisk.tasks.trace.branch import Branch
from frictiondisk.tasks.trace.curve import Curve
from frictiondisk.tasks.trace.steps import Vec, norm, sub, unit

JOIN_COS = 0.5  # directions in loop order agree within 60 degrees


def loop_direction(branch: Branch) -> Vec:
    """The branch's direction of travel in loop order (a backward end travels against it)."""
    t = branch.direction()
    return (branch.end * t[0], branch.end * t[1])


def tangent(curve: Curve, j: int) -> Vec:
    """The curve's direction in loop order at its point j (central difference)."""
    points = curve.points
    a, b = points[max(0, j - 1)].position, points[min(len(points) - 1, j + 1)].position
    return unit(sub(b, a))


def find_join(branch: Branch, curves: list[Curve], reach: float) -> tuple[Curve, int] | None:
    """The point (curve, index) that the end of `branch` meets, if any: the nearest one
    within `reach` ahead of it, heading the same way (own piece: only beyond 3 reach of
    arclength behind the end), with no point heading another way nearer than it (a jump
    of the other orientation between them: they are different curves)."""
    head = branch.curve.head(branch.end).position
    forward, travel = loop_direction(branch), branch.direction()
    best, barrier = None, math.inf
    for curve in curves:
        behind = curve.arclength_from(branch.end) if curve is branch.curve else None
        for j, point in enumerate(curve.points):
            if behind is not None and behind[j] <= 3.0 * reach:
                continue
            between = sub(point.position, head)
            gap = norm(between)
            if gap > reach:
                continue
            t = tangent(curve, j)
            if forward[0] * t[0] + forward[1] * t[1] < JOIN_COS:
                barrier = min(barrier, gap)
            elif between[0] * travel[0] + between[1] * travel[1] >= 0:
                if best is None or gap < best[0]:
                    best = (gap, curve, j)
    if best is None or best[0] >= barrier:
        return None
    return best[1], best[2]


def join(branch: Branch, target: Curve, j: int, branches: list[Branch], curves: list[Curve]):
    """Connect the end of `branch` to point j of `target`; returns the curve that is gone
    (None if the curve closed)."""
    piece = branch.curve
    if target is piece:
        piece.points = piece.points[j:] if branch.end > 0 else piece.points[: j + 1]
        piece.closed = True
        for other in branches:
            if other.curve is piece and other.active:
                other.stop("closed")
        return None
    branch.stop("joined")
    if branch.end > 0:
        piece.points = piece.points + target.points[j:]
    else:
        piece.points = target.points[: j + 1] + piece.points
    piece.ends[branch.end] = target.ends[branch.end]
    for other in branches:
        if other.curve is target:
            if other.end != branch.end and other.active:
                other.stop("joined")  # it was retracing this branch's path
            other.curve = piece  # the end that goes on, if active, extends the joined curve
    curves.remove(target)
    return target


def approach_caps(branches: list[Branch], reach: float, min_step: float) -> dict[int, float]:
    """Step caps (by id of the branch) for a forward and a backward end heading towards each
    other closer than their next steps and `reach`: each may go (gap - reach / 2) / 2."""
    caps: dict[int, float] = {}
    ends = [b for b in branches if b.active]
    for a in (b for b in ends if b.end > 0):
        for b in (b for b in ends if b.end < 0):
            if a.curve is b.curve and len(a.curve.points) < 3:
                continue
            fa, fb = loop_direction(a), loop_direction(b)
            if fa[0] * fb[0] + fa[1] * fb[1] < JOIN_COS:
                continue
            between = sub(b.curve.head(-1).position, a.curve.head(+1).position)
            if between[0] * fa[0] + between[1] * fa[1] <= 0:
                continue  # b lies behind a: they move apart
            gap = norm(between)
            if reach < gap <= a.ds + b.ds + reach:
                cap = max(min_step, 0.5 * (gap - 0.5 * reach))
                caps[id(a)] = min(caps.get(id(a), math.inf), cap)
                caps[id(b)] = min(caps.get(id(b), math.inf), cap)
    return caps
