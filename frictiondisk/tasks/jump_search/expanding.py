"""How a bisection reaches past a prediction that missed. Pure Python.

A bracket predicted from the points already done (a find_jump line's warm start), or an
interpolating probe at the friction reserve's root estimate, is a guess of mu*. When it
misses, the search should find the jump again in a few runs, not spend the horizon ladder
(retries at 2x, 4x the horizon) inside the jump's slow approach, where the guess lands
when the reserve is biased:

* a predicted bracket whose ends agree widens geometrically from the prediction: its own
  width x `widen` (8: x8, x64, ...), as an expanding search does, and never past the
  campaign's `full` bracket before that bracket's end has been tried;
* a predicted bracket with an end undetermined keeps that end *deferred* (its retry
  postponed) and moves it out by the bracket's width x `widen`, unless the other end
  holds within tol of it (then nothing else can close the bracket: the ladder is due);
* an interpolating probe that comes back undetermined is deferred too, and the next probes
  step away from it towards the bracket's sticking end, tol x 8, x 64, ... (at most half
  the way to that end), or, where the reserve (the undetermined run's own, or the
  sticking end's) puts the jump farther away than that step, half a tol past the jump it
  reads (Bisection._aim_past): a decided not-stick beyond it leaves it outside the
  bracket, never retried; a stick brings the sticking end to it, and once that end is
  within tol of it its retry is due (`ladder_due`).

Verdicts alone move a bracket; a deferred run is no evidence either way. Plain bisection
(`root_finder: bisect`) and multisection keep their fixed schedule.
"""

from __future__ import annotations

import dataclasses

WIDEN_FACTOR = 2.0  # a bracket whose ends agree is widened to this many times its width
EXPAND_FACTOR = 8.0  # the same from a prediction, and each step away from a deferred run


@dataclasses.dataclass(frozen=True)
class Expanding:
    """How a search reaches past a missed prediction (module docstring)."""

    widen: float = WIDEN_FACTOR  # a bracket whose ends agree widens to this x its width
    defer: bool = False  # an undetermined interpolating probe is deferred, not retried at once
    predicted: bool = False  # the bracket is a prediction: an undetermined end widens it
    full: tuple[float, float] | None = None  # a widening stops at this bracket's ends first


PLAIN = Expanding()  # today's search: widen x2, every undetermined run retried at once
PREDICTED = Expanding(widen=EXPAND_FACTOR, defer=True, predicted=True)


def widened_end(end: float, width: float, upwards: bool, settings: Expanding, limits) -> float:
    """The far end of a bracket widened beyond `end` to `settings.widen` x `width`, within
    `limits`, stopping first at the end of the full bracket where it lies in between."""
    if upwards:
        far = min(limits[1], end + settings.widen * width)
        full = settings.full[1] if settings.full else None
        return full if full is not None and end < full < far else far
    far = max(limits[0], end - settings.widen * width)
    full = settings.full[0] if settings.full else None
    return full if full is not None and far < full < end else far


def expanding_probe(deferred: float, stick_end: float, tol: float, steps: int) -> float:
    """The `steps`-th probe (1, 2, ...) away from a deferred run towards the sticking end:
    tol x 8**steps from it, at most half the way to that end."""
    gap = stick_end - deferred
    step = min(EXPAND_FACTOR**steps * tol, 0.5 * abs(gap))
    return deferred + (step if gap > 0 else -step)


def ladder_due(deferred: float, stick_end: float, tol: float) -> bool:
    """A deferred run is retried once the sticking end lies within tol of it: a not-stick
    there would close the bracket, and no probe elsewhere can."""
    return abs(stick_end - deferred) <= tol * (1 + 1e-9)
