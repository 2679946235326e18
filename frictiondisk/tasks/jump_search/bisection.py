"""Bisection for the jump mu* of one parameter point (docs/model.md section 7). Pure Python.

`Bisection` is a state machine: `pending()` names the runs it needs next, `feed()` takes
their outcomes. It keeps [mu_lo, mu_hi] with mu_lo -> not stick and mu_hi -> stick (a
*rising* jump; a falling one, `rising=False`, has stick at mu_lo and not stick at mu_hi)
and stops when mu_hi - mu_lo <= tol. It knows nothing of simulation, I/O or Dask, so the same
object drives a live campaign and its replay from the journal.

Rules (after Attractors.jl's `bisect_to_edge`: check, retry a bounded number of times,
never guess):
* the bracket ends are checked first; if both give the same answer the bracket is widened
  (its width doubled, within `limits`), reusing the end already known;
* an `undetermined` run is retried with a longer horizon (level + 1) up to `max_retries`;
  after that the point fails with the reason of the last run, unless the run lies inside
  the bracket, or is an end of it that can move outwards: such undecided mu (the jump's
  slow approach) are straddled while they span at most `UNDECIDED_SPAN` tol;
* an inverted bracket (stick at mu_lo, not stick at mu_hi) fails with both outcomes named;
* every run is kept; runs that contradict monotonicity (a stick below a not-stick) are
  listed in the result instead of being hidden.

Interpolation (`root_finder="itp"`, the default for split 2): every run also reports its
friction reserve (frictiondisk/verdict/reserve.py), a signed signal that crosses zero near mu*.
Each round's point is its secant root (regula falsi between the bracket ends, or a unit
slope from one end; past an end whose reserve has the wrong sign, a geometric step
beyond it), nudged past the estimate so that it lands beyond it, and then projected into
ITP's window (Oliveira & Takahashi 2020): whichever way the verdict goes, the bracket stays
within what bisection would have left `ITP_SLACK` (3) rounds later, so a signal that
misleads costs at most 3 runs more than bisection. With no usable signal (never stuck)
the round is a plain bisection. Verdicts alone move the bracket.

Multisection (`split` = k >= 2): each round asks for the k - 1 interior points that cut
[mu_lo, mu_hi] into k equal parts, all at once (they may run in parallel), and moves only
when all of them are decided: the new bracket is the lowest part whose ends differ in the
jump's direction. The schedule is fixed by k, never by how many workers are idle or the
order results arrive in, so results do not depend on either. k = 2 is plain bisection.
The last round uses the fewest parts that reach tol (at most k), so no run is wasted.
"""

from __future__ import annotations

import math
from typing import Any

from frictiondisk.model.search_settings import ROOT_FINDERS
from frictiondisk.tasks.jump_search.expanding import (
    PLAIN,
    Expanding,
    expanding_probe,
    ladder_due,
    widened_end,
)
from frictiondisk.tasks.jump_search.runs import (
    STICK,
    UNDETERMINED,
    BisectionResult,
    RunRecord,
    RunRequest,
)
from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK, Between

# the run types are used from here by the searches built on a bisection
__all__ = [
    "STICK",
    "UNDETERMINED",
    "Bisection",
    "BisectionResult",
    "RunRecord",
    "RunRequest",
    "cold_run_count",
    "zero_crossing",
]

ITP_SLACK = 3  # rounds an interpolating search may lag behind bisection at worst (ITP's n0)
UNDECIDED_SPAN = 10  # [tol] undecided mu a bracket may straddle: wider is a failure


def cold_run_count(bracket: tuple[float, float], tol: float) -> int:
    """Runs of a cold bisection over `bracket` (2 end checks + halvings), no retries."""
    return 2 + max(0, math.ceil(math.log2((bracket[1] - bracket[0]) / tol)))


def zero_crossing(mu_a: float, signal_a: float, mu_b: float, signal_b: float) -> float:
    """mu where the straight line through (mu_a, signal_a) and (mu_b, signal_b) crosses
    zero (a secant step); the signals must differ."""
    return mu_a - signal_a * (mu_b - mu_a) / (signal_b - signal_a)


class Bisection:
    """Locate the jump between not-stick and stick in mu for one parameter point (or, with
    `between`, the boundary between any two sides: sides.py; "stick" then reads side B,
    "not stick" side A, and a run on neither side is undecided like an undetermined one)."""

    def __init__(
        self,
        bracket: tuple[float, float],
        tol: float,
        limits: tuple[float, float],
        max_retries: int,
        rising: bool = True,
        split: int = 2,
        strict: int = 0,
        root_finder: str = "itp",
        expanding: Expanding = PLAIN,
        between: Between = NOT_STICK_STICK,
        reserve_offset: float = 0.0,
        watch: float = 0.0,
    ):
        lo, hi = bracket
        if not (limits[0] <= lo < hi <= limits[1]) or tol <= 0:
            raise ValueError(f"bad bracket {bracket} for limits {limits} and tol {tol}")
        if split < 2:
            raise ValueError(f"split must be >= 2 (parts per round), got {split}")
        if root_finder not in ROOT_FINDERS:
            raise ValueError(f"root_finder must be one of {ROOT_FINDERS}, got {root_finder!r}")
        self.root_finder = root_finder
        self.between = between
        self.split = split
        self.strict = strict  # certification level of every run this bisection asks for
        self.watch = watch  # [s] every run watches this long (a re-search: certify.py)
        self.lo = lo
        self.hi = hi
        self.tol = tol
        self.limits = limits
        self.max_retries = max_retries
        self.rising = rising
        self.phase = "check"
        self.runs: list[RunRecord] = []
        self._known: dict[float, str] = {}  # mu -> stick / not-stick (determined runs only)
        self._level: dict[float, int] = {}  # mu -> retry level to ask for next
        self._failure: str | None = None
        # request -> (round, level, mu) when first asked for: the order runs are reported in,
        # fixed by the schedule, never by the order results arrive in
        self._issued: dict[RunRequest, tuple[int, int, float]] = {}
        self._round = 0  # bumped whenever the bracket or the phase changes
        # an interior mu still undetermined after every retry: the critical slowing down at
        # the jump itself. The bisection then straddles it (see _interior).
        self.undecided: list[float] = []
        self.stalled_at: float | None = None  # the mu undetermined after every retry that failed it
        self._signal: dict[float, float] = {}  # mu -> friction reserve (decided runs, finite)
        # the reserve at the jump per unit mu, learned from a finished point: each reserve is
        # taken less offset x mu, so that its zero is the jump's (reserve_offset.py)
        self.reserve_offset = reserve_offset
        # (schedule key, mu) of the decided runs: "the last two" never depend on timing
        self._decided: list[tuple[tuple[int, int, float], float]] = []
        self._itp: tuple[int, int] | None = None  # (first bisect round, its round budget)
        # a missed prediction (expanding.py): undetermined runs whose retry waits
        self.expanding = expanding if split == 2 else PLAIN
        self._deferred: list[float] = []  # their mu, in the order they were deferred
        self._steps: dict[float, int] = {}  # deferred mu -> probes made away from it
        self._deferred_signal: dict[float, float] = {}  # deferred mu -> its reserve (a guide)
        self._expand_steps = 0  # the steps of this round's probe away from a deferred run
        self._laddered: set[float] = set()  # mu whose retry is due: never deferred again
        self._epoch = 0  # bumped on every deferral: the round's probes are chosen anew
        self._interior_cache: tuple[tuple[int, int], str, list[float]] | None = None

    # ---- what to run ------------------------------------------------------------------
    def pending(self) -> list[RunRequest]:
        """Runs needed before the bisection can move on (empty when done)."""
        if self.done:
            return []
        if self.phase == "check":
            ends = (self.lo, self.hi)
            mus = [mu for mu in ends if mu not in self._known and mu not in self._deferred]
        else:
            mus = [mu for mu in self._interior() if mu not in self._known]
        level = self._level.get
        requests = [
            RunRequest(mu, level(mu, 0), strict=self.strict, watch=self.watch) for mu in mus
        ]
        for request in requests:
            self._issued.setdefault(request, (self._round, request.level, request.mu))
        return requests

    @property
    def done(self) -> bool:
        return self._failure is not None or self.phase == "converged"

    def schedule_key(self, request: RunRequest) -> tuple[int, int, float] | None:
        """(round, level, mu) of a request this bisection asked for (None otherwise)."""
        return self._issued.get(request)

    def _undecided_inside(self) -> list[float]:
        """The undecided mu that lie inside the current bracket."""
        return [mu for mu in self.undecided if self.lo < mu < self.hi]

    def _straddled(self) -> tuple[float, float] | None:
        """(lowest, highest) undecided mu inside the bracket, if any (plain bisection only)."""
        inside = self._undecided_inside()
        return (min(inside), max(inside)) if inside and self.split == 2 else None

    def _open_sides(self, undecided: tuple[float, float]) -> tuple[bool, bool]:
        """Whether the gaps below and above the undecided mu [u_lo, u_hi] are wider than
        tol / 2: a closed side is not split again (probes there would halve that gap
        forever while the other side's decided probe waits), and with both closed the
        bracket has converged."""
        half = 0.5 * self.tol
        return undecided[0] - self.lo > half, self.hi - undecided[1] > half

    def _interior(self) -> list[float]:
        """This round's interior points, increasing; chosen once per round and deferral
        (pending() asks again after every result)."""
        key = (self._round, self._epoch)
        if self._interior_cache is None or self._interior_cache[0] != key:
            kind, mus = self._choose_interior()
            self._interior_cache = (key, kind, mus)
        return self._interior_cache[2]

    def _interior_kind(self) -> str | None:
        """How this round's interior was chosen: straddle, ladder, expand, aim, itp, mid or split."""
        key = (self._round, self._epoch)
        cache = self._interior_cache
        return cache[1] if cache is not None and cache[0] == key else None

    def _choose_interior(self) -> tuple[str, list[float]]:
        """lo + j (hi - lo) / parts; around the undecided mu [u_lo, u_hi], the midpoints of
        (lo, u_lo) and (u_hi, hi), but at most UNDECIDED_SPAN / 2 tol away (a wide
        bracket's midpoint once hit a far transient) and none on a side within tol / 2
        of its end; away from a deferred run
        (expanding.py); else the interpolating probe."""
        width = self.hi - self.lo
        u = self._straddled()
        if u is not None:
            near = 0.5 * UNDECIDED_SPAN * self.tol
            below, above = 0.5 * (self.lo + u[0]), 0.5 * (u[1] + self.hi)
            below_open, above_open = self._open_sides(u)
            probes = [max(below, u[0] - near)] if below_open else []
            if above_open:
                probes.append(min(above, u[1] + near))
            return "straddle", probes
        deferred = self._deferred_inside()
        if deferred is not None:
            return self._away_from(deferred)
        if self.split == 2 and self.root_finder == "itp":
            kind, probe = self._choose_probe()
            return kind, [probe]
        parts = self.split
        # the last round: the fewest parts that reach tol (same test as _maybe_converged)
        while parts > 2 and width / (parts - 1) <= self.tol * (1 + 1e-9):
            parts -= 1
        return "split", [self.lo + j * width / parts for j in range(1, parts)]

    # ---- a missed prediction (expanding.py) -------------------------------------------
    @property
    def _stick_end(self) -> float:
        return self.hi if self.rising else self.lo

    def _deferred_inside(self) -> float | None:
        """The deferred run inside the bracket nearest its sticking end, if any."""
        inside = [
            mu
            for mu in self._deferred
            if self.lo < mu < self.hi and mu not in self._known and mu not in self.undecided
        ]
        if not inside:
            return None
        return min(inside, key=lambda mu: abs(self._stick_end - mu))

    def _away_from(self, deferred: float) -> tuple[str, list[float]]:
        """The next probe away from a deferred run towards the sticking end: at the
        reserve's estimate of the jump where it has one, else a geometric step; or the
        run's retry once that end lies within tol of it."""
        if not ladder_due(deferred, self._stick_end, self.tol):
            aimed = self._aim_past(deferred)
            if aimed is not None:
                self._expand_steps = self._steps.get(deferred, 0)
                return "aim", [aimed]
            steps = self._steps.get(deferred, 0) + 1
            probe = expanding_probe(deferred, self._stick_end, self.tol, steps)
            if self.lo < probe < self.hi and probe not in self._known:
                self._steps[deferred] = self._expand_steps = steps
                return "expand", [probe]
        self._laddered.add(deferred)
        return "ladder", [deferred]

    def _aim_past(self, deferred: float) -> float | None:
        """A probe between a deferred run and the sticking end aimed at the jump by the
        reserve (unit slope from whichever of the two reads nearest zero: an undetermined
        run's reserve is no verdict, but it says where the jump lies), nudged half a tol
        towards the sticking end, or a tol from that end where the jump lies within a tol
        of it; None where the reserve says nothing, contradicts the sticking end's verdict,
        or aims no farther from the deferred run than the next geometric step (a probe
        that near would land in the same slow band): then the steps are geometric."""
        stick = self._stick_end
        if not self.rising or (stick in self._signal and not self._agrees(stick)):
            return None
        readings = [(mu, self._signal[mu]) for mu in (stick,) if mu in self._signal]
        if deferred in self._deferred_signal:
            readings.append((deferred, self._deferred_signal[deferred]))
        if not readings:
            return None
        mu, reading = min(readings, key=lambda pair: abs(pair[1]))
        estimate = mu - reading
        toward = 1.0 if stick > deferred else -1.0
        if abs(stick - estimate) < self.tol:
            probe = stick - toward * self.tol * (1.0 - 1e-6)
        else:
            probe = estimate + toward * 0.5 * self.tol
        step = expanding_probe(deferred, stick, self.tol, self._steps.get(deferred, 0) + 1)
        far_enough = (probe - deferred) * toward >= abs(step - deferred) * (1 - 1e-9)
        if not far_enough or (stick - probe) * toward <= 0:
            return None
        return None if probe in self._known or probe in self._deferred else probe

    def _defer(self, request: RunRequest) -> bool:
        """Postpone the retry of an undetermined run (a predicted bracket's end, or a probe
        at a prediction: expanding.py); False where its retry is due now."""
        mu = request.mu
        if request.level >= self.max_retries or mu in self._laddered:
            return False
        if self.phase == "check":
            if not (self.expanding.predicted and mu in (self.lo, self.hi)):
                return False
        elif not (self.expanding.defer and self._interior_kind() in ("itp", "expand", "aim")):
            return False
        self._deferred.append(mu)
        if self._interior_kind() in ("expand", "aim"):  # the steps from it go on growing
            self._steps[mu] = self._expand_steps
        self._level[mu] = request.level + 1
        self._epoch += 1
        if self.phase == "check":
            self._after_check()
        return True

    def _holds(self, end: float) -> bool:
        """A decided bracket end gave the verdict its side of the jump should give."""
        sticks = self._known[end] == STICK
        return sticks == (end == self.hi) if self.rising else sticks == (end == self.lo)

    def _past_deferred_end(self) -> None:
        """A predicted bracket with a deferred end, once both ends are settled: both
        deferred, the bracket widens to `widen` x its width about its centre; the other end
        holds, the deferred end moves out to `widen` x the width from it, or its retry is
        due where the two lie within tol; the other end does not hold, the jump lies beyond
        it (widened as for ends that agree)."""
        lo, hi, width = self.lo, self.hi, self.hi - self.lo
        if lo not in self._known and hi not in self._known:
            centre, half = 0.5 * (lo + hi), 0.5 * width
            self.lo = widened_end(centre, half, False, self.expanding, self.limits)
            self.hi = widened_end(centre, half, True, self.expanding, self.limits)
            for end in {lo, hi} & {self.lo, self.hi}:  # at a limit: no room to move
                self._laddered.add(end)
                self._deferred.remove(end)
        else:
            deferred, other = (lo, hi) if lo not in self._known else (hi, lo)
            if not self._holds(other):
                self._widen_beyond(other, width)
                return
            moved = widened_end(other, width, deferred > other, self.expanding, self.limits)
            if abs(other - deferred) <= self.tol * (1 + 1e-9) or moved == deferred:
                self._laddered.add(deferred)
                self._deferred.remove(deferred)  # its retry is pending as a bracket end
                return
            self.lo, self.hi = (moved, hi) if deferred == lo else (lo, moved)
        self._round += 1

    # ---- what came back ---------------------------------------------------------------
    def feed(self, request: RunRequest, result: dict[str, Any]) -> None:
        """Take the outcome of a requested run and advance."""
        if self.done or request not in self.pending():
            raise ValueError(f"unexpected run {request}")
        self.runs.append(RunRecord(request, result))
        outcome = result["outcome"]
        side = self.between.side(outcome)
        if side is None and self._defer(request):
            reserve = result.get("reserve") if self.between.uses_reserve else None
            if reserve is not None and math.isfinite(reserve):
                corrected = float(reserve) - self.reserve_offset * request.mu
                self._deferred_signal[request.mu] = corrected
            return
        if side is None:
            # undecided mu inside the bracket are straddled while they span at most
            # UNDECIDED_SPAN tol: the jump's slow approach, bracketed from both sides
            straddle = self.phase == "bisect" and self.split == 2
            span = self._straddled()
            if span is not None:
                straddle = straddle and self._within_span([*span, request.mu])
            if request.level >= self.max_retries and straddle:
                self.undecided.append(request.mu)
                self._round += 1  # the round around them
                self._maybe_converged()
                if not self.done:
                    self._after_round()  # its probes may be decided already
                return
            if request.level >= self.max_retries and self._step_past(request.mu):
                return
            if request.level >= self.max_retries:
                self.stalled_at = request.mu
                self._failure = (
                    f"{self.between.undecided_text(outcome)} at mu = {request.mu:.10g} after "
                    f"{request.level} retries with longer horizons: {result.get('reason', '')}"
                )
            else:
                self._level[request.mu] = request.level + 1
            return
        self._known[request.mu] = side
        self._decided.append((self._issued[request], request.mu))
        reserve = result.get("reserve") if self.between.uses_reserve else None
        if reserve is not None and math.isfinite(reserve):
            self._signal[request.mu] = float(reserve) - self.reserve_offset * request.mu
        if self.phase == "check":
            self._after_check()
        else:
            self._after_round()

    def _within_span(self, mus: list[float]) -> bool:
        """Whether undecided mu span at most UNDECIDED_SPAN tol (a bracket may straddle them)."""
        return max(mus) - min(mus) <= UNDECIDED_SPAN * self.tol * (1 + 1e-9)

    def _step_past(self, mu: float) -> bool:
        """A bracket end undetermined after every retry (a predicted bracket whose end
        fell into the jump's slow approach): the end moves UNDECIDED_SPAN / 2 tol outwards,
        within `limits`, and `mu` is straddled once the bisection starts. False where it
        cannot (no room, multisection, or undecided mu that would span more than
        UNDECIDED_SPAN tol)."""
        if self.phase != "check" or self.split != 2 or mu not in (self.lo, self.hi):
            return False
        if not self._within_span([*self.undecided, mu]):
            return False
        near = 0.5 * UNDECIDED_SPAN * self.tol
        if mu == self.lo:
            moved = max(self.limits[0], mu - near)
            if moved >= mu:
                return False
            self.lo = moved
        else:
            moved = min(self.limits[1], mu + near)
            if moved <= mu:
                return False
            self.hi = moved
        self.undecided.append(mu)
        self._round += 1
        self._after_check()  # the moved end may be known already
        return True

    def abort(self, reason: str) -> None:
        """End the bisection as failed without a run (e.g. its worker kept dying)."""
        if not self.done:
            self._failure = reason

    def _after_check(self) -> None:
        settled = (*self._known, *self._deferred)
        if self.lo not in settled or self.hi not in settled:
            return
        if self.lo not in self._known or self.hi not in self._known:
            self._past_deferred_end()
            return
        lo_stick = self._known[self.lo] == STICK
        hi_stick = self._known[self.hi] == STICK
        width = self.hi - self.lo
        if not self.rising:
            if lo_stick and not hi_stick:
                self._next_round(phase="bisect")
            else:  # a falling jump is only ever bisected inside a bracket found by a scan
                self._failure = (
                    f"no falling jump in the bracket: mu_lo = {self.lo:.10g} gave "
                    f"{self._outcome_at(self.lo)}, mu_hi = {self.hi:.10g} gave "
                    f"{self._outcome_at(self.hi)}"
                )
        elif not lo_stick and hi_stick:
            self._next_round(phase="bisect")
        elif lo_stick and not hi_stick:
            self._failure = (
                f"bracket inverted: mu_lo = {self.lo:.10g} gave {self._outcome_at(self.lo)}, "
                f"mu_hi = {self.hi:.10g} gave {self._outcome_at(self.hi)}"
            )
        else:  # both ends agree: the jump lies beyond the end that does not hold
            self._widen_beyond(self.hi if not lo_stick else self.lo, width)

    def _widen_beyond(self, end: float, width: float) -> None:
        """The jump lies beyond `end` (above hi: not stick there; below lo: stick there):
        the bracket moves past it, `expanding.widen` x `width` wide (guided by the
        reserve), or the search fails at the limit."""
        if end == self.hi:
            if self.hi >= self.limits[1]:
                self._failure = (
                    f"no {self.between.high} up to the limit: mu_lo = {self.lo:.10g} gave "
                    f"{self._outcome_at(self.lo)}, mu_hi = {self.hi:.10g} (= limit) gave "
                    f"{self._outcome_at(self.hi)}"
                )
            else:
                far = widened_end(self.hi, width, True, self.expanding, self.limits)
                self._next_round(self.hi, self._guided_end(self.hi, far))
        elif self.lo <= self.limits[0]:
            self._failure = (
                f"{self.between.high} down to the limit: mu_lo = {self.lo:.10g} (= limit) "
                f"gave {self._outcome_at(self.lo)}, mu_hi = {self.hi:.10g} gave "
                f"{self._outcome_at(self.hi)}"
            )
        else:
            far = widened_end(self.lo, width, False, self.expanding, self.limits)
            self._next_round(self._guided_end(self.lo, far), self.lo)

    def _after_round(self) -> None:
        """Once every interior point is decided: the lowest part whose ends differ in the
        jump's direction becomes the bracket (with one point, plain bisection)."""
        interior = self._interior()
        if any(mu not in self._known for mu in interior):
            return
        ends = [self.lo, *interior, self.hi]
        if len(interior) == 2 and interior[0] < interior[1] and self._straddled() is not None:
            u_lo, u_hi = interior  # around an undecided mu: a kind change on either side of it
            lo_kind = self._known[self.lo]
            if self._known[u_lo] != lo_kind:
                self._next_round(self.lo, u_lo)
            elif self._known[u_hi] == lo_kind:
                self._next_round(u_hi, self.hi)
            else:
                self._next_round(u_lo, u_hi)  # the jump is at the undecided mu
            return
        # the bracket ends are known and differ; a change is found by walking up from lo
        lo_kind = self._known[self.lo]
        for a, b in zip(ends, ends[1:], strict=False):
            if self._known[b] != lo_kind:
                self._next_round(a, b)
                return

    def _next_round(self, lo: float | None = None, hi: float | None = None, phase=None) -> None:
        if lo is not None:
            self.lo, self.hi = lo, hi
        if phase is not None:
            self.phase = phase
        self._round += 1
        if self.phase == "bisect" and self._itp is None:
            rounds = math.ceil(math.log2((self.hi - self.lo) / self.tol) - 1e-9)
            self._itp = (self._round, max(0, rounds) + ITP_SLACK)
        if self.phase == "bisect":
            self._maybe_converged()

    # ---- the interpolating probe (root_finder "itp") ---------------------------------
    def _choose_probe(self) -> tuple[str, float]:
        """This round's point ("itp": the signal's root estimate, nudged past it, inside
        ITP's window; "mid": the midpoint, where ITP keeps its promise by bisecting or the
        signal says nothing)."""
        lo, hi, tol = self.lo, self.hi, self.tol
        mid = 0.5 * (lo + hi)
        first, budget = self._itp
        # after this round the bracket must be no wider than bisection's would be at the
        # end of the budget: width <= tol 2**(rounds left), whichever way the verdict goes
        # (a hair under, so that rounding at the last round cannot leave it above tol)
        window = tol * 2.0 ** (budget - (self._round - first) - 1) * (1.0 - 1e-6)
        if 2.0 * window <= hi - lo:  # no room left: bisection keeps the promise
            return "mid", mid
        estimate = self._root_estimate()
        if estimate is None:
            return "mid", mid
        near, far = (lo, hi) if estimate - lo < hi - estimate else (hi, lo)
        toward_far = 1.0 if far > near else -1.0
        if abs(estimate - near) < tol:
            # one run closes the bracket if the root lies where the signal says
            probe = near + toward_far * tol * (1.0 - 1e-6)
        else:
            # half a tol beyond the estimate: a good estimate then leaves the near end's
            # side behind, and the next round can close the bracket in one run
            step = min(0.5 * tol, 0.5 * abs(far - estimate))
            probe = estimate + toward_far * step
        probe = min(max(probe, hi - window), lo + window)
        if not lo < probe < hi or probe in self._known:
            return "mid", mid
        return "itp", probe

    def _root_estimate(self) -> float | None:
        """Where the friction reserve crosses zero inside (lo, hi), or None: the secant
        through the bracket ends when both carry a reserve whose sign agrees with their
        verdict (reserve > 0: stick), else a unit slope from the end that does (the
        reserve is mu minus a demand that moves slowly with mu)."""
        lo, hi = self.lo, self.hi
        return next((e for e in self._estimates() if e is not None and lo < e < hi), None)

    def _estimates(self):
        """Root estimates, best first (lazily: each is tried only if the ones before it
        fall outside the bracket)."""
        lo, hi, signal = self.lo, self.hi, self._signal
        recent = [mu for _, mu in sorted(self._decided)[-2:] if self._agrees(mu)]
        if len(recent) == 2 and signal[recent[0]] != signal[recent[1]]:
            # the secant through the last two runs: no stagnation at a far end
            a, b = recent
            yield zero_crossing(b, signal[b], a, signal[a])
        if self._agrees(lo) and self._agrees(hi):
            # the reserve's sign agrees with both (different) verdicts, so signals differ
            yield zero_crossing(lo, signal[lo], hi, signal[hi])
        else:
            end = next((mu for mu in (hi, lo) if self._agrees(mu)), None)
            yield None if end is None else end - signal[end]
        yield self._past_a_contradiction()

    def _past_a_contradiction(self) -> float | None:
        """Where the jump may lie when a bracket end's reserve has the wrong sign by d (a
        stick at reserve -d, or a not-stick at +d): the reserve is biased there (contact
        compliance, a brake torque), so the jump lies beyond that end, where the reserve
        is further from zero. Aim where it is 3 d + tol from zero (unit slope): a bias b
        then costs about log3(b / d) rounds before a probe crosses, not a bisection of the
        bracket. Once the other end's reserve has the same sign and is further out, the
        bias lies between the two: aim at their geometric mean (interpolated)."""
        for end, other in ((self.hi, self.lo), (self.lo, self.hi)):
            if end not in self._signal or self._agrees(end):
                continue
            s_end = self._signal[end]
            d = abs(s_end)
            toward = 1.0 if other > end else -1.0
            s_other = self._signal.get(other)
            if s_other is not None and s_other * s_end > 0 and abs(s_other) > d:
                target = math.sqrt(abs(s_other) * d)
                if target < 3.0 * d + self.tol:
                    return end + (other - end) * (target - d) / (abs(s_other) - d)
            return end + toward * (2.0 * d + self.tol)
        return None

    def _guided_end(self, end: float, far: float) -> float:
        """The far end of a widened bracket that reaches from `end` to at most `far`: just
        past the reserve's root where both ends' reserves agree with their (equal) verdicts
        and extrapolate to a root between end and far, else `far` (geometric widening)."""
        if self.root_finder != "itp" or self.split != 2:
            return far
        other = self.hi if end == self.lo else self.lo
        if (
            not (self._agrees(end) and self._agrees(other))
            or self._signal[end] == self._signal[other]
        ):
            return far
        root = zero_crossing(end, self._signal[end], other, self._signal[other])
        direction = 1.0 if far > end else -1.0
        reach = (root - end) * direction  # how far beyond `end` the root lies
        if not 0.0 < reach < abs(far - end):
            return far
        step = max(reach + 0.5 * self.tol, self.tol * (1.0 - 1e-6))
        return end + direction * min(step, abs(far - end))

    def _agrees(self, mu: float) -> bool:
        """mu carries a reserve whose sign agrees with its verdict (> 0: stick)."""
        return mu in self._signal and (self._signal[mu] > 0) == (self._known[mu] == STICK)

    def _outcome_at(self, mu: float) -> str:
        for run in reversed(self.runs):
            if run.request.mu == mu:
                return run.outcome
        return "nothing"

    def _maybe_converged(self) -> None:
        """Converged at a width <= tol, or, around undecided mu, at a width of their span
        plus tol (or both gaps beside them within tol / 2)."""
        span = self._straddled()
        spread = 0.0 if span is None else span[1] - span[0]
        closed = span is not None and not any(self._open_sides(span))
        if closed or self.hi - self.lo <= (self.tol + spread) * (1 + 1e-9):
            self.phase = "converged"

    # ---- the answer -------------------------------------------------------------------
    def result(self) -> BisectionResult:
        if not self.done:
            raise ValueError("bisection not finished")
        converged = self._failure is None
        established = converged or self.phase == "bisect"
        nan = float("nan")
        return BisectionResult(
            status="converged" if converged else "failed",
            reason=(
                f"bracket of width {self.hi - self.lo:.3g}{self._undecided_note()}"
                if converged
                else self._failure
            ),
            mu_lo=self.lo if established else nan,
            mu_hi=self.hi if established else nan,
            # in the order requested, not the order results arrived: independent of timing
            runs=tuple(sorted(self.runs, key=lambda run: self._issued[run.request])),
            contradictions=self._contradictions(),
            rising=self.rising,
            strict=self.strict,
        )

    def _undecided_note(self) -> str:
        inside = sorted(self._undecided_inside())
        if not inside:
            return f" <= tol {self.tol:.3g}"
        mus = ", ".join(f"{mu:.10g}" for mu in inside)
        return (
            f" around mu = {mus}, undetermined after every retry (the jump's slow approach, "
            f"bracketed from both sides to its span + tol {self.tol:.3g})"
        )

    def _contradictions(self) -> tuple[tuple[float, float], ...]:
        """Pairs of runs that contradict a single jump of this bracket's direction:
        (stick mu, larger not-stick mu) for a rising jump, the reverse for a falling one."""
        sticks = sorted(mu for mu, o in self._known.items() if o == STICK)
        nots = sorted(mu for mu, o in self._known.items() if o != STICK)
        if self.rising:
            return tuple((s, n) for s in sticks for n in nots if s < n)
        return tuple((n, s) for s in sticks for n in nots if n < s)
