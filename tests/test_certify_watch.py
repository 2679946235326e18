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
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.certify import CertifiedBisection
from frictiondisk.tasks.jump_search.requests import run_config
from frictiondisk.tasks.jump_search.sides import Between
from frictiondisk.tasks.jump_search.watch import MOTION_WATCH
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
    search = CertifiedBisection(
        (0.05, 0.3), BisectionSettings(TOL, (1e-6, 10.0), 2), certify=Certify()
    )
    result = drive_results(search, _answer(0.13, rule, 91.5))
    assert result.certification == "certified"
    checks = {run.request.mu: run.request for run in result.runs if run.request.strict == 1}
    assert checks[result.mu_lo].watch == (2.0 * 91.5 if watched else 0.0)
    assert checks[result.mu_hi].watch == 0.0  # a stick seen is no extrapolation


def test_no_watch_when_certification_observes_or_the_factor_is_zero():
    for certify in (Certify(observe=True), Certify(watch=0.0)):
        search = CertifiedBisection(
            (0.05, 0.3), BisectionSettings(TOL, (1e-6, 10.0), 2), certify=certify
        )
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


def drive_requests(search, answer):
    """Feed `search` until done; answer(request) gives each run's result."""
    while not search.done:
        for request in list(search.pending()):
            if not search.done and request in search.pending():
                search.feed(request, answer(request))
    return search.result()


def test_an_end_that_flips_when_watched_is_searched_again_from_with_every_run_watched():
    """The extrapolation that decided mu_lo does not hold when watched (issue 50's d1: it
    sticks): the search goes on from the corrected end at the stricter level, every run of
    it watched as long as the check that flipped (an unwatched re-search would bracket the
    difference between watching and not), and its bracket is certified one level up."""
    t_lo = 91.5

    def answer(request):
        watched = request.strict and request.watch >= 2.0 * t_lo
        if request.mu >= 0.13 or (watched and request.mu >= 0.13 - 3 * TOL):
            return {"outcome": "stick", "decided_by": "corotation", "t_end": 170.8}
        return {"outcome": "slide", "decided_by": "sliding", "t_end": t_lo}

    search = CertifiedBisection(
        (0.05, 0.3), BisectionSettings(TOL, (1e-6, 10.0), 2), certify=Certify()
    )
    result = drive_requests(search, answer)
    assert result.certification == "recertified", result.reason
    assert result.mu_lo < 0.13 - 3 * TOL <= result.mu_hi and result.width <= TOL * (1 + 1e-9)
    assert "flipped" in result.reason and "searched again" in result.reason
    # level 1: the check of the stick end (seen: no watch), the one that flipped, and the
    # re-search below it, all watched
    below = [
        run.request for run in result.runs if run.request.strict == 1 and run.request.mu < 0.13
    ]
    assert len(below) >= 3 and all(r.watch >= 2.0 * t_lo for r in below)
    assert {r.request.mu for r in result.runs if r.request.strict == 2} == {
        result.mu_lo,
        result.mu_hi,
    }


def test_the_watch_factor_survives_the_campaign_record():
    for certify in (Certify(), Certify(watch=0.0), Certify(watch=3.0)):
        assert Certify.model_validate(certify.canonical()) == certify


def test_a_motion_boundary_end_is_checked_on_at_least_twice_its_horizon():
    """A `between` boundary of two motions (issue 65, case 2): a spiral decaying slowly,
    named slide_cycle at t_max 3000 s, self-centres by 9000 s. A check at a stricter rtol
    on the same horizon repeats the error; the check of each end watches to at least
    MOTION_WATCH x the decision time of the run that decided it, whatever rule decided it."""
    t_max = 3000.0
    hopf = 1.46

    def answer(request):
        # the run decides on what it saw by its horizon: a spiral decaying for good below
        # the Hopf point still looks like a cycle at t_max, not at twice that
        seen_to = max(t_max, request.watch)
        cycle = request.mu >= hopf or (request.mu >= 1.42 and seen_to < MOTION_WATCH * t_max)
        outcome = "slide_cycle" if cycle else "self_centring"
        return {"outcome": outcome, "decided_by": "cycle", "t_end": seen_to}

    between = Between("self_centring", "slide_cycle")
    search = CertifiedBisection(
        (1.40, 1.55), BisectionSettings(2e-3, (1.0, 2.5), 1, between=between), certify=Certify()
    )
    result = drive_requests(search, answer)
    checks = [run.request for run in result.runs if run.request.strict]
    assert checks and all(r.watch >= MOTION_WATCH * t_max for r in checks)
    # the watched check of the upper end self-centres: the search goes on from it, every
    # run watched as long, and its bracket is checked watched longer still
    assert result.certification == "recertified", result.reason
    assert result.mu_lo < hopf <= result.mu_hi and result.width <= 2e-3 * (1 + 1e-9)


def test_the_stick_jump_keeps_an_unwatched_check_of_a_seen_verdict():
    search = CertifiedBisection(
        (0.05, 0.3), BisectionSettings(TOL, (1e-6, 10.0), 2), certify=Certify()
    )
    result = drive_results(search, _answer(0.13, "cycle", 91.5))
    assert all(run.request.watch == 0.0 for run in result.runs)


def test_with_observe_a_watch_is_a_longer_horizon():
    point = scene_from_dict({"scene": "pin", "numerics": {"mode": "converge", "t_max": 300.0}})
    observe = Certify(observe=True)
    watched = run_config(point, RunRequest(0.1, strict=1, watch=600.0), 2.0, observe)
    assert watched.numerics.t_max == 600.0 and watched.numerics.evidence == "observe"
    plain = run_config(point, RunRequest(0.1, strict=1), 2.0, observe)
    assert plain.numerics.t_max == 300.0
