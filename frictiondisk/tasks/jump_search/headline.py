"""Which jump of a point is its headline: the lowest rising jump whose sticking side
persists (jumps.py). Pure Python.

A rising jump's sticking side must hold over the persistence width (`persist` tol) above
the mu_hi of its bracket at the point's own numerics: the decided values in
(mu_hi, mu_hi + width] must all stick, and where none lies there, one run at
mu_hi + width is asked for. A jump that does not persist bounds a *window*; the headline
is the lowest jump that persists, else (none persists) the lowest rising jump. A
persistence run undetermined after every retry is taken, but leaves the jump *unjudged*
(not certified).
"""

from __future__ import annotations

from frictiondisk.tasks.jump_search.runs import BisectionResult


class Persistence:
    """The persistence of a point's rising jumps, and its headline (module docstring)."""

    def __init__(self, width: float):
        self.width = width  # [mu] persist x tol
        self.at: dict[int, float] = {}  # bisection index -> its persistence mu
        self.unjudged: set[int] = set()  # rising jumps whose persistence run stayed undetermined

    @staticmethod
    def rising_jumps(bisections) -> list[tuple[int, BisectionResult, BisectionResult]]:
        """(index, result, base) of the converged rising jumps, increasing in mu: the
        reported result (after certification) and the bracket at the point's own numerics."""
        found = []
        for index, bisection in enumerate(bisections):
            res = bisection.result()
            base = bisection.searches[0].result()
            if (
                res.status == base.status == "converged"
                and res.rising
                and res.certification != "vanished"
            ):
                found.append((index, res, base))
        return sorted(found, key=lambda item: item[2].mu_lo)

    def persists(self, index: int, base, known: dict[float, bool], checks) -> bool | None:
        """Whether rising jump `index` sticks over the persistence width above the mu_hi of
        its bracket at the point's own numerics: by the decided values in
        (mu_hi, mu_hi + width]; None until one is there (`checks`: the settled persistence
        and fill runs, by mu)."""
        mu = self.at.setdefault(index, base.mu_hi + self.width)
        above = [m for m in known if base.mu_hi < m <= mu]
        if not above:
            if mu in checks:  # undetermined after every retry: taken, but not certified
                self.unjudged.add(index)
                return True
            return None
        return all(known[m] for m in above)

    def wanted(self, bisections, known: dict[float, bool], checks) -> set[float]:
        """The persistence run that the lowest rising jump not yet judged needs; empty once
        the headline is found (or no rising jump is left)."""
        for index, _, base in self.rising_jumps(bisections):
            persists = self.persists(index, base, known, checks)
            if persists is None:
                return {self.at[index]}
            if persists:
                return set()
        return set()

    def headline(self, bisections, known: dict[float, bool], checks):
        """(bisection index, result) of the lowest rising jump that persists, else of the
        lowest rising jump; None without one."""
        rising = self.rising_jumps(bisections)
        for index, res, base in rising:
            if self.persists(index, base, known, checks):
                return index, res
        return (rising[0][0], rising[0][1]) if rising else None

    def nowhere(self, bisections, known: dict[float, bool], checks) -> bool:
        """Rising jumps, but none persists (JumpSearch.persists_nowhere)."""
        rising = self.rising_jumps(bisections)
        return bool(rising) and not any(
            self.persists(i, base, known, checks) for i, _, base in rising
        )


def never_sticks(scan, checks, between) -> bool:
    """Every prescan value run decided not stick (`scan`: its last retry at each), and no
    fill run sticks (`checks`; one left undetermined leaves the grid less than wholly
    decided)."""
    return (
        bool(scan)
        and all(between.is_low(run.outcome) for run in scan)
        and all(not between.is_high(run.outcome) for run in checks)
    )
