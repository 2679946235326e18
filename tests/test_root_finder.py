"""The interpolating root finder (bisection.Bisection, root_finder "itp") against synthetic
oracles that report a verdict and a friction reserve: never worse than bisection by more
than ITP_SLACK runs, far better when the reserve is good, and always a bracket holding
the jump. Plus warm-start order and spec validation."""

import math
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from frictiondisk.model.scene import ConfigError
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.find_jump.planner import refinement
from frictiondisk.tasks.jump_search.bisection import ITP_SLACK, Bisection
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings

BRACKET, LIMITS = (0.05, 0.3), (1e-6, 10.0)


def oracle(mu_star, reserve):
    """Stick at and above mu_star; the run's reserve is reserve(mu) (None: never stuck)."""

    def run(request):
        outcome = "stick" if request.mu >= mu_star else "stick_slip"
        return {"outcome": outcome, "reserve": reserve(request.mu), "reason": "oracle"}

    return run


def search(answer, tol, root_finder="itp", bracket=BRACKET):
    bis = Bisection(bracket, BisectionSettings(tol, LIMITS, 2, root_finder=root_finder))
    while not bis.done:
        for request in bis.pending():
            if bis.done:
                break
            bis.feed(request, answer(request))
    return bis.result()


def both(answer, mu_star, tol):
    """The itp and the bisect search of one oracle; both must bracket mu* to tol."""
    res, plain = search(answer, tol), search(answer, tol, "bisect")
    assert holds(res, mu_star, tol) and holds(plain, mu_star, tol)
    return res, plain


def holds(result, mu_star, tol):
    return (
        result.status == "converged"
        and result.mu_lo < mu_star <= result.mu_hi
        and result.width <= tol * (1 + 1e-9)
    )


def test_an_exact_reserve_closes_the_bracket_in_a_few_runs():
    mu_star, tol = 0.1267234, 1e-8
    res, plain = both(oracle(mu_star, lambda mu: mu - mu_star), mu_star, tol)
    assert len(plain.runs) == 2 + math.ceil(math.log2(0.25 / tol))
    assert len(res.runs) <= 5  # 2 end checks, an estimate, and its closure


def test_a_curved_reserve_still_beats_bisection():
    mu_star, tol = 0.1267234, 1e-6
    # monotone on the bracket (slope 1 + 4 (mu - mu*) > 0), curved: slope 0.7 ... 1.7
    reserve = lambda mu: (mu - mu_star) * (1.0 + 2.0 * (mu - mu_star))  # noqa: E731
    res, plain = both(oracle(mu_star, reserve), mu_star, tol)
    assert len(res.runs) <= len(plain.runs) / 2


@pytest.mark.parametrize("bias_in_tol", [-50, -5, 5, 50])
def test_a_biased_reserve_is_overtaken_by_geometric_steps(bias_in_tol):
    # contact compliance shifts the reserve's zero off the jump by tens of tol at tol 1e-8
    mu_star, tol = 0.1267234, 1e-8
    bias = bias_in_tol * tol
    res, plain = both(oracle(mu_star, lambda mu: mu - mu_star + bias), mu_star, tol)
    assert len(res.runs) < len(plain.runs) - 8


@pytest.mark.parametrize("seed", range(6))
def test_a_reserve_that_lies_costs_at_most_the_slack(seed):
    rng = random.Random(seed)
    mu_star, tol = rng.uniform(0.06, 0.29), 10.0 ** rng.uniform(-9, -4)
    res, plain = both(oracle(mu_star, lambda mu: rng.uniform(-0.2, 0.2)), mu_star, tol)
    assert len(res.runs) <= len(plain.runs) + ITP_SLACK


def test_without_a_reserve_it_is_bisection():
    mu_star, tol = 0.1267234, 1e-6
    res, plain = both(oracle(mu_star, lambda mu: None), mu_star, tol)
    assert [r.request.mu for r in res.runs] == [r.request.mu for r in plain.runs]


@settings(max_examples=60, deadline=None)
@given(
    mu_star=st.floats(0.051, 0.299),
    log_tol=st.floats(-9, -3),
    slope=st.floats(0.2, 5.0),
    bias=st.floats(-1e-3, 1e-3),
)
def test_any_linear_reserve_is_never_worse_than_bisection_plus_slack(mu_star, log_tol, slope, bias):
    tol = 10.0**log_tol
    res, plain = both(oracle(mu_star, lambda mu: slope * (mu - mu_star) + bias), mu_star, tol)
    assert len(res.runs) <= len(plain.runs) + ITP_SLACK


def test_a_widening_the_reserve_predicts_goes_just_past_its_root():
    # both ends slip; the reserve puts the jump at 0.4, beyond hi = 0.3
    mu_star, tol = 0.4, 1e-4
    res, plain = both(oracle(mu_star, lambda mu: mu - mu_star), mu_star, tol)
    assert len(res.runs) <= 5
    assert len(plain.runs) > 10


def test_warm_start_order_is_coarse_to_fine():
    order, tree = refinement(9)
    assert order == [0, 8, 4, 2, 6, 1, 3, 5, 7]
    assert tree[0] is None and tree[8] is None
    assert tree[4] == (0, 8, None)
    assert tree[2] == (0, 4, 8) and tree[6] == (4, 8, 0)
    assert sorted(order) == list(range(9))


LINE = """
name: t
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  root_finder: {value}
  along: {{params.x_ms: [0.1]}}
"""


def test_spec_root_finder():
    assert campaign_from_text(LINE.format(value="bisect"), "<t>").task.root_finder == "bisect"
    itp = campaign_from_text(LINE.format(value="itp"), "<t>").task
    assert itp.root_finder == "itp" and "root_finder" not in itp.canonical()
    with pytest.raises(ConfigError, match=r"find_jump\.root_finder: .*must be 'itp' or 'bisect'"):
        campaign_from_text(LINE.format(value="brent"), "<t>")
