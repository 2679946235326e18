"""The trace's state machines on synthetic planes whose jump curves are known exactly
(frictiondisk.tasks.trace.tracer, trace_branch, trace_joins, fold, plane): no simulation.

Each plane says stick / not stick at (key, mu) from a formula; the oracles are the
formula's curves and tips, with tolerances in units of the requested tol."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from frictiondisk.model.search_settings import Certify
from frictiondisk.tasks.trace.plane import PlaneRequest, found_bracket, line_bisection
from frictiondisk.tasks.trace.steps import Plane
from frictiondisk.tasks.trace.tracer import Tracer, TraceSettings, key_turns

TOL = 1e-3


class Settings:
    """What a line bisection reads of a campaign task."""

    max_retries = 1
    split = 2
    certify = Certify()
    root_finder = "itp"


def settings(key_range, mu_range, resolution=0.1, keys=3, mus=21, **overrides):
    plane = Plane("params.x_ms", key_range, mu_range, TOL)
    base = dict(
        plane=plane,
        look_keys=tuple(np.linspace(*key_range, keys)),
        look_mus=tuple(np.linspace(*mu_range, mus)),
        stride=1,
        max_step=resolution,
        min_step=max(resolution / 32, 4 * plane.scaled_tol),
        first_step=resolution / 2,
        max_points=400,
        max_retries=1,
        split=2,
        certify=Certify(),
        root_finder="itp",
    )
    return TraceSettings(**{**base, **overrides})


def answer(sticks, request: PlaneRequest) -> dict:
    outcome = "stick" if sticks(request.key, request.mu) else "stick_slip"
    return {"outcome": outcome, "reserve": None}


def drive(tracer: Tracer, sticks, order=None) -> int:
    """Answer every request until the tracer is done; `order` shuffles each batch (the
    order results come back in). Returns the number of runs made."""
    made = 0
    while not tracer.done:
        batch = list(tracer.pending())
        if order is not None:
            order(batch)
        for request in batch:
            if request in tracer.pending():
                tracer.feed(request, answer(sticks, request))
                made += 1
    return made


def points_of(result):
    return [
        (p.bracket.along, p.bracket.key, p.bracket.mu, p.bracket.lo, p.bracket.hi)
        for curve in result.curves
        for p in curve.points
    ]


# ---- one line of the plane ------------------------------------------------------------------
@pytest.mark.parametrize("fixed, stick_high", [("key", True), ("key", False), ("mu", True)])
def test_a_line_bisection_finds_a_jump_whichever_side_sticks(fixed, stick_high):
    """Along mu (stick above or below) and along the key, a certified bracket of width <= tol
    around the jump at 0.4, with the sticking end where it was said to be."""
    jump = 0.4
    search = line_bisection(fixed, 0.7, (0.35, 0.38), (0.0, 1.0), stick_high, TOL, Settings())

    def verdict(request):
        x = request.mu if fixed == "key" else request.key
        return {"outcome": "stick" if (x > jump) == stick_high else "slide", "reserve": None}

    while not search.done:
        for request in search.pending():
            search.feed(request, verdict(request))
    found = found_bracket(search)
    assert found is not None and found.along == ("mu" if fixed == "key" else "key")
    assert found.lo <= jump <= found.hi and found.width <= TOL * (1 + 1e-9)
    assert found.stick_high == stick_high
    assert found.certification == "certified"
    assert any(run.request.strict for run in found.result.runs)  # the ladder ran


def test_key_turns_ignores_reversals_within_the_threshold():
    xs = [0.0, 0.1, 0.2, 0.2005, 0.1998, 0.3, 0.25, 0.1, 0.15]
    assert key_turns(xs, 0.01) == [(5, 1.0), (7, -1.0)]


# ---- whole planes ---------------------------------------------------------------------------
def test_a_straight_jump_line_is_followed_edge_to_edge_within_tol():
    """stick iff mu >= 0.2 + 0.5 key: one curve, edge to edge, every point's bracket
    holding the line, the first and last points on the plane's key edges."""

    def sticks(key, mu):
        return mu >= 0.2 + 0.5 * key

    tracer = Tracer(settings((0.0, 1.0), (0.0, 1.0)))
    drive(tracer, sticks)
    result = tracer.result()
    assert result.status == "converged", result.reason
    (curve,) = result.curves
    assert curve.ends == {+1: "edge", -1: "edge"}
    keys = [p.bracket.key for p in curve.points]
    assert keys[0] == 0.0 and keys[-1] == 1.0 and keys == sorted(keys)  # loop order: +key
    for point in curve.points:
        b = point.bracket
        assert b.along == "mu" and b.stick_high and b.width <= TOL * (1 + 1e-9)
        assert b.lo <= 0.2 + 0.5 * b.key <= b.hi
    steps = np.diff(np.array([p.position for p in curve.points]), axis=0)
    assert np.hypot(*steps.T).max() <= 0.1 + 2 * TOL  # resolution, scaled


def test_a_jump_in_a_band_of_undecided_mu_is_followed_edge_to_edge():
    """stick iff mu >= 0.21 + 0.5 key, but for key > 0.3 runs within 2.5 tol of the jump
    stay undetermined after every retry (a braked disk's slow approach, Fig 11 from rest):
    the corrections whose predicted ends fall into the band move them out and straddle
    it, and the curve is followed edge to edge with every bracket holding the jump."""
    band = 2.5 * TOL

    def jump(key):
        return 0.21 + 0.5 * key

    def reply(request: PlaneRequest) -> dict:
        if request.key > 0.3 and abs(request.mu - jump(request.key)) < band:
            return {"outcome": "undetermined", "reason": "slow approach", "reserve": None}
        return answer(lambda key, mu: mu >= jump(key), request)

    tracer = Tracer(settings((0.0, 1.0), (0.0, 1.0)))
    while not tracer.done:
        for request in list(tracer.pending()):
            if request in tracer.pending():
                tracer.feed(request, reply(request))
    result = tracer.result()
    assert result.status == "converged", result.reason
    (curve,) = result.curves
    assert curve.ends == {+1: "edge", -1: "edge"}
    keys = [p.bracket.key for p in curve.points]
    assert keys[0] == 0.0 and keys[-1] == 1.0 and keys == sorted(keys)
    straddled = 0
    for point in curve.points:
        b = point.bracket
        assert b.lo <= jump(b.key) <= b.hi
        assert b.width <= 2 * band + TOL * (1 + 1e-9)
        straddled += b.width > TOL * (1 + 1e-9)
    assert straddled > 0  # the band was met, not stepped round


def test_a_closed_window_is_one_closed_curve_with_its_two_folds_located():
    """stick inside an ellipse: a closed curve, and the two tips in the key (smooth folds,
    key 0.5 -/+ 0.3 at mu 0.5) located to tol in both coordinates."""
    centre, a, b = (0.5, 0.5), 0.3, 0.2

    def sticks(key, mu):
        return ((key - centre[0]) / a) ** 2 + ((mu - centre[1]) / b) ** 2 <= 1.0

    tracer = Tracer(settings((0.0, 1.0), (0.0, 1.0), keys=3))
    drive(tracer, sticks)
    result = tracer.result()
    assert result.status == "converged", result.reason
    (curve,) = result.curves
    assert curve.closed
    tips = sorted(fold.key for _, fold in result.folds)
    assert len(tips) == 2
    for fold, tip in zip(
        sorted((f for _, f in result.folds), key=lambda f: f.key), (0.2, 0.8), strict=True
    ):
        assert fold.status == "located" and fold.inner_sticks
        assert fold.certification == "certified"
        low, high = sorted((fold.key_in, fold.key_out))
        assert low <= tip <= high and high - low <= TOL * (1 + 1e-9)
        assert fold.mu_lo <= 0.5 <= fold.mu_hi and fold.mu_hi - fold.mu_lo <= 3 * TOL * (1 + 1e-9)


def test_a_wedge_s_corner_is_turned_and_located():
    """A sticking window between mu = 0.3 (rising) and mu = 0.7 - key (falling) closes at
    a corner, key 0.4: one curve around it, its fold at (0.4, 0.3) to tol."""

    def sticks(key, mu):
        return 0.3 <= mu <= 0.7 - key

    tracer = Tracer(settings((0.0, 1.0), (0.0, 1.0), keys=2))
    drive(tracer, sticks)
    result = tracer.result()
    assert result.status == "converged", result.reason
    (curve,) = result.curves
    assert curve.ends == {+1: "edge", -1: "edge"}
    ((_, fold),) = result.folds
    assert fold.status == "located" and fold.inner_sticks
    low, high = sorted((fold.key_in, fold.key_out))
    assert low <= 0.4 + TOL and high >= 0.4 - TOL and high - low <= TOL * (1 + 1e-9)
    assert fold.mu_lo - TOL <= 0.3 <= fold.mu_hi + TOL


def test_results_do_not_depend_on_the_order_runs_come_back_in():
    """Two seeds of one curve meet in the middle; the same points whatever the order
    each round's results arrive in (rounds: decisions on outcomes only)."""

    def sticks(key, mu):
        return mu >= 0.3 + 0.2 * math.sin(3 * key)

    runs = []
    outcomes = []
    for order in (None, list.reverse, random.Random(7).shuffle):
        tracer = Tracer(settings((0.0, 1.0), (0.0, 1.0), keys=3))
        runs.append(drive(tracer, sticks, order))
        result = tracer.result()
        outcomes.append((points_of(result), [r.request for r in result.runs]))
    assert outcomes[0] == outcomes[1] == outcomes[2]
    assert len(tracer.result().curves) == 1  # the three seeds' pieces joined


def test_a_correction_does_not_widen_across_a_narrow_gap_onto_another_jump():
    """Two rising jumps 0.04 apart (stick, not stick, stick): every point stays on its own
    curve, although a first step's bracket would span both."""

    def sticks(key, mu):
        return 0.4 <= mu <= 0.5 or mu >= 0.54

    tracer = Tracer(settings((0.0, 1.0), (0.0, 1.0), keys=2, resolution=0.2, mus=41))
    drive(tracer, sticks)
    result = tracer.result()
    assert result.status == "converged", result.reason
    for curve in result.curves:
        levels = {round(p.bracket.mu, 2) for p in curve.points}
        assert len(levels) == 1, levels  # one jump per curve: 0.4, 0.5 or 0.54
    assert sorted(round(c.points[0].bracket.mu, 2) for c in result.curves) == [0.4, 0.5, 0.54]


@pytest.mark.parametrize("shift", [5 * TOL, -5 * TOL])
def test_a_fold_whose_tip_moves_at_stricter_numerics_is_followed_there(shift):
    """At the next level the window reaches 5 tol further (the check's probe a key
    tolerance beyond the tip still sticks) or ends 5 tol sooner (a jump at the tip
    vanishes): the fold is located again at that level and certified one level above,
    `recertified`, not left `uncertain`."""
    centre, b = (0.5, 0.5), 0.2

    def sticks(key, mu, strict):
        a = 0.3 + (shift if strict else 0.0)
        return ((key - centre[0]) / a) ** 2 + ((mu - centre[1]) / b) ** 2 <= 1.0

    tracer = Tracer(settings((0.0, 1.0), (0.0, 1.0), keys=3))
    while not tracer.done:
        for request in list(tracer.pending()):
            if request in tracer.pending():
                outcome = "stick" if sticks(request.key, request.mu, request.strict) else "slide"
                tracer.feed(request, {"outcome": outcome, "reserve": None})
    result = tracer.result()
    assert result.status == "converged", result.reason
    folds = sorted((f for _, f in result.folds), key=lambda f: f.key)
    assert len(folds) == 2
    for fold, tip in zip(folds, (0.2 - shift, 0.8 + shift), strict=True):
        assert fold.status == "located" and fold.certification == "recertified"
        low, high = sorted((fold.key_in, fold.key_out))
        assert low <= tip <= high and high - low <= TOL * (1 + 1e-9)
