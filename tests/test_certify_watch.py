"""Certification that tests its verdict (issue 50): every run records the rule that decided
it (verdict/deciding_rule.py), and a stricter run at a bracket end whose run before it was
decided by an extrapolation watches (numerics.observe_until) for certify.watch times that
run's decision time before it may extrapolate (tasks/jump_search/certify.py)."""

from __future__ import annotations

import pytest
from test_certify import TOL, drive_results

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.model.search_settings import Certify
from frictiondisk.simulation.simulate import simulate
from frictiondisk.tasks.jump_search.bisection import RunRequest
from frictiondisk.tasks.jump_search.certify import CertifiedBisection
from frictiondisk.tasks.jump_search.requests import run_config
from frictiondisk.verdict.deciding_rule import DECIDING_RULES, EXTRAPOLATED

# the default pin at x_ms = 0.05 just above its jump: a stick-slip cycle that its section
# shows contracting towards at 218 s (a geometric approach, read ahead: `contract`)
CONTRACTING = {"scene": "pin", "params": {"mu": 0.0501, "x_ms": 0.05}}


def test_each_run_says_which_rule_decided_it():
    seen = simulate(scene_from_dict({"scene": "pin", "params": {"mu": 0.2}}))
    assert (seen.outcome, seen.decided_by) == ("stick", "corotation")
    read_ahead = simulate(scene_from_dict(CONTRACTING))
    assert (read_ahead.outcome, read_ahead.decided_by) == ("stick_slip", "contract")
    assert read_ahead.summary()["decided_by"] == "contract"
    assert EXTRAPOLATED < set(DECIDING_RULES) and "corotation" not in EXTRAPOLATED


def test_a_watching_run_reaches_no_not_stick_verdict_before_its_watch_ends():
    t0 = simulate(scene_from_dict(CONTRACTING)).t_end
    watch = 2.0 * t0
    watched = simulate(scene_from_dict({**CONTRACTING, "numerics": {"observe_until": watch}}))
    assert watched.outcome == "stick_slip"
    assert watched.t_end >= watch - 1e-9 * watch
    assert watched.t_end <= watch + 2 * 2 * 3.141592653589793  # the next horizon after it


def test_the_exact_coulomb_pin_refuses_a_watch():
    with pytest.raises(ValueError, match="has no watch"):
        scene_from_dict({"scene": "pin", "numerics": {"method": "coulomb", "observe_until": 60.0}})


def _answer(jump: float, rule_lo: str, t_lo: float):
    """Run results of a jump at `jump`: not stick below by `rule_lo` at t_lo [s], stick
    above by the co-rotation rule seen at 40 s."""

    def answer(mu, strict):
        if mu >= jump:
            return {"outcome": "stick", "decided_by": "corotation", "t_end": 40.0}
        return {"outcome": "slide", "decided_by": rule_lo, "t_end": t_lo}

    return answer


@pytest.mark.parametrize(("rule", "watched"), [("sliding", True), ("cannot", False)])
def test_an_extrapolated_end_is_checked_by_a_watching_run(rule, watched):
    search = CertifiedBisection((0.05, 0.3), TOL, (1e-6, 10.0), 2, certify=Certify())
    result = drive_results(search, _answer(0.13, rule, 91.5))
    assert result.certification == "certified"
    checks = {run.request.mu: run.request for run in result.runs if run.request.strict == 1}
    assert checks[result.mu_lo].watch == (2.0 * 91.5 if watched else 0.0)
    assert checks[result.mu_hi].watch == 0.0  # a stick seen is no extrapolation


def test_no_watch_when_certification_observes_or_the_factor_is_zero():
    for certify in (Certify(observe=True), Certify(watch=0.0)):
        search = CertifiedBisection((0.05, 0.3), TOL, (1e-6, 10.0), 2, certify=certify)
        result = drive_results(search, _answer(0.13, "sliding", 91.5))
        assert all(run.request.watch == 0.0 for run in result.runs)


def test_the_watch_stays_within_the_certification_budget():
    point = scene_from_dict({"scene": "pin", "numerics": {"t_decide": 30.0}})
    certify = Certify()
    budget = 30.0 * 8.0 * certify.horizon  # t_decide x horizon_budget x certify.horizon
    short = run_config(point, RunRequest(0.1, strict=1, watch=183.0), 2.0, certify)
    assert short.numerics.observe_until == 183.0
    long = run_config(point, RunRequest(0.1, strict=1, watch=5000.0), 2.0, certify)
    assert long.numerics.observe_until == budget
    assert "observe_until" not in point.canonical()["numerics"]


def test_an_end_that_flips_when_watched_leaves_the_point_uncertain_with_its_bracket():
    """The extrapolation that decided mu_lo does not hold when watched (issue 50's d1: it
    sticks): no re-search by the same rule beside it, the bracket is kept, flagged."""

    def answer(mu, strict):
        if mu >= 0.13 or (strict and mu >= 0.13 - TOL):
            return {"outcome": "stick", "decided_by": "corotation", "t_end": 170.8}
        return {"outcome": "slide", "decided_by": "sliding", "t_end": 91.5}

    search = CertifiedBisection((0.05, 0.3), TOL, (1e-6, 10.0), 2, certify=Certify())
    result = drive_results(search, answer)
    assert result.certification == "uncertain"
    assert result.mu_lo < 0.13 <= result.mu_hi and result.width <= TOL * (1 + 1e-9)
    assert f"the end mu = {result.mu_lo:.10g} flipped" in result.reason
    assert all(run.request.strict <= 1 for run in result.runs)  # no re-search


def test_the_watch_factor_survives_the_campaign_record():
    for certify in (Certify(), Certify(watch=0.0), Certify(watch=3.0)):
        assert Certify.model_validate(certify.canonical()) == certify
