"""Which points a bisection round runs, and which strategy chose them. Pure Python.

One strategy picks each round's interior points, in this order:

* `straddle`: around undecided mu inside the bracket (straddle.py);
* `expand`, `aim`, `ladder`: away from a deferred run, or its retry (deferral.py), until
  the search has spent a multiple of its round budget (itp.py `overspent`);
* `itp`, `mid`: the friction reserve's root estimate inside ITP's window, or the midpoint
  (itp.py; split 2 with `root_finder: itp`);
* `split`: the fixed schedule (`split_points`): k - 1 points cutting the bracket into
  k = `split` equal parts, all at once (they may run in parallel); the last round uses
  the fewest parts that reach tol (at most k), so no run is wasted. k = 2 is plain
  bisection.

The points are chosen once per round (and anew after a deferral), never by how many workers
are idle or the order results arrive in. `splits` tells whether they can still split the
bracket: points strictly inside it, distinct, none an undecided mu (run again, it would
only come back undecided again). Where mu resolves no finer they cannot, and the search
must end there (bisection.py).
"""

from __future__ import annotations

from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.bracket import BracketState
from frictiondisk.tasks.jump_search.deferral import Deferrals
from frictiondisk.tasks.jump_search.itp import ItpProbe
from frictiondisk.tasks.jump_search.straddle import Straddle


def split_points(lo: float, hi: float, tol: float, split: int) -> list[float]:
    """lo + j (hi - lo) / parts, j = 1 .. parts - 1: `split` parts, or the fewest that
    reach tol (same test as the convergence)."""
    width = hi - lo
    parts = split
    while parts > 2 and width / (parts - 1) <= tol * (1 + 1e-9):
        parts -= 1
    return [lo + j * width / parts for j in range(1, parts)]


class Probes:
    """Each round's interior points of one bisection (module docstring)."""

    def __init__(
        self,
        settings: BisectionSettings,
        state: BracketState,
        straddle: Straddle,
        deferrals: Deferrals,
        itp: ItpProbe,
    ):
        self.settings = settings
        self.state = state
        self.straddle = straddle
        self.deferrals = deferrals
        self.itp = itp
        self._cache: tuple[tuple[int, int], str, list[float]] | None = None

    def _key(self) -> tuple[int, int]:
        return (self.state.round, self.deferrals.epoch)

    def interior(self) -> list[float]:
        """This round's interior points, increasing; chosen once per round and deferral
        (pending() asks again after every result)."""
        if self._cache is None or self._cache[0] != self._key():
            kind, mus = self._choose()
            self._cache = (self._key(), kind, mus)
        return self._cache[2]

    def kind(self) -> str | None:
        """How this round's interior was chosen (module docstring); None before it is."""
        cache = self._cache
        return cache[1] if cache is not None and cache[0] == self._key() else None

    def _choose(self) -> tuple[str, list[float]]:
        state = self.state
        span = self.straddle.span(state)
        if span is not None:
            return "straddle", self.straddle.probes(state, span)
        deferred = self.deferrals.inside(state, self.straddle.undecided)
        if deferred is not None and not self.itp.overspent(state):
            return self.deferrals.away_from(state, deferred)
        if self.settings.interpolates:
            kind, probe = self.itp.choose(state)
            return kind, [probe]
        return "split", split_points(state.lo, state.hi, self.settings.tol, self.settings.split)

    def splits(self, mus: list[float]) -> bool:
        """Whether `mus` can split the bracket (module docstring)."""
        lo, hi, undecided = self.state.lo, self.state.hi, self.straddle.undecided
        inside = all(lo < mu < hi and mu not in undecided for mu in mus)
        return bool(mus) and inside and len(set(mus)) == len(mus)
