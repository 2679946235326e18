"""A prescan that looks where motions change (tasks/jump_search/prescan.py MotionRefinement,
jumps.py): where two neighbouring grid values below the headline name different not-stick
motions, runs between them down to the persistence width find a sticking window that sits
on the boundary (issue 65's Stribeck disk from rest: self-centring at 0.08, a whirl at 0.10,
and a window that sticks for good on [0.0900, 0.0963] below a certified mu* of 0.2079)."""

from __future__ import annotations

import numpy as np
import pytest

from frictiondisk.model.search_settings import Certify
from frictiondisk.tasks.jump_search.jumps import JumpSearch
from frictiondisk.tasks.jump_search.prescan import (
    MOTION_REFINE_BUDGET,
    motion_boundaries,
    motions_differ,
)

TOL = 1e-4
MAIN_JUMP = 0.2079
GRID = tuple(np.round(np.arange(0.02, 0.40 + 0.01, 0.02), 6))


def drive(search, outcome_of):
    """Answer every pending request with outcome_of(mu); returns the requests made."""
    made = []
    while not search.done:
        pending = list(search.pending())
        assert pending, "a search that is not done must ask for a run"
        for request in pending:
            made.append(request)
            search.feed(request, {"outcome": outcome_of(request.mu), "reason": "oracle"})
    return made


def disk_from_rest(window=(0.0907, 0.0963)):
    """Self-centring below the window, a whirl (slide_cycle) above it, sticking in it and
    above the main jump: the window sits on the motion boundary, between grid values."""

    def outcome(mu):
        if window[0] <= mu <= window[1] or mu >= MAIN_JUMP:
            return "stick"
        return "self_centring" if mu < window[0] else "slide_cycle"

    return outcome


def search():
    return JumpSearch(GRID, TOL, 2, "decide", certify=Certify(), stride=1)


def test_a_window_on_the_boundary_between_two_motions_is_found():
    jumps = search()
    made = drive(jumps, disk_from_rest())
    res = jumps.result()
    assert res.status == "converged", res.reason
    # the headline is the window's rising edge, not the main jump 1150 tol above it
    assert res.mu_lo < 0.0907 <= res.mu_hi and res.mu_hi - res.mu_lo <= TOL * (1 + 1e-9)
    assert [(w.lo, w.hi) for w in res.windows] == [pytest.approx((0.0907, 0.0963), abs=TOL)]
    # the runs between 0.08 and 0.10 ran with the prescan's numerics, as prescan runs
    between = [r for r in made if 0.08 < r.mu < 0.10 and r.mu not in GRID and r.strict == 0]
    refined = [r for r in between if r.mode == "decide"]
    assert refined and all(res.role(r) == "prescan" for r in refined)
    assert res.grid_below.motion_runs == len(refined) and res.grid_below.unrefined == 0


def test_a_window_narrower_than_the_persistence_width_is_a_window_not_the_headline():
    jumps = search()
    drive(jumps, disk_from_rest(window=(0.0901, 0.0902)))
    res = jumps.result()
    assert res.mu_lo < MAIN_JUMP <= res.mu_hi
    # the boundary was refined to the persistence width: the window, one tol wide, is
    # found where a middle landed in it, or the pair ends within 3 tol of each other
    assert res.grid_below.unrefined == 0


def test_neighbours_of_one_motion_cost_no_refinement():
    def outcome(mu):
        return "stick" if mu >= MAIN_JUMP else "self_centring"

    jumps = search()
    drive(jumps, outcome)
    res = jumps.result()
    assert res.grid_below.motion_runs == 0 and res.certification == "certified"
    assert res.mu_lo < MAIN_JUMP <= res.mu_hi


def test_the_refinement_stays_within_its_budget_and_says_what_it_left():
    """Motions alternating at every grid value below mu*: the budget (runs per grid
    value) runs out before every pair is within the persistence width; the grid below is
    then not decided, and the point is uncertain with the reason."""

    def outcome(mu):
        if mu >= MAIN_JUMP:
            return "stick"
        return ("self_centring", "slide_cycle")[int(round(mu / 0.02)) % 2]

    jumps = search()
    drive(jumps, outcome)
    res = jumps.result()
    assert res.grid_below.motion_runs <= MOTION_REFINE_BUDGET * len(GRID)
    assert res.grid_below.unrefined > 0
    assert res.certification == "uncertain"
    assert "left wider than the persistence width" in res.reason
    assert "refinement budget spent" in res.reason


def test_which_neighbours_differ():
    assert motions_differ("self_centring", "slide_cycle")
    assert motions_differ("slide", "slide_cycle")  # not yet shown, next to a shown motion
    assert not motions_differ("slide", "slide")
    assert not motions_differ("stick", "slide_cycle")  # a jump, bisected as such
    decided = {0.08: "self_centring", 0.09: "self_centring", 0.10: "slide_cycle", 0.1001: "slide"}
    assert motion_boundaries(decided, 1.0, 3 * TOL) == [(0.09, 0.10)]
    assert motion_boundaries(decided, 0.095, 3 * TOL) == []  # only below the top
    # around a value undetermined after every retry: the parts beside it, to width / 2
    assert motion_boundaries(decided, 1.0, 0.01, undetermined=(0.095,)) == []
    assert motion_boundaries(decided, 1.0, 0.0099, undetermined=(0.095,)) == [
        (0.09, 0.095),
        (0.095, 0.10),
    ]


def test_a_middle_left_undetermined_is_refined_around_and_named():
    """A run between two motions that stays undetermined after every retry (a slow
    approach) decides nothing: the parts beside it are refined to half the persistence
    width (a window wider than the persistence width that holds it then holds a decided
    value too), and the reason names it."""
    slow = 0.5 * (0.08 + 0.10)

    def motions(mu):
        if mu >= MAIN_JUMP:
            return "stick"
        if mu == slow:
            return "undetermined"
        return "self_centring" if mu < slow else "slide_cycle"  # no window

    jumps = search()
    drive(jumps, motions)
    res = jumps.result()
    assert res.grid_below.unrefined == 0 and res.grid_below.unrefined_at == (slow,)
    assert "undetermined after every retry at mu = 0.09" in res.reason
    assert res.certification == "certified"


def test_a_band_left_undetermined_spends_the_budget_and_leaves_the_grid_uncertain():
    def motions(mu):
        if mu >= MAIN_JUMP:
            return "stick"
        if 0.085 < mu < 0.095:
            return "undetermined"
        return "self_centring" if mu < 0.09 else "slide_cycle"

    jumps = search()
    drive(jumps, motions)
    res = jumps.result()
    assert res.grid_below.unrefined > 0
    assert res.grid_below.motion_runs <= MOTION_REFINE_BUDGET * len(GRID)
    assert "refinement budget spent" in res.reason
    assert res.certification == "uncertain"
