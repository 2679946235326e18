"""Searches along one line of a (key, mu) plane, for the trace task. Pure Python.

A traced plane (frictiondisk.tasks.trace.tracer) is searched along straight lines: at fixed key
over mu (a find_jump line), or at fixed mu over the key, where a jump curve is steep in mu.
Every run is a `PlaneRequest` (key value, mu, retry and certification level).

`LineSearch` turns any search of one coordinate (a `CertifiedBisection`, a `JumpSearch`:
`pending`, `feed`, `done`, `result` over `RunRequest`s) into a search of the plane. The
searched coordinate c maps to the line as key = sign c (fixed mu) or mu = sign c (fixed
key). `line_bisection` builds a certified bisection on such a line whose stick end lies
at the high end of c, whatever the line: a falling jump in mu (stick below) is bisected in
c = -mu, a key at which the stick side lies below in c = -key. The bisection and its
certification (frictiondisk.tasks.jump_search.certify) then run unchanged: the same checks, the same
widening, the same ladder.

The friction reserve (frictiondisk/verdict/reserve.py) the interpolating root finder aims
with is positive where the slave sticks and changes about as fast as mu - mu*. On a line it
is handed on as r / slope, with `slope` the rate at which it changes along the line (1
along mu; |d mu*/d key| along the key, from the curve's tangent), so that it stays close
to c - c* with slope 1, positive on the stick side (the high end of c). Where that does
not hold (a falling jump, a reserve biased by a brake), its sign disagrees with the
verdict and the bisection ignores it (bisection.Bisection._agrees).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from frictiondisk.model.search_settings import OFF
from frictiondisk.tasks.jump_search.bisection import BisectionResult, RunRequest
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.certify import CertifiedBisection
from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK


@dataclasses.dataclass(frozen=True)
class PlaneRequest:
    """One run of a traced plane: the key's value, mu, retry level and certification level
    (as in bisection.RunRequest)."""

    key: float
    mu: float
    level: int = 0
    strict: int = 0
    mode: str | None = None
    watch: float = 0.0
    reach: int = 0
    own_method: bool = False

    def mu_request(self) -> RunRequest:
        """The same run as a RunRequest of its point (the scene with the key set)."""
        return RunRequest(
            self.mu, self.level, self.mode, self.strict, self.watch, self.reach, self.own_method
        )


@dataclasses.dataclass(frozen=True)
class Line:
    """A line of the plane: `fixed` names the coordinate held ("key" or "mu") at `value`;
    the searched coordinate is c = sign x (the other coordinate x). `slope`: how fast the
    friction reserve changes with x along the line (> 0; None: hand no reserve on)."""

    fixed: str
    value: float
    sign: float = 1.0
    slope: float | None = 1.0

    @property
    def along(self) -> str:
        """The coordinate searched: "mu" or "key"."""
        return "mu" if self.fixed == "key" else "key"

    def to_plane(self, request: RunRequest) -> PlaneRequest:
        x = self.sign * request.mu
        key, mu = (self.value, x) if self.fixed == "key" else (x, self.value)
        return PlaneRequest(
            key,
            mu,
            request.level,
            request.strict,
            request.mode,
            request.watch,
            request.reach,
            request.own_method,
        )

    def coordinate(self, x: float) -> float:
        """c of the plane coordinate x along the line."""
        return self.sign * x

    def signal(self, result: dict[str, Any]) -> dict[str, Any]:
        """The run summary with its reserve scaled to the line (see the module docstring)."""
        reserve = result.get("reserve")
        if reserve is None or self.slope == 1.0:
            return result
        if self.slope is None or not math.isfinite(reserve):
            return {**result, "reserve": None}
        return {**result, "reserve": reserve / self.slope}


class LineSearch:
    """A one-coordinate search (`pending`/`feed`/`done`/`result`/`abort` over RunRequests)
    run along `line` of the plane."""

    def __init__(self, search, line: Line):
        self.search = search
        self.line = line
        self._inner: dict[PlaneRequest, RunRequest] = {}

    @property
    def done(self) -> bool:
        return self.search.done

    def pending(self) -> list[PlaneRequest]:
        out = []
        for request in self.search.pending():
            plane = self.line.to_plane(request)
            self._inner[plane] = request
            out.append(plane)
        return out

    def feed(self, request: PlaneRequest, result: dict[str, Any]) -> None:
        self.search.feed(self._inner[request], self.line.signal(result))

    def abort(self, reason: str) -> None:
        self.search.abort(reason)

    def result(self):
        return self.search.result()


@dataclasses.dataclass(frozen=True)
class LineBracket:
    """What a converged line bisection found, in plane coordinates: the jump between `lo`
    and `hi` of the coordinate `along` (lo < hi) at the fixed other coordinate; stick at hi
    when `stick_high`."""

    along: str
    fixed_value: float
    lo: float
    hi: float
    stick_high: bool
    result: BisectionResult

    @property
    def mid(self) -> float:
        return 0.5 * (self.lo + self.hi)

    @property
    def width(self) -> float:
        return self.hi - self.lo

    @property
    def stick_end(self) -> float:
        return self.hi if self.stick_high else self.lo

    @property
    def free_end(self) -> float:
        """The end that does not stick."""
        return self.lo if self.stick_high else self.hi

    @property
    def key(self) -> float:
        return self.fixed_value if self.along == "mu" else self.mid

    @property
    def mu(self) -> float:
        return self.mid if self.along == "mu" else self.fixed_value

    @property
    def certification(self) -> str:
        return self.result.certification


def line_bisection(
    fixed: str,
    value: float,
    bracket: tuple[float, float],
    limits: tuple[float, float],
    stick_high: bool,
    tol: float,
    settings,
    slope: float | None = 1.0,
    strict: int = 0,
) -> LineSearch:
    """A certified bisection along the line where `fixed` ("key" or "mu") = `value`, over
    `bracket` of the other coordinate (widened within `limits`), with stick expected at
    the bracket's high end when `stick_high`. `settings` carries max_retries, split,
    certify and root_finder (a campaign task). Its runs are at certification level
    `strict` (a fold repaired at stricter numerics, fold.py), its checks one above."""
    sign = 1.0 if stick_high else -1.0
    line = Line(fixed, value, sign, slope)
    lo, hi = sorted(line.coordinate(x) for x in bracket)
    low, high = sorted(line.coordinate(x) for x in limits)
    rules = BisectionSettings(
        tol,
        (min(low, lo), max(high, hi)),
        settings.max_retries,
        rising=True,
        split=settings.split,
        strict=strict,
        root_finder=settings.root_finder,
        between=getattr(settings, "between", NOT_STICK_STICK),
    )
    search = CertifiedBisection((lo, hi), rules, certify=getattr(settings, "certify", OFF))
    return LineSearch(search, line)


def found_bracket(search: LineSearch) -> LineBracket | None:
    """The plane bracket of a finished line bisection; None unless it converged to a jump
    that counts (not vanished, not failed)."""
    found = search.result()
    if found.status != "converged" or found.certification in ("vanished", "failed"):
        return None
    line = search.line
    a, b = line.sign * found.mu_lo, line.sign * found.mu_hi
    return LineBracket(line.along, line.value, min(a, b), max(a, b), line.sign > 0, found)


def failure(search: LineSearch) -> str:
    """Why a line search found no jump, with the line it searched (its reason speaks of
    `mu`, the searched coordinate c, which is -mu or +-key on some lines)."""
    line = search.line
    names = {"key": "the key", "mu": "mu"}
    sign = "" if line.sign > 0 else "-"
    return (
        f"on {names[line.fixed]} = {line.value:.10g}, c = {sign}{names[line.along]}: "
        f"{search.result().reason}"
    )
