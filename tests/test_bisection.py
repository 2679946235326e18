"""The bisection state machine against synthetic outcome oracles (no simulation)."""

import ast
import math
import pathlib

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import frictiondisk.tasks.jump_search as package
from frictiondisk.tasks.jump_search.bisection import Bisection, RunRequest
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings


def drive(bis, oracle):
    """Run a bisection to the end with outcomes from oracle(request) -> outcome."""
    while not bis.done:
        for req in bis.pending():
            if bis.done:
                break
            outcome = oracle(req)
            bis.feed(req, {"outcome": outcome, "reason": f"oracle at {req.mu}"})
    return bis.result()


def step_at(mu_star):
    return lambda req: "stick" if req.mu >= mu_star else "stick_slip"


def test_converges_to_a_bracket_holding_the_jump():
    res = drive(Bisection((0.05, 0.3), BisectionSettings(1e-4, (1e-6, 10.0), 2)), step_at(0.12653))
    assert res.status == "converged"
    assert res.mu_lo < 0.12653 <= res.mu_hi
    assert res.width <= 1e-4
    assert res.mu_star == pytest.approx(0.5 * (res.mu_lo + res.mu_hi))
    assert res.monotone
    assert res.end_result("hi")["outcome"] == "stick"
    assert res.end_result("lo")["outcome"] == "stick_slip"
    # 2 end checks + ceil(log2(0.25 / 1e-4)) = 12 halvings
    assert len(res.runs) == 2 + math.ceil(math.log2(0.25 / 1e-4))


@pytest.mark.parametrize("mu_star", [0.9, 0.004])
def test_widens_the_bracket_when_both_ends_agree(mu_star):
    res = drive(Bisection((0.05, 0.3), BisectionSettings(1e-4, (1e-6, 10.0), 2)), step_at(mu_star))
    assert res.status == "converged"
    assert res.mu_lo < mu_star <= res.mu_hi


def test_fails_naming_both_ends_when_the_limits_stop_the_widening():
    res = drive(Bisection((0.05, 0.3), BisectionSettings(1e-4, (0.01, 0.5), 2)), step_at(0.8))
    assert res.status == "failed"
    assert "no stick up to the limit" in res.reason
    assert "0.5" in res.reason and "stick_slip" in res.reason
    assert math.isnan(res.mu_star)


def test_inverted_bracket_fails_with_both_outcomes():
    res = drive(
        Bisection((0.05, 0.3), BisectionSettings(1e-4, (1e-6, 10.0), 2)),
        lambda r: "stick" if r.mu < 0.1 else "slide",
    )
    assert res.status == "failed"
    assert "inverted" in res.reason and "slide" in res.reason


def test_undetermined_is_retried_with_longer_horizons_then_used():
    calls = []

    def oracle(req):
        calls.append(req)
        if abs(req.mu - 0.175) < 1e-12 and req.level < 2:
            return "undetermined"
        return step_at(0.2)(req)

    res = drive(Bisection((0.05, 0.3), BisectionSettings(1e-3, (1e-6, 10.0), 2)), oracle)
    assert res.status == "converged"
    assert [r.level for r in calls if abs(r.mu - 0.175) < 1e-12] == [0, 1, 2]
    assert res.mu_lo < 0.2 <= res.mu_hi


def test_undetermined_after_all_retries_fails_with_the_run_reason():
    res = drive(
        Bisection((0.05, 0.3), BisectionSettings(1e-3, (1e-6, 10.0), 1)),
        lambda r: "undetermined" if r.mu > 0.2 else "stick_slip",
    )
    assert res.status == "failed"
    assert "after 1 retries" in res.reason and "oracle at" in res.reason


def test_non_monotone_runs_are_reported_not_hidden():
    """Inside a valid bracket every midpoint is consistent by construction, so a
    contradiction can only come from the end checks: a sticking island below a not-stick
    region. It is reported as pairs (mu of a stick, larger mu of a not stick)."""

    def oracle(req):
        return "stick" if 0.05 <= req.mu < 0.055 or req.mu >= 0.1 else "stick_slip"

    res = drive(Bisection((0.05, 0.06), BisectionSettings(1e-4, (1e-6, 10.0), 0)), oracle)
    assert res.status == "failed"
    assert not res.monotone
    assert res.contradictions == ((0.05, 0.06),)


def test_feed_rejects_runs_it_did_not_ask_for():
    bis = Bisection((0.05, 0.3), BisectionSettings(1e-4, (1e-6, 10.0), 2))
    with pytest.raises(ValueError):
        bis.feed(RunRequest(0.17), {"outcome": "stick"})


@settings(max_examples=200, deadline=None)
@given(
    mu_star=st.floats(0.001, 5.0),
    lo=st.floats(0.001, 5.0),
    width=st.floats(1e-3, 3.0),
    tol=st.floats(1e-6, 1e-3),
)
def test_any_step_oracle_is_bracketed(mu_star, lo, width, tol):
    hi = lo + width
    res = drive(Bisection((lo, hi), BisectionSettings(tol, (1e-4, 20.0), 0)), step_at(mu_star))
    if 1e-4 < mu_star <= 20.0:
        assert res.status == "converged"
        assert res.mu_lo < mu_star <= res.mu_hi
        assert res.width <= tol * (1 + 1e-9)


def slow_near(lo, hi, mu_star):
    """Undetermined (a slow approach) on [lo, hi], a jump at mu_star inside it."""

    def oracle(req):
        if lo <= req.mu <= hi:
            return "undetermined"
        return "stick" if req.mu >= mu_star else "stick_slip"

    return oracle


def test_an_interval_of_undecided_mu_is_bracketed_from_both_sides():
    tol = 1e-4
    res = drive(
        Bisection((0.1, 0.2), BisectionSettings(tol, (1e-6, 10.0), 1)),
        slow_near(0.1500, 0.1503, 0.1501),
    )
    assert res.status == "converged", res.reason
    assert res.mu_lo < 0.1500 and res.mu_hi > 0.1503  # the undecided span, both sides decided
    assert res.width <= 0.0003 + tol * (1 + 1e-9)
    assert "undetermined after every retry" in res.reason


def test_undecided_mu_spanning_more_than_ten_tol_fail_with_the_reason():
    res = drive(
        Bisection((0.1, 0.2), BisectionSettings(1e-4, (1e-6, 10.0), 1)),
        slow_near(0.140, 0.160, 0.15),
    )
    assert res.status == "failed" and "undetermined at mu" in res.reason


def test_a_bracket_end_in_the_slow_approach_moves_out_and_is_straddled():
    """A predicted bracket (a trace's correction, a warm start) whose low end lies in the
    undecided band around the jump: the end moves half the straddle span outwards, and the
    bisection brackets the band from both sides instead of failing."""
    tol = 1e-4
    band = (0.18760, 0.18790)
    res = drive(
        Bisection((0.18770, 0.18800), BisectionSettings(tol, (0.1, 0.3), 1)),
        slow_near(*band, 0.18775),
    )
    assert res.status == "converged", res.reason
    assert res.mu_lo < band[0] and res.mu_hi > band[1]
    assert res.end_result("lo")["outcome"] == "stick_slip"
    assert res.end_result("hi")["outcome"] == "stick"
    assert res.width <= (band[1] - band[0]) + tol * (1 + 1e-9) + 1e-12
    assert "undetermined after every retry" in res.reason


def test_a_bracket_end_cannot_move_past_its_limit():
    res = drive(
        Bisection((0.1876, 0.1880), BisectionSettings(1e-4, (0.1876, 0.3), 1)),
        slow_near(0.1870, 0.1877, 0.1875),
    )
    assert res.status == "failed" and "undetermined at mu = 0.1876" in res.reason


def test_both_ends_undecided_beyond_the_span_fail():
    res = drive(
        Bisection((0.140, 0.160), BisectionSettings(1e-4, (0.1, 0.3), 1)),
        slow_near(0.139, 0.161, 0.15),
    )
    assert res.status == "failed" and "undetermined at mu" in res.reason


def test_the_jump_searches_stay_in_small_parts():
    """tasks/jump_search: no module over 400 lines, no class over 20 methods (the bisection
    is its settings, its bracket state and its probe strategies, not one class)."""
    too_big = []
    for path in sorted(pathlib.Path(package.__file__).parent.glob("*.py")):
        source = path.read_text()
        if len(source.splitlines()) > 400:
            too_big.append(f"{path.name}: {len(source.splitlines())} lines")
        for node in ast.parse(source).body:
            if isinstance(node, ast.ClassDef):
                methods = [b for b in node.body if isinstance(b, ast.FunctionDef)]
                if len(methods) > 20:
                    too_big.append(f"{path.name}: {node.name} has {len(methods)} methods")
    assert not too_big
