"""The probe strategy around mu left undetermined after every retry. Pure Python.

Near the jump the motion slows down (critical slowing down): a run there may stay
undetermined after every retry with a longer horizon. Such an *undecided* mu inside the
bracket (or a bracket end that can move outwards past it, bisection.py) is not a failure
while the undecided mu span at most `UNDECIDED_SPAN` tol: the bisection then straddles
them, probing the gaps below and above, and converges once the bracket is their span plus
tol (or both gaps are within tol / 2). Plain bisection only; multisection keeps its
fixed schedule.
"""

from __future__ import annotations

from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.bracket import BracketState

UNDECIDED_SPAN = 10  # [tol] undecided mu a bracket may straddle: wider is a failure


class Straddle:
    """The undecided mu of one bisection and the probes around them (module docstring)."""

    def __init__(self, settings: BisectionSettings):
        self.settings = settings
        # interior mu still undetermined after every retry: the jump's slow approach
        self.undecided: list[float] = []
        self.stalled_at: float | None = None  # the mu undetermined after every retry that failed it

    def inside(self, state: BracketState) -> list[float]:
        """The undecided mu that lie inside the current bracket."""
        return [mu for mu in self.undecided if state.lo < mu < state.hi]

    def span(self, state: BracketState) -> tuple[float, float] | None:
        """(lowest, highest) undecided mu inside the bracket, if any (plain bisection only)."""
        inside = self.inside(state)
        return (min(inside), max(inside)) if inside and self.settings.plain else None

    def within_span(self, mus: list[float]) -> bool:
        """Whether undecided mu span at most UNDECIDED_SPAN tol (a bracket may straddle them)."""
        return max(mus) - min(mus) <= UNDECIDED_SPAN * self.settings.tol * (1 + 1e-9)

    def may_take(self, state: BracketState, mu: float) -> bool:
        """Whether `mu`, undetermined after every retry, is straddled (bisect phase, plain
        bisection, within the span) rather than ending the search."""
        if state.phase != "bisect" or not self.settings.plain:
            return False
        span = self.span(state)
        return span is None or self.within_span([*span, mu])

    def open_sides(self, state: BracketState, span: tuple[float, float]) -> tuple[bool, bool]:
        """Whether the gaps below and above the undecided mu [u_lo, u_hi] are wider than
        tol / 2: a closed side is not split again (probes there would halve that gap
        forever while the other side's decided probe waits), and with both closed the
        bracket has converged."""
        half = 0.5 * self.settings.tol
        return span[0] - state.lo > half, state.hi - span[1] > half

    def probes(self, state: BracketState, span: tuple[float, float]) -> list[float]:
        """Around the undecided mu [u_lo, u_hi], the midpoints of (lo, u_lo) and (u_hi, hi),
        but at most UNDECIDED_SPAN / 2 tol away (a wide bracket's midpoint once hit a far
        transient) and none on a side within tol / 2 of its end."""
        near = 0.5 * UNDECIDED_SPAN * self.settings.tol
        below, above = 0.5 * (state.lo + span[0]), 0.5 * (span[1] + state.hi)
        below_open, above_open = self.open_sides(state, span)
        probes = [max(below, span[0] - near)] if below_open else []
        if above_open:
            probes.append(min(above, span[1] + near))
        return probes

    def converged(self, state: BracketState) -> bool:
        """Converged at a width <= tol, or, around undecided mu, at a width of their span
        plus tol (or both gaps beside them within tol / 2)."""
        span = self.span(state)
        spread = 0.0 if span is None else span[1] - span[0]
        closed = span is not None and not any(self.open_sides(state, span))
        return closed or state.hi - state.lo <= (self.settings.tol + spread) * (1 + 1e-9)

    def note(self, state: BracketState) -> str:
        """How a converged bracket's reason names the undecided mu it straddles."""
        inside = sorted(self.inside(state))
        if not inside:
            return f" <= tol {self.settings.tol:.3g}"
        mus = ", ".join(f"{mu:.10g}" for mu in inside)
        return (
            f" around mu = {mus}, undetermined after every retry (the jump's slow approach, "
            f"bracketed from both sides to its span + tol {self.settings.tol:.3g})"
        )
