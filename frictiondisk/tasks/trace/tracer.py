"""Trace every jump curve through a (key, mu) plane (the `trace` task). Pure Python.

`Tracer` is a state machine like `Bisection` (`pending`, `feed`, `done`, `result`): it asks
for runs (`PlaneRequest`s) and takes their summaries; it knows nothing of simulation, files
or Dask, so the same object drives a live campaign and its replay from the journal.

1. **First look.** Every key value of `first_look` is searched in mu like a find_jump
   point with a prescan (jump_search.jumps.JumpSearch: adaptive prescan, every stick / not-stick
   change bisected and certified). Each jump found is a *seed*: a certified point of a curve.
2. **Tracing.** From each seed a `Curve` grows at both ends (branch.Branch:
   predict, correct by a certified bisection across the curve, control the step), until
   it leaves the plane, closes, meets another curve's end (two seeds of one curve: the
   pieces are joined), fails, or reaches max_points.
3. **Folds.** Where a curve turns back in the key (a smooth bend, or a corner passed by a
   turn), a `FoldLocator` (fold.py) brackets the tip where the two jumps meet, to tol
   in both coordinates.

It advances in *rounds*: every branch and every fold locator has one step (one search, or
two) in a round, all of them run together (their runs may run in parallel), and only when
all are done does the tracer look at them, in a fixed order (curve, end; fold). Joins,
turns and new steps thus depend only on outcomes, never on the order results arrive in or
on the number of workers.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.tasks.jump_search.jumps import JumpSearch, run_role
from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK, Between
from frictiondisk.tasks.trace.branch import Branch
from frictiondisk.tasks.trace.curve import Curve, CurvePoint
from frictiondisk.tasks.trace.fold import Fold, FoldLocator
from frictiondisk.tasks.trace.joins import approach_caps, find_join, join
from frictiondisk.tasks.trace.plane import Line, LineBracket, LineSearch, PlaneRequest
from frictiondisk.tasks.trace.probe import Probe
from frictiondisk.tasks.trace.steps import Plane


@dataclasses.dataclass(frozen=True)
class TraceSettings:
    """What the tracer needs of a trace task (tasks/trace/spec.Trace builds it)."""

    plane: Plane
    look_keys: tuple[float, ...]  # key values of the first look
    look_mus: tuple[float, ...]  # its prescan values of mu
    stride: int  # adaptive prescan stride (1: dense)
    max_step: float  # scaled: the resolution
    min_step: float
    first_step: float
    max_points: int  # per curve
    max_retries: int
    split: int
    certify: Any
    root_finder: str
    between: Between = NOT_STICK_STICK  # the boundary's two sides (jump_search/sides.py)


@dataclasses.dataclass(frozen=True)
class TracedRun:
    """One run of a trace, in schedule order: what it was for and its summary."""

    request: PlaneRequest
    result: dict[str, Any]
    role: str  # prescan, search or certification
    purpose: str  # first_look, curve or fold


@dataclasses.dataclass(frozen=True)
class TraceResult:
    status: str  # "converged": the first look and every curve ended normally; else "failed"
    reason: str
    curves: tuple[Curve, ...]
    folds: tuple[tuple[int, Fold], ...]  # (curve id, fold)
    runs: tuple[TracedRun, ...]
    look: tuple[tuple[float, Any], ...]  # (key, JumpSearchResult) of the first look


class Tracer:
    """Find and follow every jump curve of the plane (see the module docstring)."""

    def __init__(self, settings: TraceSettings):
        self.settings = settings
        self.plane = settings.plane
        self.known: dict[PlaneRequest, dict[str, Any]] = {}
        self.runs: list[TracedRun] = []
        self._logged: set[PlaneRequest] = set()
        self.curves: list[Curve] = []
        self.branches: list[Branch] = []
        self.locators: list[tuple[int, FoldLocator]] = []
        self.folds: list[tuple[int, Fold]] = []
        self._folded: set[int] = set()  # ids of the points whose fold is being located
        self.look: list[tuple[float, LineSearch]] = []
        self.round = 0
        self._current: list[tuple[str, Any]] = []  # (purpose, search) of this round
        self._finished = False
        self._failure: str | None = None
        for key in settings.look_keys:
            search = JumpSearch(
                settings.look_mus,
                self.plane.tol,
                settings.max_retries,
                None,
                settings.split,
                settings.certify,
                settings.root_finder,
                settings.stride,
                between=settings.between,
            )
            self.look.append((key, LineSearch(search, Line("key", key))))
        self._current = [("first_look", s) for _, s in self.look]

    # ---- the state machine ---------------------------------------------------------------
    @property
    def done(self) -> bool:
        return self._finished

    def pending(self) -> list[PlaneRequest]:
        """Every run this round still needs (runs already known are answered at once)."""
        while True:
            wanted = self._wanted()
            answered = [r for r in wanted if r in self.known]
            if not answered:
                if not wanted and not self._finished:
                    self._end_round()
                    continue
                return wanted
            for request in answered:
                self._route(request, self.known[request])

    def searching(self) -> list[Any]:
        """The searches of this round still running."""
        return [search for _, search in self._current if not search.done]

    def _wanted(self) -> list[PlaneRequest]:
        out: list[PlaneRequest] = []
        for _, search in self._current:
            if not search.done:
                out += [r for r in search.pending() if r not in out]
        return out

    def feed(self, request: PlaneRequest, result: dict[str, Any]) -> None:
        if request not in self._wanted():
            raise ValueError(f"unexpected run {request}")
        self.known[request] = result
        self._route(request, result)

    def _route(self, request: PlaneRequest, result: dict[str, Any]) -> None:
        for _, search in self._current:
            if not search.done and request in search.pending():
                search.feed(request, result)

    def abort(self, reason: str) -> None:
        """End without more runs (e.g. the runs of this round kept killing their worker)."""
        self._failure = reason
        for _, search in self._current:
            search.abort(reason)
        self._log_round()  # the runs the round made before it ended
        for branch in self.branches:
            if branch.active:
                branch.stop("failed", reason)
        self._current = []
        self._finished = True

    # ---- rounds ----------------------------------------------------------------------------
    def _end_round(self) -> None:
        self._log_round()
        if self.round == 0:
            self._seed()
        else:
            for branch in self.branches:
                branch.finish()
            for ident, locator in self.locators:
                locator.finish()
                if locator.done:
                    self.folds.append((ident, locator.result()))
            self.locators = [(i, loc) for i, loc in self.locators if not loc.done]
        caps = self._join()
        self._find_folds()
        self.round += 1
        self._current = []
        for branch in self.branches:
            searches = branch.start(caps.get(id(branch)), self.curves)
            self._current += [("curve", s) for s in searches]
        for ident, locator in self.locators:
            self._current += [("fold", s) for s in locator.start()]
            if locator.done:  # it ended without another search
                self.folds.append((ident, locator.result()))
        self.locators = [(i, loc) for i, loc in self.locators if not loc.done]
        if not self._current:
            self._finished = True

    def _log_round(self) -> None:
        """Keep every run of this round's searches, in the round's fixed order."""
        for purpose, search in self._current:
            for request, role in _made(search):
                if request not in self._logged and request in self.known:
                    self._logged.add(request)
                    self.runs.append(TracedRun(request, self.known[request], role, purpose))

    def _seed(self) -> None:
        """One curve per jump of the first look, growing at both ends; not the two edges of
        a window narrower than the persistence width (jump_search/jumps.py: no tol-wide corridor
        between them to follow; the first look reports it)."""
        for key, search in self.look:
            found = search.result()
            narrow = {m for w in found.windows if w.narrow for m in (w.lo, w.hi)}
            for jump in found.jumps:
                if jump.status != "converged" or jump.certification in ("vanished", "failed"):
                    continue
                if jump.mu_star in narrow:
                    continue
                bracket = LineBracket("mu", key, jump.mu_lo, jump.mu_hi, jump.rising, jump)
                point = CurvePoint(bracket, self.plane.scaled(bracket.key, bracket.mu))
                curve = Curve(len(self.curves), point)
                self.curves.append(curve)
                heading = (1.0, 0.0) if jump.rising else (-1.0, 0.0)  # sticking side on the left
                for end in (+1, -1):
                    direction = (end * heading[0], end * heading[1])
                    self.branches.append(Branch(curve, end, self.plane, self.settings, direction))

    # ---- folds -----------------------------------------------------------------------------
    def _find_folds(self) -> None:
        """A locator for every new point where a curve turns back in the key (a closed
        curve is read from a point halfway between its extremes, round to that point)."""
        for curve in self.curves:
            points = curve.points
            if curve.closed and len(points) > 2:
                xs = [point.position[0] for point in points]
                middle = 0.5 * (min(xs) + max(xs))
                first = min(range(len(xs)), key=lambda j: abs(xs[j] - middle))
                points = points[first:] + points[: first + 1]
            xs = [point.position[0] for point in points]
            for index, tip in key_turns(xs, self.plane.scaled_tol):
                point = points[index]
                if id(point) not in self._folded and 0 < index < len(xs) - 1:
                    self._folded.add(id(point))
                    self._locate(curve, points, index, tip)

    def _locate(self, curve: Curve, points: list[CurvePoint], index: int, tip: float) -> None:
        """Start a FoldLocator at the tip near points[index] (an extreme of the key,
        towards `tip`): inside the region a little back from the tip, between the curve's
        two sides there. Loop order keeps the sticking side on the left: a curve that
        passes a tip at larger keys going up has the region between its sides on its left,
        so that region sticks (a window); going down, it does not (a gap)."""
        point, before, after = points[index], points[index - 1], points[index + 1]
        inner_sticks = (tip > 0) == (after.position[1] > before.position[1])
        bracket = point.bracket
        near = min(abs(bracket.key - before.bracket.key), abs(bracket.key - after.bracket.key))
        back = max(4.0 * self.plane.key_tol, 0.25 * near)
        key_in = bracket.key - tip * back
        sides = [_mu_along(points, index, step, key_in) for step in (-1, 1)]
        mu_in = 0.5 * (sides[0] + sides[1]) if None not in sides else bracket.mu
        # the two jumps' slopes near the tip, for the locator's first predictions
        deeper = key_in - tip * back
        inner = [_mu_along(points, index, step, deeper) for step in (-1, 1)]
        slopes = None
        if None not in sides and None not in inner:
            pairs = sorted(zip(sides, inner, strict=True))  # the lower jump first
            slopes = tuple((a - b) / (key_in - deeper) for a, b in pairs)
        if bracket.along == "key":  # its end beyond the tip: a run outside the region
            key_out = bracket.free_end if inner_sticks else bracket.stick_end
        else:
            key_out = bracket.key + tip * back
        if (key_out - key_in) * tip <= 0:
            key_out = key_in + tip * self.plane.key_tol
        widths = [abs(m - mu_in) for m in sides if m is not None]
        half = 2.0 * max(widths) if widths else self.plane.tol
        locator = FoldLocator(
            self.plane, self.settings, key_in, mu_in, inner_sticks, tip, key_out, half, slopes
        )
        self.locators.append((curve.id, locator))

    # ---- joins -----------------------------------------------------------------------------
    def _join(self) -> dict[int, float]:
        """Join every end that meets a piece of its own curve (trace_joins); returns the
        step caps of ends about to meet."""
        reach = self.settings.max_step
        for branch in self.branches:
            found = find_join(branch, self.curves, reach) if branch.active else None
            if found is not None:
                gone = join(branch, *found, self.branches, self.curves)
                if gone is not None:
                    kept = branch.curve.id

                    def renamed(items, gone_id=gone.id, kept=kept):
                        return [(kept if i == gone_id else i, item) for i, item in items]

                    self.folds = renamed(self.folds)
                    self.locators = renamed(self.locators)
        return approach_caps(self.branches, reach, self.settings.min_step)

    # ---- the answer ------------------------------------------------------------------------
    def result(self) -> TraceResult:
        if not self.done:
            raise ValueError("trace not finished")
        problems = []
        if self._failure:
            problems.append(self._failure)
        for key, search in self.look:
            found = search.result()
            # a key where every prescan run is decided and none changes has no curve: fine
            sides = self.settings.between
            quiet = not found.jumps and all(sides.side(r.outcome) is not None for r in found.scan)
            if found.status != "converged" and not quiet:
                problems.append(f"first look at key {key:.6g}: {found.reason}")
        number = {curve.id: n for n, curve in enumerate(self.curves)}  # as in results.nc
        for curve in self.curves:
            for end, why in curve.ends.items():
                if why.startswith("failed"):
                    side = "last" if end > 0 else "first"
                    problems.append(f"curve {number[curve.id]} ({side} end) {why}")
        status = "failed" if problems else "converged"
        # a fold not located leaves the curves whole: noted, flagged in results.nc
        problems += [
            f"fold on curve {number.get(ident, '?')} not located: {fold.reason}"
            for ident, fold in self.folds
            if fold.status != "located"
        ]
        reason = "; ".join(problems) if status == "failed" else self._summary()
        if status == "converged" and problems:
            reason += "; " + "; ".join(problems)
        look = tuple((key, search.result()) for key, search in self.look)
        return TraceResult(
            status, reason, tuple(self.curves), tuple(self.folds), tuple(self.runs), look
        )

    def _summary(self) -> str:
        points = sum(len(c.points) for c in self.curves)
        return (
            f"{len(self.curves)} curve(s), {points} points, {len(self.folds)} fold(s), "
            f"{len(self.runs)} runs"
        )

    def partial(self) -> TraceResult:
        """What is known so far (for partial results): the curves as traced until now."""
        look = tuple((key, search.result()) for key, search in self.look if search.done)
        return TraceResult(
            "pending",
            "not finished yet",
            tuple(self.curves),
            tuple(self.folds),
            tuple(self.runs),
            look,
        )


def _made(search) -> list[tuple[PlaneRequest, str]]:
    """(plane request, role) of every run a finished (or aborted) search made."""
    if isinstance(search, Probe):
        return [(r, "certification" if r.strict else "search") for r in search.requests_made()]
    found = search.result()
    role = getattr(found, "role", run_role)
    return [(search.line.to_plane(run.request), role(run.request)) for run in found.runs]


def _mu_along(points: list[CurvePoint], index: int, step: int, key: float) -> float | None:
    """mu of the curve where it crosses `key`, walking from points[index] by `step`
    (linear between the two points that straddle it); None if it does not within the list."""
    j = index
    while 0 <= j + step < len(points):
        a, b = points[j].bracket, points[j + step].bracket
        if (a.key - key) * (b.key - key) <= 0 and a.key != b.key:
            return a.mu + (b.mu - a.mu) * (key - a.key) / (b.key - a.key)
        j += step
    return None


def key_turns(xs: list[float], threshold: float) -> list[tuple[int, float]]:
    """(index, +1 or -1) of every point where the sequence xs turns back: a maximum
    (+1) or minimum (-1) from which it moves back by more than `threshold` (a zigzag
    filter: reversals within the positions' noise do not count)."""
    turns: list[tuple[int, float]] = []
    lo = hi = anchor = 0
    direction = 0
    for j in range(1, len(xs)):
        if direction == 0:
            lo = j if xs[j] < xs[lo] else lo
            hi = j if xs[j] > xs[hi] else hi
            if xs[hi] - xs[lo] > threshold:
                direction = 1 if hi > lo else -1
                anchor = hi if direction > 0 else lo
        elif direction * (xs[j] - xs[anchor]) > 0:
            anchor = j
        elif direction * (xs[anchor] - xs[j]) > threshold:
            turns.append((anchor, float(direction)))
            direction, anchor = -direction, j
    return turns
