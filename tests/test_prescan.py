"""The adaptive prescan (frictiondisk/tasks/jump_search/prescan.py): a coarse grid, refined where verdicts
change or the friction reserve does not explain them; the same jumps as a dense prescan."""

import numpy as np
import pytest

from frictiondisk.model.scene import ConfigError
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.jump_search.jumps import JumpSearch
from frictiondisk.tasks.jump_search.prescan import (
    AdaptiveGrid,
    default_stride,
    needs_a_run_inside,
    stride_of,
)

GRID = tuple(float(mu) for mu in np.round(np.linspace(0.05, 0.40, 36), 6))


def linear_reserve(mu_star, offset=0.0):
    """A scene whose reserve is mu - mu_star (+ offset) and that sticks above mu_star."""

    def run(request):
        mu = request.mu
        outcome = "stick" if mu >= mu_star else "stick_slip"
        return {"outcome": outcome, "reserve": mu - mu_star + offset, "reason": "test"}

    return run


def islands(sticks, reserve=None):
    """Stick where sticks(mu); the reserve is `reserve(mu)` (None: never stuck, NaN)."""

    def run(request):
        mu = request.mu
        value = reserve(mu) if reserve else None
        return {
            "outcome": "stick" if sticks(mu) else "slide",
            "reserve": value,
            "reason": "test",
        }

    return run


def drive(search, answer):
    made = []
    while not search.done:
        for request in search.pending():
            made.append(request)
            search.feed(request, answer(request))
    return search.result(), made


def jumps(result):
    return [(j.rising, round(j.mu_star, 8)) for j in result.jumps]


def both(answer, stride, tol=1e-4):
    dense = drive(JumpSearch(GRID, tol, 2), answer)
    adaptive = drive(JumpSearch(GRID, tol, 2, stride=stride), answer)
    return dense, adaptive


def prescan_runs(made, search_result):
    """The runs of the prescan itself: before the grid below the headline is filled in."""
    return [r.request for r in search_result.prescan_runs]


def test_a_single_jump_gets_the_dense_bracket_in_a_third_of_the_prescan_runs():
    (dense, dense_runs), (adaptive, runs) = both(linear_reserve(0.2345), stride=6)
    assert adaptive.status == dense.status == "converged"
    # the same jump to the last digit: refined to the same neighbouring grid values, then
    # the same bisection
    assert jumps(adaptive) == jumps(dense)
    assert [j.mu_lo for j in adaptive.jumps] == [j.mu_lo for j in dense.jumps]
    assert len(prescan_runs(runs, adaptive)) <= len(GRID) / 3
    assert "adaptive prescan ran" in adaptive.reason
    # every grid value below the headline runs in the end (a skipped interval is
    # unexamined): the adaptive prescan saves the runs above it
    below = adaptive.grid_below
    assert below.decided == below.total == sum(mu < 0.2345 for mu in GRID)
    assert len(dense_runs) - len(runs) == sum(mu > 0.2345 for mu in GRID) - len(
        [r for r in prescan_runs(runs, adaptive) if r.mu > 0.2345]
    )


def test_the_reserve_picks_the_refinement_so_a_jump_costs_few_grid_runs():
    _, (adaptive, runs) = both(linear_reserve(0.2345), stride=6)
    coarse = len(range(0, len(GRID), 6)) + 1
    # an exact reserve points at the change: 2 grid runs, not log2(6) halvings and more
    assert len(prescan_runs(runs, adaptive)) <= coarse + 2


def test_a_sticking_window_narrower_than_the_stride_is_found_from_one_coarse_value():
    # stick only in [0.2, 0.23] (4 grid steps), stride 4: one coarse value (0.21) sticks,
    # and both of the window's edges are refined to the dense prescan's brackets
    window = islands(lambda mu: 0.2 <= mu <= 0.23, lambda mu: 0.015 - abs(mu - 0.215))
    (dense, _), (adaptive, _) = both(window, stride=4)
    assert len(dense.jumps) == 2
    assert jumps(adaptive) == jumps(dense)


def test_a_reserve_that_contradicts_its_verdict_makes_the_prescan_dense_there():
    # sticking window [0.2, 0.23] that the reserve does not show (positive everywhere, so
    # every not-stick run contradicts it): every interval with a not-stick end is refined
    # to neighbouring grid values; only the inside of the window (stick at both ends,
    # explained) is not
    window = islands(lambda mu: 0.2 <= mu <= 0.23, lambda mu: 1.0)
    (dense, _), (adaptive, runs) = both(window, stride=6)
    assert jumps(adaptive) == jumps(dense) and len(dense.jumps) == 2
    ran = {r.mu for r in prescan_runs(runs, adaptive)}
    assert ran == {mu for mu in GRID if not 0.2 <= mu <= 0.23} | {0.2, 0.23}


def test_a_window_the_reserve_does_not_show_is_missed_above_a_headline_only():
    # the documented limit: stick in [0.3, 0.33] with a reserve that is NaN (never stuck)
    # at every not-stick run, between coarse values that do not stick (0.29, 0.40), above
    # a headline (a jump at 0.1234, sticking up to 0.25 over the coarse value 0.17): skipped
    def sticks(mu):
        return 0.1234 <= mu <= 0.25 or 0.3 <= mu <= 0.33

    window = islands(sticks, lambda mu: 0.01 if sticks(mu) else None)
    (dense, _), (adaptive, _) = both(window, stride=12)
    assert len(dense.jumps) == 4
    assert jumps(adaptive) == jumps(dense)[:2]


def test_without_any_change_the_whole_grid_runs_and_finds_the_hidden_window():
    # the same hidden window with nothing sticking anywhere else: a point without a jump
    # is an answer only on its whole grid, so every value the prescan skipped runs
    window = islands(lambda mu: 0.2 <= mu <= 0.23, lambda mu: 0.01 if 0.2 <= mu <= 0.23 else None)
    (dense, _), (adaptive, _) = both(window, stride=12)
    assert len(dense.jumps) == 2
    assert jumps(adaptive) == jumps(dense) and adaptive.status == "converged"
    # and where nothing sticks at all: no jump, on every grid value
    (dense, _), (adaptive, runs) = both(islands(lambda mu: False), stride=12)
    assert adaptive.status == dense.status == "no_jump"
    assert {r.mu for r in runs} == set(GRID)
    assert adaptive.grid_below.decided == adaptive.grid_below.total == len(GRID)


def test_undetermined_values_are_refined_around_as_in_the_dense_prescan():
    def answer(request):
        if abs(request.mu - 0.23) < 1e-9:
            return {"outcome": "undetermined", "reserve": None, "reason": "slow"}
        return linear_reserve(0.2345)(request)

    (dense, _), (adaptive, runs) = both(answer, stride=6)
    assert jumps(adaptive) == jumps(dense)
    assert dense.status == adaptive.status


def test_needs_a_run_inside():
    stick = {"outcome": "stick", "reserve": 0.01}
    slip = {"outcome": "stick_slip", "reserve": -0.01}
    never = {"outcome": "slide", "reserve": None}
    assert needs_a_run_inside(slip, stick)  # verdicts differ
    assert not needs_a_run_inside(never, slip)  # both explained, no change
    assert not needs_a_run_inside(stick, stick)
    assert needs_a_run_inside({"outcome": "stick", "reserve": -0.01}, stick)
    assert needs_a_run_inside({"outcome": "slide", "reserve": 0.01}, never)
    assert needs_a_run_inside({"outcome": "undetermined", "reserve": None}, never)


def test_grid_refinement_stops_at_neighbouring_values():
    grid = AdaptiveGrid(tuple(range(10)), 4)
    assert grid.wanted == {0, 4, 8, 9}
    for k in sorted(grid.waiting):
        grid.settle(k, {"outcome": "stick" if k >= 8 else "slide", "reserve": None})
    assert grid.refine() == {6}
    with pytest.raises(ValueError, match="not asked for"):
        grid.settle(5, {"outcome": "stick"})


def test_default_stride():
    assert default_stride(36, "decide", "corotation") == 6
    assert default_stride(90, "decide", "corotation") == 9
    assert default_stride(36, "converge", "corotation") == 1  # every value is data
    assert default_stride(36, "decide", "contacts") == 1  # islands the reserve misses
    assert default_stride(5, "decide", "corotation") == 1


CAMPAIGN = """
name: t
scene: pin
find_jump:
  tol: 1.0e-3
  prescan: {{mu: {{start: 0.05, stop: 0.3, num: 26}}, mode: decide{extra}}}
  along: {{params.x_ms: [0.1]}}
"""


def test_spec_stride_is_checked_and_only_a_given_stride_enters_the_hash():
    auto = campaign_from_text(CAMPAIGN.format(extra=""), "<t>")
    assert auto.task.prescan.stride is None
    assert stride_of(auto.task.prescan, "corotation") == 5
    assert "stride" not in auto.task.prescan.canonical()
    dense = campaign_from_text(CAMPAIGN.format(extra=", stride: 1"), "<t>")
    assert stride_of(dense.task.prescan, "corotation") == 1
    assert dense.task.prescan.canonical()["stride"] == 1
    for bad in ("0", "26", "2.5", "'x'"):
        with pytest.raises(ConfigError, match=r"find_jump\.prescan\.stride: .* must be"):
            campaign_from_text(CAMPAIGN.format(extra=f", stride: {bad}"), "<t>")
