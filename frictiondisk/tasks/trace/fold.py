"""Where two jumps meet: locate the tip of a sticking window (or gap) in the plane. Pure Python.

A sticking window is the set of mu between a rising jump (below) and a falling jump
(above) at one key; where the two jumps meet, the curve they form turns back in the key
(a *fold*: smooth, with both jumps vertical there, or a corner). A gap is the same with
stick and not stick swapped. `FoldLocator` brackets the tip in the key:

* at `key_in` the inner region exists: both jumps are bisected in mu there (line
  bisections from a run known to lie inside, widening outwards only);
* at `key_out` it does not: a run at the inner region's predicted centre gives the outer
  verdict (both jumps extrapolated linearly, with slopes from the last two windows or
  from the traced curve near the tip; the centre is kept inside the last window: a
  window narrows towards its tip, so the windows nest);
* a probe between them (aimed where the squared width, linear near a smooth fold,
  extrapolates to (tol / 2)^2, kept within the middle 80 % of the bracket) moves one of the
  two, until key_out - key_in <= the key's tolerance and the window at key_in is at most tol
  wide. The tip is then known to tol in both coordinates: its key within [key_in,
  key_out], its mu within the two jumps' brackets at key_in.

It starts from a point inside the region (checked first). Certification, once located: the
two jumps at key_in are certified (find_jump's ladder), and one probe a key tolerance
beyond key_in, at the next certification level, must give the outer verdict (the
reported key bracket is then [key_in, that key]: tol wide); the fold's certification is
the weakest of the three. Where that probe still gives the inner verdict, the tip lies
further out at stricter numerics: while a stricter level is left, the search goes on from
the probe (it lies inside) with every run at that level; where a jump at key_in vanishes
there, the tip lies further in: it is located again at that level between the start point
and key_in. Either is checked one level above (`recertified`); at the last level the fold
is `uncertain`. A tip that lies beyond the plane, two jumps that stay apart (the window
ends abruptly), or a search that fails, is reported `not located` with the reason.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from frictiondisk.model.search_settings import OFF
from frictiondisk.tasks.jump_search.certify import point_certification
from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK
from frictiondisk.tasks.trace.plane import (
    LineBracket,
    failure,
    found_bracket,
    line_bisection,
)
from frictiondisk.tasks.trace.probe import Probe
from frictiondisk.tasks.trace.steps import Plane

MAX_PROBES = 60  # probes of one fold before it is given up


class _Uncertified:
    """A task's search settings without certification (the windows on the way)."""

    certify = OFF

    def __init__(self, task):
        self._task = task

    def __getattr__(self, name: str):
        return getattr(self._task, name)


AIM_CLIP = 0.1  # a probe lies at least this fraction of the key bracket inside it
EDGE_REACH = 8.0  # an edge's bracket may widen to this many initial half-widths


@dataclasses.dataclass(frozen=True)
class Fold:
    """The tip where two jumps meet: between key_in (inner region present) and key_out
    (absent); lower and upper are the two jumps at key_in (mu brackets)."""

    status: str  # "located" or "not located"
    reason: str
    key_in: float
    key_out: float
    lower: LineBracket | None
    upper: LineBracket | None
    inner_sticks: bool
    certification: str

    @property
    def key(self) -> float:
        return 0.5 * (self.key_in + self.key_out)

    @property
    def mu(self) -> float:
        """The centre of the inner region at key_in (NaN without both jumps)."""
        if self.lower is None or self.upper is None:
            return math.nan
        return 0.5 * (self.lower.hi + self.upper.lo)

    @property
    def mu_lo(self) -> float:
        return math.nan if self.lower is None else self.lower.lo

    @property
    def mu_hi(self) -> float:
        return math.nan if self.upper is None else self.upper.hi


class FoldLocator:
    """Brackets the tip of an inner region (a window if `inner_sticks`, else a gap) that
    exists at `key_in` (a run at (key_in, mu_in) gave the inner verdict) and closes
    towards `tip` (+1: larger keys). `key_out`: a first guess of a key beyond the tip;
    `half`: a first guess of the distance in mu from mu_in to each jump."""

    def __init__(
        self,
        plane: Plane,
        task,
        key_in: float,
        mu_in: float,
        inner_sticks: bool,
        tip: float,
        key_out: float,
        half: float,
        slopes: tuple[float, float] | None = None,
    ):
        self.plane, self.task = plane, task
        self.inner_sticks = inner_sticks
        self.tip = 1.0 if tip > 0 else -1.0
        self.key_in, self.mu_in = key_in, mu_in
        self.key_out = key_out
        self.out_known = False
        self.half = max(half, plane.tol)
        self.slopes = slopes  # d mu / d key of the lower and the upper jump near the tip
        self.windows: list[tuple[float, LineBracket, LineBracket]] = []  # (key, lower, upper)
        self.searches: list[Any] = []
        self.phase = "start"  # start (is (key_in, mu_in) inner?), edges, probe, check
        self.probes = 0
        self.result_fold: Fold | None = None
        self._probe_key = math.nan
        self._probe_mu = math.nan
        self.strict = 0  # certification level of its searches (raised by a repair)
        self._start = (key_in, mu_in, self.half)  # where it started: inside, far from the tip

    @property
    def done(self) -> bool:
        return self.result_fold is not None

    # ---- one round -----------------------------------------------------------------------
    def start(self) -> list[Any]:
        """The searches of this round (the two jumps at key_in, or one probe)."""
        if self.phase == "probe":
            self._choose_probe()  # may end the search, or go on to the final check
        if self.done:
            return []
        if self.phase == "start":
            self.searches = [self._probe(self.key_in, self.mu_in)]
        elif self.phase == "edges":
            self.searches = [self._edge(lower=True), self._edge(lower=False)]
        elif self.phase == "check":  # the last window's jumps certified, and a probe beyond
            strict = self.strict + 1 if self.task.certify.enabled else 0
            _, lower, upper = self.windows[-1]
            self.searches = [
                *(self._certified(edge) for edge in (lower, upper)),
                self._probe(self._probe_key, self._probe_mu, strict),
            ]
        else:
            self.searches = [self._probe(self._probe_key, self._probe_mu)]
        return self.searches

    def _probe(self, key: float, mu: float, strict: int | None = None) -> Probe:
        between = getattr(self.task, "between", NOT_STICK_STICK)
        level = self.strict if strict is None else strict
        return Probe(key, mu, self.task.max_retries, level, between)

    def _certified(self, edge: LineBracket):
        """The certified bisection of a jump already bracketed to tol (its ends' runs are
        known: only the certification runs are new)."""
        return line_bisection(
            "key",
            edge.fixed_value,
            (edge.lo, edge.hi),
            self.plane.mu_range,
            edge.stick_high,
            self.plane.tol,
            self.task,
            strict=self.strict,
        )

    def _edge(self, lower: bool):
        """A bisection in mu at key_in from mu_in outwards to one jump (certified only in
        the last window, by the check)."""
        sign = -1.0 if lower else 1.0
        span = self.plane.mu_span
        m0, m1 = self.plane.mu_range
        near = self.mu_in
        far = min(m1, max(m0, near + sign * self.half))
        # after a repair the window may be far wider than the last one (a tip moved by s
        # opens a smooth fold's window by ~ sqrt(s)): its edges may widen over the plane
        reach = EDGE_REACH * self.half if self.strict == 0 else span
        widest = min(m1, max(m0, near + sign * reach))
        if far == near:
            far = near + sign * min(self.half, 0.5 * span)
        stick_high = self.inner_sticks if lower else not self.inner_sticks
        return line_bisection(
            "key",
            self.key_in,
            (min(near, far), max(near, far)),
            (min(near, widest, far), max(near, widest, far)),
            stick_high,
            self.plane.tol,
            _Uncertified(self.task),
            strict=self.strict,
        )

    def finish(self) -> None:
        """Take this round's results."""
        if self.done or not self.searches:
            return
        if self.phase == "edges":
            lower, upper = (found_bracket(s) for s in self.searches)
            if lower is None or upper is None:
                search = self.searches[0] if lower is None else self.searches[1]
                lost = search.result()
                if lost.certification == "vanished":  # the region is the short horizon's
                    self._end(
                        "not located",
                        f"the region vanishes at stricter numerics at key {self.key_in:.10g}",
                        certification="vanished",
                    )
                    return
                self._end("not located", f"a jump at key {self.key_in:.10g}: {failure(search)}")
                return
            self.windows.append((self.key_in, lower, upper))
            self.half = max(self.plane.tol, 0.5 * (upper.hi - lower.lo))  # the next is narrower
            self.phase = "probe"
            return
        probe = self.searches[-1]
        if probe.sticks is None:
            self._end("not located", f"undetermined at key {probe.key:.10g}, mu {probe.mu:.10g}")
            return
        inner = probe.sticks == self.inner_sticks
        if self.phase == "start":
            if not inner:
                region = "sticking window" if self.inner_sticks else "gap"
                self._end(
                    "not located",
                    f"no {region} at the start point key {probe.key:.10g}, mu {probe.mu:.10g} "
                    f"({probe.outcome})",
                )
            else:
                self.phase = "edges"
            return
        if self.phase == "check":
            key, *_ = self.windows[-1]
            edges = [found_bracket(search) for search in self.searches[:2]]
            flags = [search.result().certification for search in self.searches[:2]]
            if None not in edges:
                self.windows[-1] = (key, *edges)
            if inner and None not in edges and self._repair(probe):
                return
            if "vanished" in flags and self._repair_inward(key):
                return
            if not inner:
                self.key_out = probe.key  # the bracket that was checked: key_tol wide
            certified = point_certification(flags) if None not in edges else "uncertain"
            if certified == "certified" and self.strict > 0:
                certified = "recertified"
            self._end("located", "", certification="uncertain" if inner else certified)
            return
        self.probes += 1
        if inner:
            if not self.out_known:  # the tip lies further: look twice as far beyond
                reach = max(2.0 * abs(probe.key - self.key_in), self.plane.key_tol)
                self.key_out = probe.key + self.tip * reach
            self.key_in, self.mu_in = probe.key, probe.mu
            self.phase = "edges"
        else:
            self.key_out, self.out_known = probe.key, True

    def _repair(self, probe: Probe) -> bool:
        """The check's probe a key tolerance beyond key_in gave the inner verdict at the
        next level: the tip lies further out there. Go on from the probe (inside) with every
        run at that level, while a level above it is left for the check; False at the last."""
        if self.strict + 2 > self.task.certify.levels:
            return False
        self.strict += 1
        reach = max(2.0 * abs(probe.key - self.key_in), self.plane.key_tol)
        self.key_in, self.mu_in = probe.key, probe.mu
        self.key_out, self.out_known = probe.key + self.tip * reach, False
        self.phase = "edges"
        return True

    def _repair_inward(self, key: float) -> bool:
        """A jump at key_in vanished at the next level: the region ends before key_in
        there. Locate the tip again at that level between the start point (checked first:
        it must still lie inside) and key_in (now outside); False at the last level."""
        if self.strict + 2 > self.task.certify.levels:
            return False
        self.strict += 1
        self.key_in, self.mu_in, self.half = self._start
        self.key_out, self.out_known = key, True
        self.windows = []
        self.phase = "start"
        return True

    # ---- where to probe --------------------------------------------------------------------
    @staticmethod
    def _width(window) -> float:
        """Width of a window's inner region: between the jumps' inner ends."""
        _, lower, upper = window
        return upper.lo - lower.hi

    def _choose_probe(self) -> None:
        tol_k = self.plane.key_tol
        width = self._width(self.windows[-1])
        gap = (self.key_out - self.key_in) * self.tip
        if self.probes >= MAX_PROBES:
            self._end("not located", f"no tip after {MAX_PROBES} probes")
            return
        if not self.out_known:
            key = self.key_out
        elif gap <= tol_k * (1 + 1e-9) and width <= self.plane.tol:
            # the check: at stricter numerics, the region is absent a key tolerance beyond
            low, high = self.plane.key_range
            key = min(high, max(low, self.key_in + self.tip * tol_k))
            self._probe_key, self._probe_mu = key, self._centre(key)
            self.phase = "check"
            return
        elif gap <= tol_k * 1e-6:
            self._end(
                "not located",
                f"the two jumps stay {width:.3g} apart at the tip: the region ends abruptly",
            )
            return
        elif width <= self.plane.tol:
            key = self.key_in + self.tip * min(tol_k, 0.5 * gap)
        else:
            key = self.key_in + self.tip * gap * self._aim(gap)
        low, high = self.plane.key_range
        if not low <= key <= high:
            self._end("not located", "the region reaches the plane's edge")
            return
        self._probe_key, self._probe_mu = key, self._centre(key)

    def _aim(self, gap: float) -> float:
        """Fraction of the bracket (key_in ... key_out) to probe at: where the squared width
        of the last two windows extrapolates to (tol / 2)^2, kept within [AIM_CLIP, 1 - AIM_CLIP]."""
        if len(self.windows) < 2:
            return 0.5
        (k0, *_), (k1, *_) = self.windows[-2], self.windows[-1]
        w0, w1 = self._width(self.windows[-2]), self._width(self.windows[-1])
        target = (0.5 * self.plane.tol) ** 2
        if k1 == k0 or w0**2 == w1**2:
            return 0.5
        rate = (w1**2 - w0**2) / (k1 - k0)
        reach = (target - w1**2) / rate  # from k1 (= key_in) along the key
        fraction = reach * self.tip / gap
        if not math.isfinite(fraction):
            return 0.5
        return min(1 - AIM_CLIP, max(AIM_CLIP, fraction))

    def _centre(self, key: float) -> float:
        """The predicted centre of the inner region at `key`: both jumps extrapolated
        linearly (slopes from the last two windows, or the curve's near the tip), kept
        inside the last window."""
        k1, lower, upper = self.windows[-1]
        inside = (lower.hi, upper.lo) if lower.hi <= upper.lo else (upper.lo, lower.hi)
        slopes = self.slopes
        if len(self.windows) >= 2:
            k0, l0, u0 = self.windows[-2]
            if k1 != k0:
                slopes = ((lower.hi - l0.hi) / (k1 - k0), (upper.lo - u0.lo) / (k1 - k0))
        centre = 0.5 * (inside[0] + inside[1])
        if slopes is not None:
            low = lower.hi + slopes[0] * (key - k1)
            high = upper.lo + slopes[1] * (key - k1)
            centre = 0.5 * (low + high)
        return min(inside[1], max(inside[0], centre))

    def _end(self, status: str, reason: str, certification: str | None = None) -> None:
        lower = upper = None
        if self.windows:
            _, lower, upper = self.windows[-1]
        key_in = self.windows[-1][0] if self.windows else self.key_in
        flag = certification or ("failed" if status != "located" else "off")
        self.result_fold = Fold(
            status,
            reason,
            key_in,
            self.key_out if self.out_known else math.nan,
            lower,
            upper,
            self.inner_sticks,
            flag,
        )
        self.searches = []

    def result(self) -> Fold:
        if self.result_fold is None:
            raise ValueError("fold not located yet")
        return self.result_fold
