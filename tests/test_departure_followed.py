"""A departure from sticking is a motion in progress (issue 50): generator 1's 1/42, a
Stribeck pin whose certified mu_lo was called `slide` by a departure at 32.5 s and sticks
for good at 435 s. Its certification check follows the departure to where it lands
(numerics.follow_departures_until, set with the watch: tasks/jump_search/requests.py)."""

from __future__ import annotations

import pytest

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.model.search_settings import Certify
from frictiondisk.simulation.simulate import simulate
from frictiondisk.tasks.jump_search.bisection import RunRequest
from frictiondisk.tasks.jump_search.requests import run_config

MU_LO = 0.06664924653560993  # the certified bracket's lower end
# the well-posedness study's scene (generator 1, seed 1, scene 42) at its campaign's numerics
PIN_1_42 = {
    "scene": "pin",
    "params": {
        "F_n": 1.0,
        "beta_s": 0.1,
        "c_s": 1.0,
        "m_s": 0.6179541114588963,
        "mu": MU_LO,
        "omega_m": 1.5444742621120224,
        "x0": 0.0139076393941776,
        "x_ms": 0.05009892302179292,
    },
    "contact": {
        "damping_ratio": 1.0,
        "eps": 1.0e-9,
        "stiffness": 253000.0,
        "stribeck": {"r": 0.7202370578735778, "v_s": 0.0015510105710485461},
    },
    "numerics": {"rtol": 1.0e-5, "atol": 1.0e-8, "t_decide": 30.0},
}


@pytest.fixture(scope="module")
def default_run():
    return simulate(scene_from_dict(PIN_1_42))


def test_the_default_reads_the_departure_as_not_stick(default_run):
    assert (default_run.outcome, default_run.decided_by) == ("stick_slip", "depart")
    assert default_run.t_end < 40.0


def test_the_check_follows_the_departure_and_sees_it_stick(default_run):
    """The check of that end (rtol and atol x certify.rtol, watching 2 x 32.5 s) is no
    longer decided by the same departure after its watch: it follows it, and the pin
    sticks, seen (co-rotation), after about 100 revolutions of growing slip."""
    watch = Certify().watch * default_run.t_end
    request = RunRequest(MU_LO, strict=1, watch=watch, reach=2)
    check = run_config(scene_from_dict(PIN_1_42), request, 2.0, Certify())
    # followed to the end of the check's strict budget, 30 s x 8 x 4, short of its reach
    assert check.numerics.follow_departures_until == pytest.approx(960.0)
    run = simulate(check)
    assert (run.outcome, run.decided_by) == ("stick", "corotation")
    assert 300.0 < run.t_end < check.numerics.follow_departures_until


def test_only_a_watching_check_follows_departures():
    point = scene_from_dict(PIN_1_42)
    assert not point.numerics.follow_departures_until
    assert "follow_departures_until" not in point.canonical()["numerics"]  # journals keep
    plain = run_config(point, RunRequest(MU_LO, strict=1), 2.0, Certify())
    assert not plain.numerics.follow_departures_until
