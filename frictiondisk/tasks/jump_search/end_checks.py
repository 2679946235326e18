"""A bisection's first phase: check the bracket's ends, widen it until they differ. Pure
Python.

* Both ends give the same answer: the jump lies beyond the end that does not hold, and the
  bracket is widened past it (its width x `expanding.widen`, within `limits`, guided by
  the reserve: itp.py), reusing the end already known; at a limit the search fails,
  naming both ends.
* An inverted bracket (stick at mu_lo, not stick at mu_hi) fails with both outcomes named;
  a falling jump is only ever bisected inside a bracket found by a scan.
* A predicted bracket with a deferred end (deferral.py, expanding.py) widens about it.
* An end undetermined after every retry (a predicted bracket whose end fell into the
  jump's slow approach) moves `UNDECIDED_SPAN` / 2 tol outwards and is straddled once the
  bisection starts (straddle.py).
"""

from __future__ import annotations

from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.bracket import BracketState
from frictiondisk.tasks.jump_search.deferral import Deferrals
from frictiondisk.tasks.jump_search.expanding import widened_end
from frictiondisk.tasks.jump_search.itp import ItpProbe
from frictiondisk.tasks.jump_search.straddle import UNDECIDED_SPAN, Straddle


class EndChecks:
    """The check phase of one bisection over its parts (module docstring)."""

    def __init__(
        self,
        settings: BisectionSettings,
        state: BracketState,
        deferrals: Deferrals,
        straddle: Straddle,
        itp: ItpProbe,
    ):
        self.settings = settings
        self.state = state
        self.deferrals = deferrals
        self.straddle = straddle
        self.itp = itp

    def settle(self) -> bool:
        """Move on once both ends are settled: True where they differ in the jump's
        direction (the bisection may start); else widen, or fail."""
        state, deferred = self.state, self.deferrals.deferred
        settled = (*state.known, *deferred)
        if state.lo not in settled or state.hi not in settled:
            return False
        if state.lo not in state.known or state.hi not in state.known:
            self._past_deferred_end()
            return False
        lo_stick, hi_stick = state.sticks(state.lo), state.sticks(state.hi)
        if not self.settings.rising:
            if lo_stick and not hi_stick:
                return True
            state.fail(f"no falling jump in the bracket: {self._ends_text()}")
        elif not lo_stick and hi_stick:
            return True
        elif lo_stick and not hi_stick:
            state.fail(f"bracket inverted: {self._ends_text()}")
        else:  # both ends agree: the jump lies beyond the end that does not hold
            self.widen_beyond(state.hi if not lo_stick else state.lo, state.hi - state.lo)
        return False

    def _ends_text(self, at_limit: str = "") -> str:
        lo, hi, outcome = self.state.lo, self.state.hi, self.state.outcome_at
        lo_limit = " (= limit)" if at_limit == "lo" else ""
        hi_limit = " (= limit)" if at_limit == "hi" else ""
        return (
            f"mu_lo = {lo:.10g}{lo_limit} gave {outcome(lo)}, "
            f"mu_hi = {hi:.10g}{hi_limit} gave {outcome(hi)}"
        )

    def widen_beyond(self, end: float, width: float) -> None:
        """The jump lies beyond `end` (above hi: not stick there; below lo: stick there):
        the bracket moves past it, `expanding.widen` x `width` wide (guided by the
        reserve), or the search fails at the limit."""
        state, limits, high = self.state, self.settings.limits, self.settings.between.high
        expanding = self.settings.expanding
        if end == state.hi:
            if state.hi >= limits[1]:
                state.fail(f"no {high} up to the limit: {self._ends_text('hi')}")
            else:
                far = widened_end(state.hi, width, True, expanding, limits)
                state.move(state.hi, self.itp.guided_end(state, state.hi, far))
        elif state.lo <= limits[0]:
            state.fail(f"{high} down to the limit: {self._ends_text('lo')}")
        else:
            far = widened_end(state.lo, width, False, expanding, limits)
            state.move(self.itp.guided_end(state, state.lo, far), state.lo)

    def _past_deferred_end(self) -> None:
        """A predicted bracket with a deferred end, once both ends are settled: both
        deferred, the bracket widens to `widen` x its width about its centre; the other end
        holds, the deferred end moves out to `widen` x the width from it, or its retry is
        due where the two lie within tol; the other end does not hold, the jump lies beyond
        it (widened as for ends that agree)."""
        state, expanding, limits = self.state, self.settings.expanding, self.settings.limits
        lo, hi, width = state.lo, state.hi, state.hi - state.lo
        if lo not in state.known and hi not in state.known:
            centre, half = 0.5 * (lo + hi), 0.5 * width
            state.lo = widened_end(centre, half, False, expanding, limits)
            state.hi = widened_end(centre, half, True, expanding, limits)
            for end in {lo, hi} & {state.lo, state.hi}:  # at a limit: no room to move
                self.deferrals.ladder(end)
        else:
            deferred, other = (lo, hi) if lo not in state.known else (hi, lo)
            if not state.holds(other, self.settings.rising):
                self.widen_beyond(other, width)
                return
            moved = widened_end(other, width, deferred > other, expanding, limits)
            if abs(other - deferred) <= self.settings.tol * (1 + 1e-9) or moved == deferred:
                self.deferrals.ladder(deferred)  # its retry is pending as a bracket end
                return
            state.lo, state.hi = (moved, hi) if deferred == lo else (lo, moved)
        state.round += 1

    def step_past(self, mu: float) -> bool:
        """A bracket end undetermined after every retry: the end moves UNDECIDED_SPAN / 2
        tol outwards, within `limits`, and `mu` is straddled once the bisection starts.
        False where it cannot (no room, multisection, or undecided mu that would span more
        than UNDECIDED_SPAN tol)."""
        state, limits = self.state, self.settings.limits
        if state.phase != "check" or not self.settings.plain or mu not in (state.lo, state.hi):
            return False
        if not self.straddle.within_span([*self.straddle.undecided, mu]):
            return False
        near = 0.5 * UNDECIDED_SPAN * self.settings.tol
        if mu == state.lo:
            moved = max(limits[0], mu - near)
            if moved >= mu:
                return False
            state.lo = moved
        else:
            moved = min(limits[1], mu + near)
            if moved <= mu:
                return False
            state.hi = moved
        self.straddle.undecided.append(mu)
        state.round += 1
        return True
