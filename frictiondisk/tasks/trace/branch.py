"""One traced curve and the branches that extend it: predict, correct, control the step.

A `Curve` is a list of certified points in *loop order*: the sticking side lies on the
left of that direction (a rising jump in mu is walked towards larger keys, a falling one
towards smaller keys), so one orientation holds across folds. Each curve has two ends;
a `Branch` extends one of them, step after step (BifurcationKit's ContinuationPar, with a
certified bisection across the curve as the corrector):

* predict the next point ds along the curve (trace_steps.predict);
* correct it by a certified bisection across the curve: in mu at the predicted key where
  the curve is flatter than 45 degrees in scaled units, else in the key at the predicted
  mu (plane.line_bisection), starting from the predicted bracket and widening within
  a few steps of it, never further (another curve must not be taken for this one);
* grow ds (x GROW, up to `max_step`) when the prediction held its bracket and the curve
  bends little; shrink it (x SHRINK) when the correction failed, had to widen, or the
  curve turned by more than MAX_TURN; a point that turned by more than 2 MAX_TURN is
  dropped and the step retried shorter;
* where the predicted point leaves the plane, the last correction is made on the plane's
  edge and the branch ends there;
* at `min_step`, a failing correction means the curve turns back sharply (a corner of a
  sticking window or gap, where two jumps meet): two searches along the direction of
  travel, one from the head's sticking end and one from its other end, find the other
  side of the wedge; the nearer one becomes the next point (`turn`).

Pure Python: a branch hands out `LineSearch`es (frictiondisk.tasks.trace.plane) and reads their
results once they are done; the tracer (frictiondisk.tasks.trace.tracer) runs them.
"""

from __future__ import annotations

import math

from frictiondisk.tasks.trace.curve import Curve, CurvePoint, clearance
from frictiondisk.tasks.trace.plane import (
    LineBracket,
    LineSearch,
    failure,
    found_bracket,
    line_bisection,
)
from frictiondisk.tasks.trace.steps import (
    GROW,
    MAX_TURN,
    SAGITTA,
    SHRINK,
    Plane,
    Prediction,
    Vec,
    add,
    curvature,
    exit_point,
    left_normal,
    norm,
    on_edge,
    predict,
    quadratic,
    sub,
    unit,
)

LIMIT_STEPS = 4.0  # a correction may widen this many bracket half-widths (or a step) away
TURN_REACH = 4.0  # a turn search spans this many min_steps along the direction of travel
# a quadratic through three points each within tol / 2 extrapolates one spacing ahead
# with weights (1, -3, 3): up to 3.5 tol off from their uncertainty alone
NOISE = 3.5


class Branch:
    """Extends one end of `curve` (+1: its last point, in loop direction; -1: its first)."""

    def __init__(self, curve: Curve, end: int, plane: Plane, task, heading: Vec):
        self.curve = curve
        self.end = end
        self.plane = plane
        self.task = task
        self.heading = heading  # direction of travel while the stretch has one point
        self.ds = task.first_step
        self.stretch = 1  # points of the current stretch (since the seed or the last turn)
        self.state = "active"
        self.reason = ""
        self.kind = ""  # what the searches of this round are: step, edge, refine or turn
        self.searches: list[LineSearch] = []
        self.prediction = None
        self.edge_fraction = 1.0
        self._turn_next = False  # the next step is a turn (a failure at min_step)
        self._refine: tuple[CurvePoint, CurvePoint] | None = None  # a chord too far off
        self._kept: set[tuple[int, int]] = set()  # chords whose refinement found no jump
        self._at_edge = False  # reached the plane's edge (stops once nothing is refined)

    @property
    def active(self) -> bool:
        return self.state == "active"

    def history(self) -> list[Vec]:
        return [p.position for p in self.curve.travel(self.end, min(3, self.stretch))]

    def direction(self) -> Vec:
        """The direction of travel at the head (scaled)."""
        points = self.history()
        return unit(sub(points[-1], points[-2])) if len(points) > 1 else self.heading

    def stop(self, state: str, reason: str = "") -> None:
        self.state = state
        self.reason = reason
        self.curve.ends[self.end] = f"{state}: {reason}" if reason else state

    # ---- one step ----------------------------------------------------------------------
    def start(self, cap: float | None = None, curves: list[Curve] = ()) -> list[LineSearch]:
        """The searches of this branch's next step (none once it has stopped); `curves`:
        every curve traced so far, whose points its correction keeps clear of."""
        self.searches = []
        if not self.active:
            return []
        if self._turn_next:
            self._turn_next = False
            self._start_turn()
            return self.searches
        if self._refine is not None:
            self.searches = [self._refinement(curves)]
            return self.searches
        if len(self.curve.points) >= self.task.max_points:
            self.stop("limit", f"max_points = {self.task.max_points} reached")
            return []
        history = self.history()
        head = history[-1]
        ds = self.ds if cap is None else max(self.task.min_step, min(self.ds, cap))
        self.prediction = predict(history, self.heading, ds, self.plane.scaled_tol)
        if on_edge(head, self.prediction.tangent):
            self.stop("edge")
            return []
        leaving = exit_point(head, self.prediction.point)
        if leaving is None:
            self.kind = "step"
            target, tangent = self.prediction.point, self.prediction.tangent
            along = "mu" if abs(tangent[1]) <= abs(tangent[0]) else "key"
            fixed = None
        else:
            fraction, edge_axis, edge = leaving
            self.kind = "edge"
            self.edge_fraction = fraction
            target = add(head, sub(self.prediction.point, head), fraction)
            tangent = self.prediction.tangent
            # on a key edge the curve is crossed in mu, on a mu edge in the key
            along = "mu" if edge_axis == "key" else "key"
            fixed = edge
        room = clearance(target, list(curves), self.curve, self.end, 2.0 * ds)
        self.searches = [self._correction(target, tangent, along, ds, fixed, room)]
        return self.searches

    def _correction(
        self, target: Vec, tangent: Vec, along: str, ds: float, fixed, room: float
    ) -> LineSearch:
        """A certified bisection across the curve at `target` along `along`, starting from
        the predicted bracket and widening at most a step (or LIMIT_STEPS bracket
        half-widths) from it, and less than `room`: never as far as another curve."""
        normal = left_normal(tangent)
        normal = (self.end * normal[0], self.end * normal[1])  # towards the sticking side
        axis = 1 if along == "mu" else 0
        other = 1 - axis
        if fixed is not None:
            target = (fixed, target[1]) if other == 0 else (target[0], fixed)
        tol = self.plane.scaled_tol
        half = max(0.5 * tol, min(self.prediction.error, 0.45 * room))
        reach = max(half + tol, min(max(LIMIT_STEPS * half, ds), 0.9 * room))
        low, high = (max(0.0, target[axis] - reach), min(1.0, target[axis] + reach))
        lo, hi = max(low, target[axis] - half), min(high, target[axis] + half)
        if hi <= lo:  # the target lies on the plane's edge in this coordinate
            lo, hi = max(low, hi - 2 * half), min(high, lo + 2 * half)
        key, mu = self.plane.unscaled(target)
        fixed_name, value = ("key", key) if along == "mu" else ("mu", mu)
        span = self.plane.span_of(along)
        origin = self.plane.range_of(along)[0]
        bracket = (origin + lo * span, origin + hi * span)
        limits = (origin + low * span, origin + high * span)
        slope = 1.0
        if along == "key":  # the reserve's rate along the key: |d mu* / d key| (unscaled)
            ratio = abs(tangent[1] * self.plane.mu_span) / max(
                abs(tangent[0]) * self.plane.key_span, 1e-300
            )
            slope = ratio if ratio > 0 else None
        return line_bisection(
            fixed_name,
            value,
            bracket,
            limits,
            normal[axis] > 0,
            self.plane.tol_of(along),
            self.task,
            slope,
        )

    def finish(self) -> None:
        """Take the step's results (every search of this round is done)."""
        if not self.active or not self.searches:
            return
        if self.kind == "turn":
            self._finish_turn()
            return
        found = found_bracket(self.searches[0])
        if self.kind == "refine":
            a, b = self._refine
            self._refine = None
            if found is not None:
                index = max(self.curve.points.index(a), self.curve.points.index(b))
                self.curve.points.insert(index, self._point(found))
                self.stretch += 1
            else:  # the chord stays as it is: no point is guessed
                self._kept.add((id(a), id(b)))
            self._next_refinement()
            return
        if found is None:
            self._failed(failure(self.searches[0]))
            return
        point = self._point(found)
        history = self.history()
        head = history[-1]
        step = sub(point.position, head)
        ds = norm(step)
        tol = self.plane.scaled_tol
        bend = 0.0  # the turn at the head, less what the points' uncertainty can make of it
        if len(history) > 1:
            bend = curvature(history[-2], head, point.position, tol)
            bend *= 0.5 * (norm(sub(head, history[-2])) + ds)
        if bend > 2 * MAX_TURN and self.ds > self.task.min_step:
            self.ds = max(self.task.min_step, self.ds * SHRINK)  # too far for this bend
            return
        self.curve.add(self.end, point)
        self.stretch += 1
        self._at_edge = self.kind == "edge"
        # extrapolating points that lie anywhere in their brackets is off by a few tol
        # anyway (NOISE): only an error beyond that says the step was too long
        error = norm(sub(point.position, self.prediction.point))
        allowed = max(self.prediction.error, NOISE * tol)
        if bend > MAX_TURN or error > allowed:
            self.ds = max(self.task.min_step, max(ds, self.task.min_step) * SHRINK)
        elif error <= 0.5 * allowed and bend <= 0.5 * MAX_TURN:
            self.ds = min(self.task.max_step, max(ds, self.ds) * GROW)
        if len(history) > 1:  # the chord of the next step within SAGITTA tol of the curve
            kappa = curvature(history[-2], head, point.position, tol)
            if kappa > 0:
                self.ds = max(
                    self.task.min_step, min(self.ds, math.sqrt(8 * SAGITTA * tol / kappa))
                )
        self._next_refinement()

    # ---- chords too far from the curve ----------------------------------------------------
    def _next_refinement(self) -> None:
        """Refine the oldest of the last three chords whose sagitta, kappa L^2 / 8 with the
        larger curvature at its two ends, exceeds SAGITTA tol (a step made before the
        curvature was known, such as the first from a seed); stop at the edge otherwise."""
        points = self.curve.travel(self.end, min(self.stretch, 5))
        tol = self.plane.scaled_tol
        positions = [p.position for p in points]
        for j in range(max(0, len(points) - 4), len(points) - 1):
            length = norm(sub(positions[j + 1], positions[j]))
            if length <= 2 * self.task.min_step or (id(points[j]), id(points[j + 1])) in self._kept:
                continue
            kappa = (
                max(
                    curvature(*positions[k - 1 : k + 2], tol)
                    for k in (j, j + 1)
                    if 0 < k < len(positions) - 1
                )
                if len(positions) > 2
                else 0.0
            )
            if kappa * length**2 / 8 > SAGITTA * tol:
                self._refine = (points[j], points[j + 1])
                return
        if self._at_edge:
            self.stop("edge")

    def _refinement(self, curves) -> LineSearch:
        """A correction at the middle of the chord to refine, on the quadratic through it
        and its neighbour."""
        a, b = self._refine
        points = self.curve.travel(self.end, min(self.stretch, 5))
        j = points.index(a)
        three = points[j - 1 : j + 2] if j > 0 else points[j : j + 3]
        positions = [p.position for p in three]
        start = norm(sub(positions[1], positions[0])) if j > 0 else 0.0
        middle = start + 0.5 * norm(sub(b.position, a.position))
        target, tangent = quadratic(positions, middle)
        sag = norm(sub(target, add(a.position, sub(b.position, a.position), 0.5)))
        self.kind = "refine"
        self.prediction = Prediction(target, tangent, max(self.plane.scaled_tol, sag))
        along = "mu" if abs(tangent[1]) <= abs(tangent[0]) else "key"
        ds = norm(sub(b.position, a.position))
        room = clearance(target, list(curves), self.curve, self.end, 2.0 * ds + self._behind(a))
        return self._correction(target, tangent, along, 0.5 * ds, None, room)

    def _behind(self, point: CurvePoint) -> float:
        """Arclength from the branch's end back to `point`."""
        return self.curve.arclength_from(self.end)[self.curve.points.index(point)]

    def _point(self, found: LineBracket) -> CurvePoint:
        return CurvePoint(found, self.plane.scaled(found.key, found.mu))

    def _failed(self, why: str) -> None:
        if self.kind == "edge":
            # the curve turned before the edge: go on with steps that stay inside
            self.ds = max(self.task.min_step, self.edge_fraction * self.ds * SHRINK)
            return
        if self.ds > self.task.min_step:
            self.ds = max(self.task.min_step, self.ds * SHRINK * SHRINK)
            return
        if self.stretch < 2:
            self.stop("failed", f"no jump near the predicted point: {why}")
            return
        self._turn_next = True

    # ---- corners -------------------------------------------------------------------------
    def _start_turn(self) -> None:
        """Search along the direction of travel from both ends of the head's bracket."""
        head = self.curve.head(self.end).bracket
        t = self.direction()
        along = "key" if head.along == "mu" else "mu"
        axis = 0 if along == "key" else 1
        forward = 1.0 if t[axis] >= 0 else -1.0
        span = self.plane.span_of(along)
        start = head.fixed_value
        reach = TURN_REACH * self.task.min_step * span
        low, high = self.plane.range_of(along)
        far = min(high, max(low, start + forward * reach))
        widest = min(high, max(low, start + forward * LIMIT_STEPS * reach))
        if far == start:
            self.stop("failed", "the curve turns at the plane's edge")
            return
        bracket = (min(start, far), max(start, far))
        limits = (min(start, widest), max(start, widest))
        self.kind = "turn"
        self.searches = [
            # from the sticking end: the sticking side ends ahead (a window's tip)
            line_bisection(
                head.along,
                head.stick_end,
                bracket,
                limits,
                forward < 0,
                self.plane.tol_of(along),
                self.task,
                None,
            ),
            # from the other end: the free side ends ahead (a gap's tip)
            line_bisection(
                head.along,
                head.free_end,
                bracket,
                limits,
                forward > 0,
                self.plane.tol_of(along),
                self.task,
                None,
            ),
        ]

    def _finish_turn(self) -> None:
        found = [b for b in map(found_bracket, self.searches) if b is not None]
        if not found:
            reasons = "; ".join(map(failure, self.searches))
            self.stop("failed", f"lost the curve: no jump ahead and no turn ({reasons})")
            return
        head = self.curve.head(self.end)
        # the nearer side of the two (a wedge found from both ends: the tip that comes first)
        bracket = min(found, key=lambda b: abs(b.mid - head.bracket.fixed_value))
        point = self._point(bracket)
        t = self.direction()
        self.heading = (-t[0], -t[1])  # back along the other side of the wedge
        self.curve.add(self.end, point)
        self.stretch = 1
        self.ds = 2 * self.task.min_step
        self.kind = ""
