"""Multisection (find_jump.split = k): k - 1 interior runs per round, a schedule fixed by
k alone, so results do not depend on the order runs come back in."""

import math
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from frictiondisk.tasks.jump_search.bisection import Bisection
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.jumps import JumpSearch


def drive(search, oracle, order=None):
    """Answer every round in full, in the order `order` shuffles it; returns (result,
    rounds, runs)."""
    rounds = runs = 0
    while not search.done:
        pending = list(search.pending())
        if order is not None:
            order.shuffle(pending)
        rounds += 1
        for request in pending:
            search.feed(request, {"outcome": oracle(request.mu), "reason": "oracle"})
            runs += 1
    return search.result(), rounds, runs


def step_at(mu_star):
    return lambda mu: "stick" if mu >= mu_star else "stick_slip"


@settings(max_examples=150, deadline=None)
@given(
    mu_star=st.floats(0.06, 0.29),
    tol=st.floats(1e-8, 1e-3),
    split=st.integers(2, 9),
)
def test_any_split_brackets_the_step_to_tol(mu_star, tol, split):
    res, _, _ = drive(
        Bisection((0.05, 0.3), BisectionSettings(tol, (1e-6, 10.0), 0, split=split)),
        step_at(mu_star),
    )
    assert res.status == "converged"
    assert res.mu_lo < mu_star <= res.mu_hi
    assert res.width <= tol * (1 + 1e-9)


@pytest.mark.parametrize("split", [2, 3, 4, 8])
def test_rounds_and_runs_follow_the_schedule(split):
    width, tol = 0.25, 1e-8
    res, rounds, runs = drive(
        Bisection((0.05, 0.3), BisectionSettings(tol, (1e-6, 10.0), 0, split=split)),
        step_at(0.1234567),
    )
    # 1 round of end checks, then ceil(log_k(width / tol)) rounds of at most k - 1 runs
    cuts = math.ceil(math.log(width / tol) / math.log(split) - 1e-12)
    assert rounds == 1 + cuts
    assert runs <= 2 + (split - 1) * cuts
    assert len(res.runs) == runs  # every run kept, none repeated


def test_plain_bisection_is_split_two():
    a, _, _ = drive(Bisection((0.05, 0.3), BisectionSettings(1e-6, (1e-6, 10.0), 0)), step_at(0.2))
    b, _, _ = drive(
        Bisection((0.05, 0.3), BisectionSettings(1e-6, (1e-6, 10.0), 0, split=2)), step_at(0.2)
    )
    assert a == b


@pytest.mark.parametrize("split", [3, 5])
def test_order_of_arrival_does_not_change_the_result(split):
    """Even with outcomes that contradict a single jump inside a round (non-monotone)."""

    def ragged(mu):
        return "stick" if (mu >= 0.2 or 0.11 < mu < 0.1112) else "stick_slip"

    results = [
        drive(
            Bisection((0.05, 0.3), BisectionSettings(1e-7, (1e-6, 10.0), 0, split=split)),
            ragged,
            order,
        )[0]
        for order in (None, random.Random(1), random.Random(2))
    ]
    assert results[0] == results[1] == results[2]
    assert results[0].status == "converged"


def test_jump_search_bisects_every_jump_with_the_split_and_any_order():
    def window(mu):
        return "stick" if 0.12345 <= mu <= 0.16789 else "stick_slip"

    mus = tuple(0.05 + 0.01 * i for i in range(26))
    plain, plain_rounds, plain_runs = drive(JumpSearch(mus, 1e-8, 0), window)
    res, rounds, runs = drive(JumpSearch(mus, 1e-8, 0, split=4), window, random.Random(3))
    again, _, _ = drive(JumpSearch(mus, 1e-8, 0, split=4), window, random.Random(4))
    assert res == again
    assert [j.rising for j in res.jumps] == [True, False]
    for a, b in zip(plain.jumps, res.jumps, strict=True):
        assert max(a.mu_lo, b.mu_lo) < min(a.mu_hi, b.mu_hi)  # the same jump, both to tol
    # the two jumps' rounds run together, and a 4-way split needs half the rounds (the
    # prescan, the bisections, then one round for the headline's persistence run)
    assert rounds < plain_rounds <= 2 + math.ceil(math.log2(0.01 / 1e-8))
    assert runs > plain_runs


def test_split_below_two_is_refused():
    with pytest.raises(ValueError, match="split"):
        Bisection((0.05, 0.3), BisectionSettings(1e-4, (1e-6, 10.0), 0, split=1))


@pytest.mark.parametrize("value", [1, 0, 2.5, 65, "three"])
def test_a_bad_split_is_refused_naming_the_field_and_range(value):
    from frictiondisk.model.scene import ConfigError
    from frictiondisk.tasks.campaign import campaign_from_text

    text = f"""name: c
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  split: {value}
  along: {{params.x_ms: [0.1]}}
"""
    with pytest.raises(ConfigError) as info:
        campaign_from_text(text, "<test>")
    assert "find_jump.split" in str(info.value) and "2" in str(info.value)


def test_split_two_keeps_the_campaign_hash_and_other_splits_change_it():
    from frictiondisk.tasks.campaign import campaign_from_text

    base = "name: c\nscene: pin\nfind_jump:\n  bracket: [0.05, 0.3]\n{}  along: {{params.x_ms: [0.1]}}\n"
    plain = campaign_from_text(base.format(""), "<t>")
    two = campaign_from_text(base.format("  split: 2\n"), "<t>")
    three = campaign_from_text(base.format("  split: 3\n"), "<t>")
    assert plain.task.canonical() == two.task.canonical()
    assert three.task.canonical()["split"] == 3 and plain.diff(three)
