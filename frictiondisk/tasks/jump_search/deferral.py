"""The probe strategy after a missed prediction: deferred runs and the steps away from
them (the rules in expanding.py). Pure Python.

An undetermined run at a predicted bracket's end, or at an interpolating probe, is
*deferred*: its retry waits while the next probes step away from it towards the
bracket's sticking end (geometrically, or aimed by the friction reserve), until that end
lies within tol of it and its retry is due (it is then *laddered*: never deferred again).
`Deferrals` keeps those runs and chooses the probes; the bisection (bisection.py) moves
the bracket.
"""

from __future__ import annotations

from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.bracket import BracketState
from frictiondisk.tasks.jump_search.expanding import expanding_probe, ladder_due
from frictiondisk.tasks.jump_search.runs import RunRequest

DEFERRING_KINDS = ("itp", "expand", "aim")  # probes whose undetermined run is deferred
STEPPING_KINDS = ("expand", "aim")  # probes whose steps away from a deferred run go on


class Deferrals:
    """The deferred runs of one bisection and the probes away from them (module docstring)."""

    def __init__(self, settings: BisectionSettings):
        self.settings = settings
        self.deferred: list[float] = []  # their mu, in the order they were deferred
        self.steps: dict[float, int] = {}  # deferred mu -> probes made away from it
        self.signal: dict[float, float] = {}  # deferred mu -> its reserve (a guide)
        self.expand_steps = 0  # the steps of this round's probe away from a deferred run
        self.laddered: set[float] = set()  # mu whose retry is due: never deferred again
        self.epoch = 0  # bumped on every deferral: the round's probes are chosen anew

    def stick_end(self, state: BracketState) -> float:
        return state.hi if self.settings.rising else state.lo

    def ladder(self, mu: float) -> None:
        """`mu`'s retry is due now (as a bracket end or a probe): no longer deferred."""
        self.laddered.add(mu)
        if mu in self.deferred:
            self.deferred.remove(mu)

    def inside(self, state: BracketState, undecided: list[float]) -> float | None:
        """The deferred run inside the bracket nearest its sticking end, if any."""
        inside = [
            mu
            for mu in self.deferred
            if state.lo < mu < state.hi and mu not in state.known and mu not in undecided
        ]
        if not inside:
            return None
        stick = self.stick_end(state)
        return min(inside, key=lambda mu: abs(stick - mu))

    def away_from(self, state: BracketState, deferred: float) -> tuple[str, list[float]]:
        """The next probe away from a deferred run towards the sticking end: at the
        reserve's estimate of the jump where it has one, else a geometric step; or the
        run's retry once that end lies within tol of it."""
        tol = self.settings.tol
        if not ladder_due(deferred, self.stick_end(state), tol):
            aimed = self._aim_past(state, deferred)
            if aimed is not None:
                self.expand_steps = self.steps.get(deferred, 0)
                return "aim", [aimed]
            steps = self.steps.get(deferred, 0) + 1
            probe = expanding_probe(deferred, self.stick_end(state), tol, steps)
            if state.lo < probe < state.hi and probe not in state.known:
                self.steps[deferred] = self.expand_steps = steps
                return "expand", [probe]
        self.laddered.add(deferred)
        return "ladder", [deferred]

    def _aim_past(self, state: BracketState, deferred: float) -> float | None:
        """A probe between a deferred run and the sticking end aimed at the jump by the
        reserve (unit slope from whichever of the two reads nearest zero: an undetermined
        run's reserve is no verdict, but it says where the jump lies), nudged half a tol
        towards the sticking end, or a tol from that end where the jump lies within a tol
        of it; None where the reserve says nothing, contradicts the sticking end's verdict,
        or aims no farther from the deferred run than the next geometric step (a probe
        that near would land in the same slow band): then the steps are geometric."""
        stick, tol = self.stick_end(state), self.settings.tol
        if not self.settings.rising or (stick in state.signal and not state.agrees(stick)):
            return None
        readings = [(mu, state.signal[mu]) for mu in (stick,) if mu in state.signal]
        if deferred in self.signal:
            readings.append((deferred, self.signal[deferred]))
        if not readings:
            return None
        mu, reading = min(readings, key=lambda pair: abs(pair[1]))
        estimate = mu - reading
        toward = 1.0 if stick > deferred else -1.0
        if abs(stick - estimate) < tol:
            probe = stick - toward * tol * (1.0 - 1e-6)
        else:
            probe = estimate + toward * 0.5 * tol
        step = expanding_probe(deferred, stick, tol, self.steps.get(deferred, 0) + 1)
        far_enough = (probe - deferred) * toward >= abs(step - deferred) * (1 - 1e-9)
        if not far_enough or (stick - probe) * toward <= 0:
            return None
        return None if probe in state.known or probe in self.deferred else probe

    def defer(self, state: BracketState, request: RunRequest, kind: str | None, reserve) -> bool:
        """Postpone the retry of an undetermined run (a predicted bracket's end, or a probe
        at a prediction of `kind`) and keep its reserve as a guide; False where its retry
        is due now."""
        mu, expanding = request.mu, self.settings.expanding
        if request.level >= self.settings.max_retries or mu in self.laddered:
            return False
        if state.phase == "check":
            if not (expanding.predicted and mu in (state.lo, state.hi)):
                return False
        elif not (expanding.defer and kind in DEFERRING_KINDS):
            return False
        self.deferred.append(mu)
        if kind in STEPPING_KINDS:  # the steps from it go on growing
            self.steps[mu] = self.expand_steps
        state.level[mu] = request.level + 1
        self.epoch += 1
        corrected = self.settings.corrected(mu, reserve)
        if corrected is not None:
            self.signal[mu] = corrected
        return True
