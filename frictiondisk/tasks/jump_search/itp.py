"""The interpolating probe strategy of a bisection (`root_finder: itp`). Pure Python.

Every run also reports its friction reserve (frictiondisk/verdict/reserve.py), a signed
signal that crosses zero near mu*. Each round's point is its secant root (regula falsi
between the bracket ends, or a unit slope from one end; past an end whose reserve has the
wrong sign, a geometric step beyond it), nudged past the estimate so that it lands beyond
it, and then projected into ITP's window (Oliveira & Takahashi 2020): whichever way the
verdict goes, the bracket stays within what bisection would have left `ITP_SLACK` (3)
rounds later, so a signal that misleads costs at most 3 runs more than bisection. With no
usable signal (never stuck) the round is a plain bisection. Verdicts alone move the
bracket.

The round budget counts halvings down to tol, or down to the narrowest bracket mu resolves
where tol lies below it (bisection_settings.py), so that the window keeps the promise of a
bisection that ends. Past `STEPPING_BUDGETS` times the budget the steps away from deferred
runs (deferral.py) stop too, and the search bisects.
"""

from __future__ import annotations

import math

from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.bracket import BracketState

ITP_SLACK = 3  # rounds an interpolating search may lag behind bisection at worst (ITP's n0)
# rounds, in units of the budget, after which a search steps no longer away from deferred
# runs (deferral.py) but bisects: in a slow band far wider than tol those steps would walk
# through it a few tol a round
STEPPING_BUDGETS = 2


def zero_crossing(mu_a: float, signal_a: float, mu_b: float, signal_b: float) -> float:
    """mu where the straight line through (mu_a, signal_a) and (mu_b, signal_b) crosses
    zero (a secant step); the signals must differ."""
    return mu_a - signal_a * (mu_b - mu_a) / (signal_b - signal_a)


class ItpProbe:
    """Each round's point from the friction reserve, inside ITP's window (module docstring)."""

    def __init__(self, settings: BisectionSettings):
        self.settings = settings
        self.budget: tuple[int, int] | None = None  # (first bisect round, its round budget)

    def open(self, state: BracketState) -> None:
        """Fix the round budget when the bisection starts: halvings to tol (or to the
        narrowest bracket mu resolves, where wider) plus the slack."""
        if self.budget is not None:
            return
        reach = max(self.settings.tol, self.settings.floor(max(abs(state.lo), abs(state.hi))))
        rounds = math.ceil(math.log2((state.hi - state.lo) / reach) - 1e-9)
        self.budget = (state.round, max(0, rounds) + ITP_SLACK)

    def overspent(self, state: BracketState) -> bool:
        """Whether the search has made STEPPING_BUDGETS times its round budget of rounds."""
        if self.budget is None:
            return False
        first, budget = self.budget
        return state.round - first > STEPPING_BUDGETS * budget

    def choose(self, state: BracketState) -> tuple[str, float]:
        """This round's point ("itp": the signal's root estimate, nudged past it, inside
        ITP's window; "mid": the midpoint, where ITP keeps its promise by bisecting or the
        signal says nothing)."""
        lo, hi, tol = state.lo, state.hi, self.settings.tol
        mid = 0.5 * (lo + hi)
        first, budget = self.budget
        # after this round the bracket must be no wider than bisection's would be at the
        # end of the budget: width <= tol 2**(rounds left), whichever way the verdict goes
        # (a hair under, so that rounding at the last round cannot leave it above tol)
        window = tol * 2.0 ** (budget - (state.round - first) - 1) * (1.0 - 1e-6)
        if 2.0 * window <= hi - lo:  # no room left: bisection keeps the promise
            return "mid", mid
        estimate = self.root_estimate(state)
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
        if not lo < probe < hi or probe in state.known:
            return "mid", mid
        return "itp", probe

    def root_estimate(self, state: BracketState) -> float | None:
        """Where the friction reserve crosses zero inside (lo, hi), or None: the secant
        through the bracket ends when both carry a reserve whose sign agrees with their
        verdict (reserve > 0: stick), else a unit slope from the end that does (the
        reserve is mu minus a demand that moves slowly with mu)."""
        lo, hi = state.lo, state.hi
        return next((e for e in self._estimates(state) if e is not None and lo < e < hi), None)

    def _estimates(self, state: BracketState):
        """Root estimates, best first (lazily: each is tried only if the ones before it
        fall outside the bracket)."""
        lo, hi, signal = state.lo, state.hi, state.signal
        recent = [mu for _, mu in sorted(state.decided)[-2:] if state.agrees(mu)]
        if len(recent) == 2 and signal[recent[0]] != signal[recent[1]]:
            # the secant through the last two runs: no stagnation at a far end
            a, b = recent
            yield zero_crossing(b, signal[b], a, signal[a])
        if state.agrees(lo) and state.agrees(hi):
            # the reserve's sign agrees with both (different) verdicts, so signals differ
            yield zero_crossing(lo, signal[lo], hi, signal[hi])
        else:
            end = next((mu for mu in (hi, lo) if state.agrees(mu)), None)
            yield None if end is None else end - signal[end]
        yield self._past_a_contradiction(state)

    def _past_a_contradiction(self, state: BracketState) -> float | None:
        """Where the jump may lie when a bracket end's reserve has the wrong sign by d (a
        stick at reserve -d, or a not-stick at +d): the reserve is biased there (contact
        compliance, a brake torque), so the jump lies beyond that end, where the reserve
        is further from zero. Aim where it is 3 d + tol from zero (unit slope): a bias b
        then costs about log3(b / d) rounds before a probe crosses, not a bisection of the
        bracket. Once the other end's reserve has the same sign and is further out, the
        bias lies between the two: aim at their geometric mean (interpolated)."""
        tol = self.settings.tol
        for end, other in ((state.hi, state.lo), (state.lo, state.hi)):
            if end not in state.signal or state.agrees(end):
                continue
            s_end = state.signal[end]
            d = abs(s_end)
            toward = 1.0 if other > end else -1.0
            s_other = state.signal.get(other)
            if s_other is not None and s_other * s_end > 0 and abs(s_other) > d:
                target = math.sqrt(abs(s_other) * d)
                if target < 3.0 * d + tol:
                    return end + (other - end) * (target - d) / (abs(s_other) - d)
            return end + toward * (2.0 * d + tol)
        return None

    def guided_end(self, state: BracketState, end: float, far: float) -> float:
        """The far end of a widened bracket that reaches from `end` to at most `far`: just
        past the reserve's root where both ends' reserves agree with their (equal) verdicts
        and extrapolate to a root between end and far, else `far` (geometric widening)."""
        if not self.settings.interpolates:
            return far
        other = state.hi if end == state.lo else state.lo
        signal = state.signal
        if not (state.agrees(end) and state.agrees(other)) or signal[end] == signal[other]:
            return far
        root = zero_crossing(end, signal[end], other, signal[other])
        direction = 1.0 if far > end else -1.0
        reach = (root - end) * direction  # how far beyond `end` the root lies
        if not 0.0 < reach < abs(far - end):
            return far
        step = max(reach + 0.5 * self.settings.tol, self.settings.tol * (1.0 - 1e-6))
        return end + direction * min(step, abs(far - end))
