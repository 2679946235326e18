"""Certification of located jumps (tasks/jump_search/certify.py): the ladder on synthetic oracles
whose jump moves with the numerics level, as a short horizon moves it in the kernel."""

from __future__ import annotations

import pytest

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.model.search_settings import OFF, Certify
from frictiondisk.tasks.jump_search.bisection import RunRequest
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.certify import CertifiedBisection, point_certification
from frictiondisk.tasks.jump_search.jumps import JumpSearch
from frictiondisk.tasks.jump_search.requests import run_config

TOL = 1e-4


def drive(search, outcome_of):
    """Feed `search` until done; outcome_of(mu, strict) gives each run's outcome."""
    return drive_results(search, lambda mu, strict: {"outcome": outcome_of(mu, strict)})


def threshold(*mu_star_per_level):
    """stick iff mu >= the jump of the run's level (the last one for stricter levels)."""

    def outcome(mu, strict):
        level = min(strict, len(mu_star_per_level) - 1)
        return "stick" if mu >= mu_star_per_level[level] else "stick_slip"

    return outcome


DEFAULT = Certify()


def bisection(certify=DEFAULT):
    return CertifiedBisection((0.05, 0.3), BisectionSettings(TOL, (1e-6, 10.0), 2), certify=certify)


def test_a_jump_that_holds_at_stricter_numerics_is_certified():
    result = drive(bisection(), threshold(0.13))
    assert result.certification == "certified"
    assert result.mu_lo < 0.13 <= result.mu_hi and result.width <= TOL * (1 + 1e-9)
    strict = [run for run in result.runs if run.request.strict == 1]
    assert sorted(run.request.mu for run in strict) == [result.mu_lo, result.mu_hi]
    assert result.strict == 0


def test_a_jump_that_moves_is_searched_again_at_the_stricter_level():
    for true_jump in (0.1337, 0.1262):  # the hi end flips, or the lo end flips
        result = drive(bisection(), threshold(0.13, true_jump))
        assert result.certification == "recertified", result.reason
        assert result.strict == 1
        assert result.mu_lo < true_jump <= result.mu_hi and result.width <= TOL * (1 + 1e-9)
        # and it was confirmed one level further
        assert any(run.request.strict == 2 for run in result.runs)


def test_a_jump_that_keeps_moving_is_uncertain_with_its_best_bracket():
    result = drive(bisection(), threshold(0.13, 0.1337, 0.1345))
    assert result.certification == "uncertain"
    assert result.status == "converged"
    assert result.mu_lo < 0.1337 <= result.mu_hi  # the bracket of the strictest search


def test_an_undetermined_strict_run_makes_the_jump_uncertain():
    def outcome(mu, strict):
        return "undetermined" if strict else threshold(0.13)(mu, 0)

    result = drive(bisection(), outcome)
    assert result.certification == "uncertain"
    # it ended at a horizon no budget extends (mode converge's t_max): retried first, each
    # retry's budget covering the levels left above it
    assert any(run.request.level == 2 for run in result.runs)
    assert all(r.request.level + r.request.reach == 2 for r in result.runs if r.request.strict)


def test_a_check_whose_budget_ran_out_is_not_restarted():
    """A check's budget already reaches as far as its last retry would: one that spent it
    is final (a retry would compute the same motion again from t = 0)."""

    def answer(mu, strict):
        if strict:
            return {"outcome": "undetermined", "decided_by": "budget"}
        return {"outcome": threshold(0.13)(mu, 0)}

    result = drive_results(bisection(), answer)
    assert result.certification == "uncertain"
    strict = [run.request for run in result.runs if run.request.strict]
    assert sorted(r.mu for r in strict) == [result.mu_lo, result.mu_hi]
    assert all((r.level, r.reach) == (0, 2) for r in strict)


def _drive_requests(search, answer):
    """Feed `search` until done; answer(request) gives each run's result. As the engine
    does (tasks/in_order.py), a run the search no longer waits for is dropped."""
    while not search.done:
        for request in list(search.pending()):
            if not search.done and request in search.pending():
                search.feed(request, answer(request))
    return search.result()


def test_a_check_whose_integrator_fails_is_checked_again_with_the_points_own():
    """certify.method's run of an end fails (a step-size underflow): a longer horizon
    would compute the same failure, so the end is checked again at the same level with the
    point's own integrator (request.own_method), whose verdict counts."""

    def answer(request):
        if request.strict and request.mu > 0.13 and not request.own_method:
            return {"outcome": "undetermined", "decided_by": "error"}
        return {"outcome": threshold(0.13)(request.mu, request.strict)}

    result = _drive_requests(bisection(), answer)
    assert result.certification == "certified", result.reason
    strict = [run.request for run in result.runs if run.request.strict]
    hi = [r for r in strict if r.mu == result.mu_hi]
    assert [(r.own_method, r.level) for r in hi] == [(False, 0), (True, 0)]
    assert [r.own_method for r in strict if r.mu == result.mu_lo] == [False]
    # with the point's own integrator as certify.method there is nothing to switch to:
    # the ladder retries with longer horizons, and the end stays undetermined
    same = _drive_requests(bisection(Certify(method="rodas4")), answer)
    assert same.certification == "uncertain"
    assert not any(run.request.own_method for run in same.runs)


def test_a_check_reaches_as_far_as_its_last_retry_without_restarting():
    """A check's budget is the strict budget times horizon_factor per retry level it covers
    (the reach of the retry it replaces, from the first horizon on); its departure is
    followed only to the end of the strict budget, as before the check covered its retries."""
    point = scene_from_dict({"scene": "pin", "params": {"mu": 0.2, "x_ms": 0.1, "x0": 0.0}})
    budget = point.numerics.horizon_budget * DEFAULT.horizon
    one = run_config(point, RunRequest(0.2, strict=1, watch=50.0, reach=2), 2.0, DEFAULT)
    assert one.numerics.t_decide == point.numerics.t_decide
    assert one.numerics.horizon_budget == pytest.approx(budget * 2.0**2)
    last = run_config(point, RunRequest(0.2, level=2, strict=1, watch=50.0), 2.0, DEFAULT)
    reach = one.numerics.t_decide * one.numerics.horizon_budget
    assert reach == pytest.approx(last.numerics.t_decide * last.numerics.horizon_budget)
    assert one.numerics.follow_departures_until == pytest.approx(point.numerics.t_decide * budget)


def test_certification_off_makes_no_strict_run():
    result = drive(bisection(OFF), threshold(0.13))
    assert result.certification == "off"
    assert all(run.request.strict == 0 for run in result.runs)


def test_jumps_that_exist_only_at_the_short_horizon_vanish_from_a_prescan():
    # default numerics: stick on [0.13, 0.16) and [0.19, 1); strict: stick from 0.13 only
    def outcome(mu, strict):
        stick = mu >= 0.13 if strict else (0.13 <= mu < 0.16 or mu >= 0.19)
        return "stick" if stick else "slide"

    search = JumpSearch(tuple(0.01 * k for k in range(5, 30)), TOL, 2, "decide", 2, Certify())
    result = drive(search, outcome)
    assert result.status == "converged", result.reason
    assert len(result.jumps) == 1 and result.jumps[0].rising
    assert result.mu_lo < 0.13 <= result.mu_hi
    assert "2 more vanished" in result.reason
    assert result.certification == "certified"


@pytest.mark.parametrize(
    "flags, expected",
    [
        (["certified", "recertified"], "recertified"),
        (["certified", "uncertain", "vanished"], "uncertain"),
        (["vanished"], "failed"),
        (["off"], "off"),
    ],
)
def test_a_point_is_as_certain_as_its_weakest_jump(flags, expected):
    assert point_certification(flags) == expected


def test_an_undecided_mu_at_the_jump_is_straddled_to_tol():
    """Critical slowing down: the run at the jump itself never decides. The bisection closes
    in on it from both sides instead of failing."""
    jump = 0.175  # the first midpoint of [0.05, 0.3]

    def outcome(mu, strict):
        if abs(mu - jump) < 1e-12:
            return "undetermined"
        return "stick" if mu > jump else "stick_slip"

    result = drive(bisection(), outcome)
    assert result.status == "converged", result.reason
    assert result.mu_lo < jump < result.mu_hi and result.width <= TOL * (1 + 1e-9)
    assert "undetermined after every retry" in result.reason
    assert result.certification == "certified"


def test_two_undecided_mu_in_a_row_fail_with_the_reason():
    def outcome(mu, strict):
        if 0.17 < mu < 0.23:
            return "undetermined"
        return "stick" if mu > 0.2 else "stick_slip"

    result = drive(bisection(), outcome)
    assert result.status == "failed"
    assert "undetermined" in result.reason


def test_a_narrow_undecided_band_in_a_wide_bracket_is_straddled_near_it():
    """The first probe of the bracket (0.05, 0.3), its midpoint 0.175, lands in an undecided
    band (0.1749, 0.1752), 3 tol wide, with the jump inside it; 0.08 ... 0.12 is undecided
    too (a transient that decides nothing about this jump, like accuracy_brake.yaml's at
    0.1825). The bracket closes in on the band from at most UNDECIDED_SPAN / 2 tol away,
    so it never asks the far transient (the midpoint of (0.05, 0.1749) would), and it
    converges around the band."""

    def outcome(mu, strict):
        if 0.1749 < mu < 0.1752 or 0.08 < mu < 0.12:
            return "undetermined"
        return "stick" if mu > 0.1751 else "stick_slip"

    result = drive(bisection(), outcome)
    assert result.status == "converged", result.reason
    assert result.mu_lo <= 0.1749 and result.mu_hi >= 0.1752
    assert result.mu_hi - result.mu_lo <= 0.0003 + 2 * TOL
    assert not any(0.08 < run.request.mu < 0.12 for run in result.runs)


# --- the guided opening of a cold search --------------------------------------------------


def reserve_oracle(mu_star, reserve, undetermined=()):
    """Stick iff mu >= mu_star (every level); the run's friction reserve is reserve(mu)."""

    def outcome(mu, strict):
        if any(abs(mu - u) < 1e-12 for u in undetermined):
            return {"outcome": "undetermined", "reserve": None}
        stick = mu >= mu_star
        return {"outcome": "stick" if stick else "stick_slip", "reserve": reserve(mu)}

    return outcome


def drive_results(search, answer):
    """Feed `search` until done; answer(mu, strict) gives each run's result."""
    return _drive_requests(search, lambda request: answer(request.mu, request.strict))


def guided(tol=TOL, bracket=(0.05, 0.3)):
    return CertifiedBisection(
        bracket, BisectionSettings(tol, (1e-6, 10.0), 2), certify=DEFAULT, guided=True
    )


@pytest.mark.parametrize("tol", [1e-4, 1e-8])
def test_a_cold_search_opens_at_the_stick_end_and_never_runs_a_far_lo(tol):
    mu_star = 0.1267234
    # a reserve that is good near the jump and off by 3 % of the distance far from it
    answer = reserve_oracle(mu_star, lambda mu: (mu - mu_star) * (1 + 0.03 * (mu - mu_star) / 0.1))
    result = drive_results(guided(tol), answer)
    assert result.certification == "certified"
    assert result.mu_lo < mu_star <= result.mu_hi and result.width <= tol * (1 + 1e-9)
    searched = [run.request.mu for run in result.runs if run.request.strict == 0]
    assert 0.3 in searched  # opened at the stick end
    assert 0.05 not in searched  # the bracket's lo end was never needed
    plain = drive_results(
        CertifiedBisection((0.05, 0.3), BisectionSettings(tol, (1e-6, 10.0), 2), certify=DEFAULT),
        answer,
    )
    assert len(result.runs) < len(plain.runs)


def test_a_guide_that_sticks_becomes_the_upper_end_and_lo_is_checked():
    # the reserve overestimates: its zero lies above the jump, so the guide sticks
    mu_star = 0.12
    answer = reserve_oracle(mu_star, lambda mu: mu - mu_star - 0.01)
    result = drive_results(guided(), answer)
    assert result.certification == "certified"
    assert result.mu_lo < mu_star <= result.mu_hi and result.width <= TOL * (1 + 1e-9)
    assert 0.05 in [run.request.mu for run in result.runs]  # lo checked after all
    assert 0.3 in [run.request.mu for run in result.runs]  # the opening run is kept


def test_an_opening_without_a_usable_reserve_is_the_plain_check():
    answer = reserve_oracle(0.13, lambda mu: None)
    result = drive_results(guided(), answer)
    plain = drive_results(
        CertifiedBisection((0.05, 0.3), BisectionSettings(TOL, (1e-6, 10.0), 2), certify=DEFAULT),
        answer,
    )
    assert [r.request for r in result.runs] == [r.request for r in plain.runs]


def test_an_undetermined_guide_falls_back_to_the_bracket():
    mu_star = 0.1267234
    guide = 0.3 - (0.3 - mu_star)  # the exact reserve's zero
    answer = reserve_oracle(mu_star, lambda mu: mu - mu_star, undetermined=(guide,))
    result = drive_results(guided(), answer)
    assert result.certification == "certified"
    assert result.mu_lo < mu_star <= result.mu_hi
    mus = [run.request.mu for run in result.runs]
    assert guide in mus and 0.05 in mus  # kept among the runs; lo checked instead


def test_the_guided_opening_replays_to_the_same_runs():
    """Fed the same results again (a resume from the journal), it asks for the same runs."""
    answer = reserve_oracle(0.1267234, lambda mu: mu - 0.1267234 + 1e-6 * (mu > 0.2))
    first = drive_results(guided(1e-8), answer)
    again = drive_results(guided(1e-8), answer)
    assert [r.request for r in first.runs] == [r.request for r in again.runs]
    assert (first.mu_lo, first.mu_hi) == (again.mu_lo, again.mu_hi)


def test_a_certification_level_tightens_rtol_atol_and_lengthens_the_budget():
    point = scene_from_dict({"scene": "disk", "params": {"beta_b": 0.005}})
    for strict in (1, 2):
        num = run_config(point, RunRequest(0.2, strict=strict), 2.0, DEFAULT).numerics
        factor = DEFAULT.rtol**strict
        assert num.rtol == pytest.approx(1e-6 * factor)
        assert num.atol == pytest.approx(1e-9 * factor)  # atol moves a braked disk's mu*
        # the friction law's resolution only where asked: a slip below eps T counts as none
        assert run_config(point, RunRequest(0.2, strict=strict), 2.0, DEFAULT).contact.eps == 1e-9
        finer = run_config(point, RunRequest(0.2, strict=strict), 2.0, Certify(eps=0.1))
        assert finer.contact.eps == pytest.approx(1e-9 * 0.1**strict)
        # judged from the same horizon on, with more room to find its evidence
        assert num.t_decide == pytest.approx(30.0)
        assert num.horizon_budget == pytest.approx(8.0 * DEFAULT.horizon**strict)
        # and its work budgets grow with that time: steps and events per second of watch
        assert num.max_steps == 2_000_000 * DEFAULT.horizon**strict
        assert num.max_events == 200_000 * DEFAULT.horizon**strict
    # a run of the point's own level keeps the point's budgets
    same = run_config(point, RunRequest(0.2), 2.0, DEFAULT).numerics
    assert (same.max_steps, same.max_events) == (2_000_000, 200_000)


def test_a_certification_setting_survives_the_campaign_file_round_trip():
    """A campaign written back to YAML (campaign.yaml, resume) keeps the certification it
    was given: the integrator and the resolution factor too, not only the defaults."""
    for given in ({"method": "rodas4"}, {"eps": 0.1}, {"eps": 0.3, "levels": 1}):
        certify = Certify(**given)
        again = Certify(**certify.canonical())
        assert again == certify, given


def test_a_certification_level_checks_with_another_integrator():
    """The stricter runs of a rodas4 point run rodas5 (certify.method); the point's own
    runs, and a point that chose another method, keep theirs."""
    point = scene_from_dict({"scene": "pin"})
    assert run_config(point, RunRequest(0.2), 2.0, DEFAULT).numerics.method == "rodas4"
    assert run_config(point, RunRequest(0.2, strict=1), 2.0, DEFAULT).numerics.method == "rodas5"
    same = Certify(method="rodas4")
    assert run_config(point, RunRequest(0.2, strict=1), 2.0, same).numerics.method == "rodas4"
    own = RunRequest(0.2, strict=1, own_method=True)
    assert run_config(point, own, 2.0, DEFAULT).numerics.method == "rodas4"
    radau = scene_from_dict({"scene": "pin", "numerics": {"method": "scipy-radau"}})
    strict = run_config(radau, RunRequest(0.2, strict=1), 2.0, DEFAULT).numerics
    assert strict.method == "scipy-radau"


def test_a_jump_that_leaves_its_prescan_cell_at_stricter_numerics_is_followed():
    """Seed 0 scene 0 of the well-posedness study in miniature: the prescan value 0.08
    sticks at the point's numerics (an extrapolated shakedown) but not when watched, and the
    jump lies in the next cell. The re-search follows it there instead of losing it."""
    result = drive(
        JumpSearch(tuple(0.01 * k for k in range(2, 30, 3)), TOL, 2, "decide", 2, Certify()),
        threshold(0.0774, 0.0912),
    )
    assert result.status == "converged", result.reason
    (jump,) = result.jumps
    assert jump.certification == "recertified"
    assert jump.mu_lo < 0.0912 <= jump.mu_hi and jump.mu_hi - jump.mu_lo <= TOL * (1 + 1e-9)


def test_a_re_search_that_stalls_is_uncertain_not_vanished():
    def outcome(mu, strict):
        if strict == 0:
            return "stick" if mu >= 0.13 else "stick_slip"
        return "undetermined" if mu >= 0.13 else "stick_slip"

    result = drive(bisection(), outcome)
    assert result.certification == "uncertain"
    assert result.status == "converged"  # the checks were undetermined: the bracket is kept


def test_certification_watches_only_when_asked():
    """certify.observe: the stricter levels take numerics.evidence observe."""
    from frictiondisk.model.scene import scene_from_dict
    from frictiondisk.tasks.jump_search.requests import run_config

    point = scene_from_dict({"scene": "pin"})
    plain = run_config(point, RunRequest(0.2, strict=1), 2.0, Certify())
    watched = run_config(point, RunRequest(0.2, strict=1), 2.0, Certify(observe=True))
    base = run_config(point, RunRequest(0.2), 2.0, Certify(observe=True))
    assert plain.numerics.evidence == base.numerics.evidence == "extrapolate"
    assert watched.numerics.evidence == "observe"
    assert Certify(observe=False).canonical() == Certify().canonical()  # journals keep


def test_every_run_is_listed_by_the_request_that_ran():
    """A check that flipped becomes the re-search's bracket end without running again; the
    runs name it by the request that ran (its reach included), so that a caller keeping
    its results by request (the trace's run log) finds every one."""
    ran = []

    def answer(mu, strict):
        return {"outcome": threshold(0.13, 0.1337)(mu, strict)}

    search = bisection()
    while not search.done:
        for request in list(search.pending()):
            if not search.done and request in search.pending():
                ran.append(request)
                search.feed(request, answer(request.mu, request.strict))
    result = search.result()
    assert result.certification == "recertified"
    assert all(run.request in ran for run in result.runs)
    assert len(result.runs) == len(set(ran))
