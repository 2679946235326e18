"""The geometry of a traced plane and the predictor of a curve's next point. Pure Python.

A plane spans a scene key over [k0, k1] and mu over [m0, m1]. Steps, angles and distances
are measured in *scaled* coordinates x = (key - k0) / (k1 - k0), y = (mu - m0) / (m1 - m0),
so that a curve is followed the same way whatever the units of its key. tol (in mu) is
tol / (m1 - m0) scaled; a bracket in the key has the same scaled width, tol (k1 - k0) /
(m1 - m0) in the key's unit.

The predictor (BifurcationKit's tangent predictor, with a secant for a tangent): from the
last points of a curve, parameterized by their arclength s, the next point at s + ds is
extrapolated linearly from the last two, or quadratically from the last three. The
difference between the two is the prediction's error estimate (as the warm start of
find_jump/planner.py uses it across a line). A step's chord stays within SAGITTA tol of the
curve (kappa ds^2 / 8 with the curvature kappa from three points): the polyline through a
curve's points is then as good as its points, for interpolation between them.
"""

from __future__ import annotations

import dataclasses
import math

Vec = tuple[float, float]

GROW = 1.5  # step factor after a correction that held its predicted bracket
SHRINK = 0.5  # step factor after a correction that failed or had to widen
MAX_TURN = 0.35  # [rad] largest change of direction per step before the step shrinks
# bracket half-width: this x |quadratic - linear| (find_jump/planner.py's warm start)
ERROR_FACTOR = 2.0
SECANT_SLACK = 0.25  # bracket half-width of a secant step, in units of ds (a bend of ~14 deg)
SAGITTA = 1.0  # a step's chord may deviate this many tol from the curve (kappa ds^2 / 8)


@dataclasses.dataclass(frozen=True)
class Plane:
    """The (key, mu) rectangle of a trace and its tolerance (tol: bracket width in mu)."""

    key: str
    key_range: tuple[float, float]
    mu_range: tuple[float, float]
    tol: float

    @property
    def key_span(self) -> float:
        return self.key_range[1] - self.key_range[0]

    @property
    def mu_span(self) -> float:
        return self.mu_range[1] - self.mu_range[0]

    @property
    def scaled_tol(self) -> float:
        return self.tol / self.mu_span

    @property
    def key_tol(self) -> float:
        """Bracket width of a search in the key: tol at the same scaled width."""
        return self.scaled_tol * self.key_span

    def tol_of(self, along: str) -> float:
        return self.tol if along == "mu" else self.key_tol

    def span_of(self, along: str) -> float:
        return self.mu_span if along == "mu" else self.key_span

    def range_of(self, along: str) -> tuple[float, float]:
        return self.mu_range if along == "mu" else self.key_range

    def scaled(self, key: float, mu: float) -> Vec:
        return (
            (key - self.key_range[0]) / self.key_span,
            (mu - self.mu_range[0]) / self.mu_span,
        )

    def unscaled(self, point: Vec) -> tuple[float, float]:
        """(key, mu) of a scaled point."""
        return (
            self.key_range[0] + point[0] * self.key_span,
            self.mu_range[0] + point[1] * self.mu_span,
        )


def sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1])


def add(a: Vec, b: Vec, scale: float = 1.0) -> Vec:
    return (a[0] + scale * b[0], a[1] + scale * b[1])


def norm(a: Vec) -> float:
    return math.hypot(a[0], a[1])


def unit(a: Vec) -> Vec:
    length = norm(a)
    return (a[0] / length, a[1] / length) if length > 0 else (0.0, 0.0)


def angle(a: Vec, b: Vec) -> float:
    """Angle [rad] between two directions (0 ... pi)."""
    na, nb = norm(a), norm(b)
    if na == 0 or nb == 0:
        return 0.0
    cos = (a[0] * b[0] + a[1] * b[1]) / (na * nb)
    return math.acos(max(-1.0, min(1.0, cos)))


def left_normal(t: Vec) -> Vec:
    """t turned by +90 degrees."""
    return (-t[1], t[0])


@dataclasses.dataclass(frozen=True)
class Prediction:
    """The predicted next point (scaled), the tangent there, and how far off it may be
    (scaled; the half-width of the bracket the correction starts from)."""

    point: Vec
    tangent: Vec
    error: float


def quadratic(points: list[Vec], s: float) -> tuple[Vec, Vec]:
    """The point and unit tangent at arclength s (from points[0]) of the quadratic in
    arclength through three points (Lagrange)."""
    p0, p1, p2 = points
    s1 = norm(sub(p1, p0))
    s2 = s1 + norm(sub(p2, p1))
    w = (
        (s - s1) * (s - s2) / (s1 * s2),
        s * (s - s2) / (s1 * (s1 - s2)),
        s * (s - s1) / (s2 * (s2 - s1)),
    )
    d = (
        ((s - s1) + (s - s2)) / (s1 * s2),
        (2 * s - s2) / (s1 * (s1 - s2)),
        (2 * s - s1) / (s2 * (s2 - s1)),
    )
    point = tuple(sum(w[k] * points[k][i] for k in range(3)) for i in range(2))
    slope = tuple(sum(d[k] * points[k][i] for k in range(3)) for i in range(2))
    return point, unit(slope)


def predict(history: list[Vec], heading: Vec, ds: float, tol: float) -> Prediction:
    """The next point at arclength ds beyond history[-1] (history: the last points of the
    current stretch, oldest first, scaled). With one point: along `heading`, error ds (an
    unknown slope up to 1); two: the secant, error SECANT_SLACK ds; three: the quadratic in
    arclength, error ERROR_FACTOR |quadratic - linear|. Never less than tol / 2."""
    head = history[-1]
    if len(history) == 1:
        t = unit(heading)
        return Prediction(add(head, t, ds), t, max(0.5 * tol, ds))
    t = unit(sub(head, history[-2]))
    linear = add(head, t, ds)
    p0, p1, p2 = ([history[0]] + history)[-3:]
    if len(history) == 2 or norm(sub(p1, p0)) == 0 or norm(sub(p2, p1)) == 0:
        return Prediction(linear, t, max(0.5 * tol, SECANT_SLACK * ds))
    quad, tangent = quadratic([p0, p1, p2], norm(sub(p1, p0)) + norm(sub(p2, p1)) + ds)
    if tangent == (0.0, 0.0):
        tangent = t
    error = ERROR_FACTOR * norm(sub(quad, linear))
    return Prediction(quad, tangent, max(0.5 * tol, error))


def curvature(a: Vec, b: Vec, c: Vec, tol: float) -> float:
    """The curve's curvature at b from its neighbours a and c (scaled), less what the
    points' own uncertainty (tol / 2 each) can make of it: the turning angle at b minus
    2 tol / (the shorter segment), over the mean segment length; 0 if that is negative."""
    before, after = sub(b, a), sub(c, b)
    shorter = max(min(norm(before), norm(after)), tol)
    turn = max(0.0, angle(before, after) - 2.0 * tol / shorter)
    return turn / max(0.5 * (norm(before) + norm(after)), tol)


def exit_point(head: Vec, target: Vec) -> tuple[float, str, float] | None:
    """Where the segment head -> target leaves the unit square: (fraction of the segment,
    the edge's coordinate "key" (x = 0 or 1) or "mu" (y = 0 or 1), its value 0 or 1); None
    if target lies inside."""
    best = None
    for axis, coordinate in ((0, "key"), (1, "mu")):
        for edge in (0.0, 1.0):
            outside = target[axis] < edge if edge == 0.0 else target[axis] > edge
            if not outside or head[axis] == target[axis]:
                continue
            fraction = (edge - head[axis]) / (target[axis] - head[axis])
            if 0.0 <= fraction <= 1.0 and (best is None or fraction < best[0]):
                best = (fraction, coordinate, edge)
    return best


def on_edge(point: Vec, direction: Vec) -> bool:
    """Whether `point` lies on the square's boundary with `direction` pointing out."""
    eps = 1e-12
    return (
        (point[0] <= eps and direction[0] < 0)
        or (point[0] >= 1 - eps and direction[0] > 0)
        or (point[1] <= eps and direction[1] < 0)
        or (point[1] >= 1 - eps and direction[1] > 0)
    )
