"""Bisection for the jump mu* of one parameter point (docs/model.md section 7). Pure Python.

`Bisection` is a state machine: `pending()` names the runs it needs next, `feed()` takes
their outcomes. It keeps [mu_lo, mu_hi] with mu_lo -> not stick and mu_hi -> stick (a
*rising* jump; a falling one, `rising=False`, has stick at mu_lo and not stick at mu_hi)
and stops when mu_hi - mu_lo <= tol. It knows nothing of simulation, I/O or Dask, so the same
object drives a live campaign and its replay from the journal.

Rules (after Attractors.jl's `bisect_to_edge`: check, retry a bounded number of times,
never guess):
* the bracket ends are checked first; if both give the same answer the bracket is widened
  (its width doubled, within `limits`), reusing the end already known (end_checks.py);
* an `undetermined` run is retried with a longer horizon (level + 1) up to `max_retries`;
  after that the point fails with the reason of the last run, unless the run lies inside
  the bracket, or is an end of it that can move outwards: such undecided mu (the jump's
  slow approach) are straddled while they span at most `UNDECIDED_SPAN` tol (straddle.py);
* an inverted bracket (stick at mu_lo, not stick at mu_hi) fails with both outcomes named;
* every search ends: a bracket that mu (or the numerics) resolves no finer, before it
  reaches tol, ends the point `failed` with that reason (bisection_settings.py `floor`);
* every run is kept; runs that contradict monotonicity (a stick below a not-stick) are
  listed in the result instead of being hidden.

The parts: the fixed rules (`BisectionSettings`, bisection_settings.py), what is known so
far (`BracketState`, bracket.py), and the probe strategies that pick each round's points
(probes.py: plain bisection and multisection, the friction reserve's root estimate in
ITP's window (itp.py), the steps away from a missed prediction (deferral.py), the straddle
of undecided mu). `Bisection` moves the bracket from round to round.
"""

from __future__ import annotations

import math
from typing import Any

from frictiondisk.tasks.jump_search.bisection_settings import FLOOR_ULPS, BisectionSettings
from frictiondisk.tasks.jump_search.bracket import BracketState
from frictiondisk.tasks.jump_search.deferral import Deferrals
from frictiondisk.tasks.jump_search.end_checks import EndChecks
from frictiondisk.tasks.jump_search.itp import ITP_SLACK, ItpProbe, zero_crossing
from frictiondisk.tasks.jump_search.probes import Probes
from frictiondisk.tasks.jump_search.runs import BisectionResult, RunRecord, RunRequest
from frictiondisk.tasks.jump_search.straddle import UNDECIDED_SPAN, Straddle
from frictiondisk.verdict.outcomes import STICK, UNDETERMINED

# the run types and constants are used from here by the searches built on a bisection
__all__ = [
    "ITP_SLACK",
    "STICK",
    "UNDECIDED_SPAN",
    "UNDETERMINED",
    "Bisection",
    "BisectionResult",
    "BisectionSettings",
    "RunRecord",
    "RunRequest",
    "cold_run_count",
    "zero_crossing",
]


def cold_run_count(bracket: tuple[float, float], tol: float) -> int:
    """Runs of a cold bisection over `bracket` (2 end checks + halvings), no retries."""
    return 2 + max(0, math.ceil(math.log2((bracket[1] - bracket[0]) / tol)))


class Bisection:
    """Locate the jump between not-stick and stick in mu for one parameter point (or, with
    `between`, the boundary between any two sides: sides.py; "stick" then reads side B,
    "not stick" side A, and a run on neither side is undecided like an undetermined one).

    `bracket` [mu] is where it starts; `settings` hold its rules for the whole search."""

    def __init__(self, bracket: tuple[float, float], settings: BisectionSettings):
        lo, hi = bracket
        if not settings.limits[0] <= lo < hi <= settings.limits[1]:
            raise ValueError(
                f"bad bracket {bracket} for limits {settings.limits} and tol {settings.tol}"
            )
        self.settings = settings
        self.state = BracketState(lo, hi)
        self.straddle = Straddle(settings)
        self.itp = ItpProbe(settings)
        self.deferrals = Deferrals(settings)
        self.probes = Probes(settings, self.state, self.straddle, self.deferrals, self.itp)
        self.ends = EndChecks(settings, self.state, self.deferrals, self.straddle, self.itp)

    # ---- read by the searches built on a bisection ------------------------------------
    @property
    def lo(self) -> float:
        return self.state.lo

    @property
    def hi(self) -> float:
        return self.state.hi

    @property
    def runs(self) -> list[RunRecord]:
        """Every run, in the order it came back."""
        return self.state.runs

    @property
    def strict(self) -> int:
        return self.settings.strict

    @property
    def stalled_at(self) -> float | None:
        """The mu undetermined after every retry that failed the search, if one did."""
        return self.straddle.stalled_at

    # ---- what to run ------------------------------------------------------------------
    @property
    def done(self) -> bool:
        return self.state.done

    def pending(self) -> list[RunRequest]:
        """Runs needed before the bisection can move on (empty when done)."""
        if self.done:
            return []
        state = self.state
        if state.phase == "check":
            ends = (state.lo, state.hi)
            deferred = self.deferrals.deferred
            mus = [mu for mu in ends if mu not in state.known and mu not in deferred]
        else:
            mus = [mu for mu in self.probes.interior() if mu not in state.known]
        level, strict, watch = state.level, self.settings.strict, self.settings.watch
        requests = [RunRequest(mu, level.get(mu, 0), strict=strict, watch=watch) for mu in mus]
        for request in requests:
            state.issue(request)
        return requests

    def schedule_key(self, request: RunRequest) -> tuple[int, int, float] | None:
        """(round, level, mu) of a request this bisection asked for (None otherwise)."""
        return self.state.issued.get(request)

    # ---- what came back ---------------------------------------------------------------
    def feed(self, request: RunRequest, result: dict[str, Any]) -> None:
        """Take the outcome of a requested run and advance."""
        if self.done or request not in self.pending():
            raise ValueError(f"unexpected run {request}")
        self._take(request, result)
        self._close_rounds()

    def _take(self, request: RunRequest, result: dict[str, Any]) -> None:
        state = self.state
        state.runs.append(RunRecord(request, result))
        side = self.settings.between.side(result["outcome"])
        if side is None:
            self._undecided_run(request, result)
            return
        state.learn(request, side, self.settings.corrected(request.mu, result.get("reserve")))
        if state.phase == "check":
            self._after_check()
        else:
            self._after_round()

    def _close_rounds(self) -> None:
        """After every result: a round whose points are all decided already is closed (the
        bracket moves); one whose points cannot split the bracket ends the search, so that
        a search always ends, and ends within `feed` (the searches built on it look then)."""
        while self.state.phase == "bisect" and not self.done:
            mus = self.probes.interior()
            if not self.probes.splits(mus):
                self._unresolved()
            elif all(mu in self.state.known for mu in mus):
                before = self.state.round
                self._after_round()
                if self.state.round == before and not self.done:
                    self._unresolved()
            else:
                return

    def _undecided_run(self, request: RunRequest, result: dict[str, Any]) -> None:
        """A run on neither side: deferred (a missed prediction), retried with a longer
        horizon, or after every retry straddled, stepped past as a bracket end, or the end
        of the search."""
        state, mu = self.state, request.mu
        if self.deferrals.defer(state, request, self.probes.kind(), result.get("reserve")):
            if state.phase == "check":
                self._after_check()
            return
        if request.level < self.settings.max_retries:
            state.level[mu] = request.level + 1
        elif self.straddle.may_take(state, mu):
            # the jump's slow approach, bracketed from both sides
            self.straddle.undecided.append(mu)
            state.round += 1  # the round around them
            self._maybe_converged()
            if not self.done:
                self._after_round()  # its probes may be decided already
        elif self.ends.step_past(mu):
            self._after_check()  # the moved end may be known already
        else:
            self.straddle.stalled_at = mu
            undecided = self.settings.between.undecided_text(result["outcome"])
            state.fail(
                f"{undecided} at mu = {mu:.10g} after {request.level} retries with longer "
                f"horizons: {result.get('reason', '')}"
            )

    def abort(self, reason: str) -> None:
        """End the bisection as failed without a run (e.g. its worker kept dying)."""
        if not self.done:
            self.state.fail(reason)

    # ---- the bracket moves ------------------------------------------------------------
    def _after_check(self) -> None:
        if self.ends.settle():
            self._next_round(phase="bisect")

    def _after_round(self) -> None:
        """Once every interior point is decided: the lowest part whose ends differ in the
        jump's direction becomes the bracket (with one point, plain bisection)."""
        state = self.state
        interior = self.probes.interior()
        if any(mu not in state.known for mu in interior):
            return
        lo_kind = state.known[state.lo]
        if len(interior) == 2 and interior[0] < interior[1] and self.straddle.span(state):
            u_lo, u_hi = interior  # around an undecided mu: a kind change on either side of it
            if state.known[u_lo] != lo_kind:
                self._next_round(state.lo, u_lo)
            elif state.known[u_hi] == lo_kind:
                self._next_round(u_hi, state.hi)
            else:
                self._next_round(u_lo, u_hi)  # the jump is at the undecided mu
            return
        # the bracket ends are known and differ; a change is found by walking up from lo
        ends = [state.lo, *interior, state.hi]
        for a, b in zip(ends, ends[1:], strict=False):
            if state.known[b] != lo_kind:
                self._next_round(a, b)
                return

    def _next_round(self, lo: float | None = None, hi: float | None = None, phase=None) -> None:
        self.state.move(lo, hi, phase)
        if self.state.phase == "bisect":
            self.itp.open(self.state)
            self._maybe_converged()

    def _maybe_converged(self) -> None:
        """Converged (straddle.py `converged`), or failed where mu resolves the bracket no
        finer."""
        state = self.state
        if self.straddle.converged(state):
            state.phase = "converged"
        elif state.hi - state.lo <= self.settings.floor(max(abs(state.lo), abs(state.hi))):
            self._unresolved()

    def _unresolved(self) -> None:
        """End the search where its bracket cannot be split finer (every search ends)."""
        state, settings = self.state, self.settings
        floor = settings.floor(max(abs(state.lo), abs(state.hi)))
        what = (
            f"the numerics' resolution {settings.resolution:.3g}"
            if floor == settings.resolution
            else f"{FLOOR_ULPS} floating-point steps of mu, {floor:.3g}"
        )
        state.fail(
            f"bracket [{state.lo:.17g}, {state.hi:.17g}] (width {state.hi - state.lo:.3g}) "
            f"cannot be split finer than mu resolves ({what}): tol {settings.tol:.3g} "
            "cannot be reached"
        )

    # ---- the answer -------------------------------------------------------------------
    def result(self) -> BisectionResult:
        if not self.done:
            raise ValueError("bisection not finished")
        state = self.state
        converged = state.failure is None
        established = converged or state.phase == "bisect"
        nan = float("nan")
        return BisectionResult(
            status="converged" if converged else "failed",
            reason=(
                f"bracket of width {state.hi - state.lo:.3g}{self.straddle.note(state)}"
                if converged
                else state.failure
            ),
            mu_lo=state.lo if established else nan,
            mu_hi=state.hi if established else nan,
            runs=state.ordered_runs(),
            contradictions=state.contradictions(self.settings.rising),
            rising=self.settings.rising,
            strict=self.settings.strict,
        )
