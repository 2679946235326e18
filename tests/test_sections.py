"""Evidence from the motion's own section (frictiondisk/verdict/section_evidence.py,
docs/model.md section 6): synthetic section sequences with a known future, and the runs of
a Stribeck pin whose transient the old trend test let through."""

from __future__ import annotations

import math

import numpy as np
import pytest
from verdict_records import DEFAULT, records, sequence

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict import records as rc
from frictiondisk.verdict.params import VerdictParams
from frictiondisk.verdict.section_evidence import section_evidence

S0 = 1e-8  # slip per step that counts as none [m]


def evidence(points, slip, stick, rtol=1e-6, stribeck=False):
    """The EV_* code of a sequence and the verdict record with its diagnostics: points
    (n, <= 5) [m], slip (n) [m], stick (n) [s]; stribeck: the friction law falls with the
    slip speed."""
    rules, _, vs = records(S0, rtol=rtol, stribeck=stribeck)
    seq = sequence(points, slip, stick)
    return int(section_evidence(DEFAULT, rules, vs, seq, len(slip), S0)), vs


def along(distances, start=(0.05, 0.03)):
    """Section points stepping by `distances` [m] along a fixed direction."""
    travel = np.concatenate([[0.0], np.cumsum(distances)])
    return np.column_stack([start[0] + 0.6 * travel, start[1] + 0.8 * travel])


def test_a_section_still_moving_towards_sticking_is_no_evidence():
    # the transient: the section still moves 0.076 m a cycle, the slip per cycle
    # falls and the sticking time grows (as a Stribeck pin's does on its way to sticking)
    n = 10
    steps = 0.076 * 0.97 ** np.arange(n - 1)
    slip = 0.2 * 0.9 ** np.arange(n)
    stick = 2.0 + 0.3 * np.arange(n)
    code, _ = evidence(along(steps), slip, stick)
    assert code == rc.EV_NONE


def test_a_slow_passage_with_a_growing_ratio_is_no_contraction():
    # distances shrink, but by a ratio that grows towards and past 1 (a ghost of a fold)
    ratios = 0.6 + 0.06 * np.arange(9)
    steps = 0.02 * np.cumprod(ratios)
    slip = np.full(len(steps) + 1, 0.1) - 1e-3 * np.arange(len(steps) + 1)
    code, mf = evidence(along(steps), slip, np.full(len(slip), 1.4))
    assert code == rc.EV_NONE and mf["ev_ratio_bound"] > VerdictParams().q_max


def test_a_geometric_contraction_to_a_slipping_cycle_is_evidence():
    q = 0.78
    steps = 0.01 * q ** np.arange(14)
    slip = 0.1 + 0.08 * q ** np.arange(15)  # converges to 0.1 m a cycle
    stick = 1.237 + 0.1 * q ** np.arange(15)  # the sticking time falls to its limit
    code, mf = evidence(along(steps), slip, stick)
    assert code == rc.EV_CONTRACT
    assert mf["ev_ratio"] == pytest.approx(q, rel=1e-9)
    # the travel still to come is the geometric tail of the newest step
    assert mf["ev_limit"] == pytest.approx(
        steps[-1] * mf["ev_ratio_bound"] / (1 - mf["ev_ratio_bound"])
    )


def test_a_fast_contraction_while_the_slip_falls_ever_slower_is_no_evidence():
    """Study scene 6/10 (a Stribeck pin) at 46 s: its section contracts by 0.665 a
    revolution, but its slip per revolution falls by 0.57, 0.66, 0.75 of the fall before,
    ever slower: the slip follows a slower direction than the distances show. The run
    leaves the cycle the distances pointed to and sticks at 102 s."""
    steps = [6.471e-02, 4.416e-02, 2.990e-02, 2.020e-02, 1.357e-02, 9.058e-03, 6.021e-03]
    slip = [3.1118e-01, 1.2992e-01, 9.2374e-02, 7.5640e-02, 6.7124e-02, 6.2254e-02]
    slip += [5.9043e-02, 5.6636e-02]
    code, mf = evidence(along(steps), slip, np.zeros(len(slip)))
    assert mf["ev_ratio_bound"] < 0.7  # the distances alone would have passed
    assert code == rc.EV_NONE
    # the same distances with a slip whose falls shrink at the distances' ratio: evidence
    q = 0.665
    falls = 2.4e-3 * q ** np.arange(len(slip) - 1)
    steady = 0.05 + np.concatenate([[0.0], np.cumsum(falls[::-1])])[::-1]
    code, _ = evidence(along(steps), steady, np.zeros(len(slip)))
    assert code == rc.EV_CONTRACT


def test_a_stribeck_slip_still_falling_is_no_evidence_of_a_cycle():
    """Study scene 1/43 (a Stribeck disk spinning up) at 350 s: its section contracts by
    0.59 a revolution while its slip falls by a steady 0.96 of the fall before, 9 % of
    it still to come. Under Coulomb friction that is a cycle that still slips; under a
    Stribeck law the falling slip speed raises the friction and feeds its own fall (the
    disk sticks for good at 1 265 s): no evidence until the slip is steady within the 1 %
    a steady slip may lose."""
    q, r = 0.59, 0.96
    steps = 1e-3 * q ** np.arange(14)
    falls = 4.0e-4 * r ** np.arange(14)
    slip = 0.1 - np.concatenate([[0.0], np.cumsum(falls)])
    remaining = falls[-1] * r / (1 - r) / slip[-1]
    assert 0.01 < remaining < VerdictParams().contract_slip_fall
    stick = np.zeros(len(slip))
    assert evidence(along(steps), slip, stick)[0] == rc.EV_CONTRACT
    assert evidence(along(steps), slip, stick, stribeck=True)[0] == rc.EV_NONE
    # the same section with a slip that has nearly stopped falling: a cycle either way
    settled = 0.1 - np.concatenate([[0.0], np.cumsum(falls * 1e-2)])
    assert evidence(along(steps), settled, stick, stribeck=True)[0] == rc.EV_CONTRACT


def test_an_algebraic_contraction_is_not_taken_for_a_geometric_one():
    # distances ~ n^-3: the ratio creeps towards 1 like 1 - 3/n
    k = np.arange(10, 30)
    steps = 1e-2 * (k / 10.0) ** -3.0
    slip = 0.05 + 1e-3 * (k[0] / np.append(k, k[-1] + 1)) ** 2
    code, _ = evidence(along(steps), slip, np.full(len(slip), 1.0))
    assert code != rc.EV_CONTRACT


def test_a_repeating_section_is_a_cycle_and_a_moving_one_is_not():
    rng = np.random.default_rng(0)
    noise = 1e-10 * rng.standard_normal((12, 2))
    slip = 0.1 + 1e-9 * rng.standard_normal(12)
    code, mf = evidence(np.array([0.0355, 0.0302]) + noise, slip, np.full(12, 1.237))
    assert code == rc.EV_REPEAT and mf["ev_distance"] < 1e-9
    # a period-2 cycle repeats every second step
    two = np.array([[0.03, 0.02], [0.05, -0.01]] * 6) + noise
    code, _ = evidence(two, slip, np.full(12, 1.2))
    assert code == rc.EV_REPEAT
    # steps of 1e-5 m (ten times cycle_tol) are no repeat
    code, _ = evidence(along(np.full(11, 1e-5)), slip, np.full(12, 1.2))
    assert code != rc.EV_REPEAT


def test_a_creep_onto_a_sticking_circle_never_repeats():
    # the section moves 4e-8 m a step (within cycle_tol) while the slip per step still
    # falls by 0.7 % and the sticking time grows: an algebraic approach, not a cycle
    n = 12
    slip = 1.7e-7 * (1 - 0.007) ** np.arange(n)
    stick = 10.08 + 1e-3 * np.arange(n)
    code, _ = evidence(along(np.full(n - 1, 4e-8)), slip, stick)
    assert code == rc.EV_NONE


def test_a_creep_that_sticks_a_whole_revolution_now_and_then_never_repeats():
    """A revolution section modelled on seed 6 scene 32 (mu = 0.0765753): steps of 7e-8 m
    a revolution shrinking by 0.94 (a tail within cycle_tol), the slip per revolution
    falling 6 % a revolution and the sticking time growing, except every fifth
    revolution, which sticks throughout (slip 4e-14 m). Read step against step eight
    back, such a revolution hid the trend and the old rule called a cycle. (The real
    run at rtol 1e-5 still does: its slip falls by less than atol = 1e-8 m over the
    window, docs/wellposed.md.)"""
    n = 20
    slip = 6.2e-8 * 0.94 ** np.arange(n)
    stick = 9.49 + 0.009 * np.arange(n)
    whole = np.arange(n) % 5 == 1  # one of them eight steps before the newest
    slip[whole], stick[whole] = 4e-14, 10.075
    code, _ = evidence(along(7e-8 * 0.94 ** np.arange(n - 1)), slip, stick, rtol=1e-5)
    assert code != rc.EV_REPEAT


def test_a_growing_slip_and_shrinking_sticking_time_is_a_departure():
    n = 6
    steps = 0.0175 * 1.09 ** np.arange(n - 1)
    slip = 0.0073 * 1.25 ** np.arange(n)
    stick = 3.52 - 0.12 * np.arange(n)
    code, _ = evidence(along(steps), slip, stick)
    assert code == rc.EV_DEPART
    # the same section approaching sticking (slip falling, sticking longer) is not
    code, _ = evidence(along(steps), slip[::-1], stick[::-1])
    assert code == rc.EV_NONE


def test_a_slip_below_the_tolerance_that_does_not_fall_is_no_departure():
    """A pin creeping onto the rim of its sticking disc (well-posedness seed 2 scene 24,
    mu = 0.103125) sticks for all but milliseconds of a cycle and slips about 5e-11 m a
    cycle, at the friction law's floor: a slip that does not fall there was read as a
    departure from sticking, and the point's certified mu* lay 1.3 tol above the jump."""
    n = 6
    steps = 5.3e-11 * (1.0 + 0.01 * np.arange(n - 1))
    slip = 5.0e-11 * (1.0 + 0.02 * np.arange(n))
    stick = 6.31 - 1e-8 * np.arange(n)
    code, _ = evidence(along(steps), slip, stick)
    assert code == rc.EV_NONE
    # the same shape with a slip per step above the tolerance still departs
    code, _ = evidence(along(steps * 1e4), slip * 1e4, stick)
    assert code == rc.EV_DEPART


@pytest.mark.parametrize("law", ["geometric", "power"])
def test_a_slip_that_falls_to_nothing_is_shakedown(law):
    k = np.arange(1, 41)
    slip = 1e-3 * 0.8**k if law == "geometric" else 1e-3 * k**-2.0
    stick = 10.0 - 5.0 * slip / slip[0]
    code, mf = evidence(along(np.full(len(k) - 1, 1e-4)), slip, stick)
    assert code == rc.EV_SHAKEDOWN and mf["ev_limit"] <= S0
    # the same fall towards a slip that stays (a cycle) is no shakedown
    code, _ = evidence(along(np.full(len(k) - 1, 1e-4)), slip + 1e-4, stick)
    assert code != rc.EV_SHAKEDOWN
    # nor towards one that stays below s0 (the demo disk at x_ms 0.12, mu = 0.142785:
    # 1.4e-9 m a revolution levelling off at 8e-10 m, s0 = 6e-9 m, then rising again):
    # the limit must be nothing beside the slip still left, not merely <= s0
    k = np.arange(1, 81)  # on until the slip is within 1 % of its floor
    slip = (1e-3 * 0.8**k if law == "geometric" else 1e-3 * k**-6.0) + 0.3 * S0
    stick = 10.0 - 5.0 * slip / slip[0]
    code, _ = evidence(along(np.full(len(k) - 1, 1e-4)), slip, stick)
    assert code != rc.EV_SHAKEDOWN


# A Stribeck pin of the well-posedness study (seed 2, scene 18). At mu = 0.0885 its
# stick-slip cycle drifts onto sticking: the section moves 2e-3 m a cycle, the slip per
# cycle falls and the sticking time grows, and it sticks for good at t = 141.7 s. The old
# trend test called it stick_slip at t = 91 s. At mu = 0.0875 the cycle converges.
STRIBECK_PIN = {
    "scene": "pin",
    "params": {
        "x_ms": 0.0831730301512242,
        "x0": 0.016238610057472506,
        "m_s": 1.156135679724225,
        "omega_m": 0.620894193870852,
    },
    "contact": {"stribeck": {"r": 0.812197287277602, "v_s": 0.027744485632723612}},
}


def stribeck_pin(mu, **numerics):
    data = {**STRIBECK_PIN, "params": {**STRIBECK_PIN["params"], "mu": mu}, "numerics": numerics}
    return simulate(scene_from_dict(data))


def test_a_transient_towards_sticking_is_extended_not_classified():
    res = stribeck_pin(0.0885)
    assert res.outcome == "stick", res.reason
    assert res.t_end > 4 * 30.0  # extended far past t_decide, one revolution at a time
    # with too small a budget it is undetermined, never guessed
    short = stribeck_pin(0.0885, horizon_budget=2.0)
    assert short.outcome == "undetermined" and "without evidence" in short.reason
    assert short.t_end <= 2 * 30.0 + 2 * math.pi / 0.620894193870852 + 1e-9


def test_a_converging_cycle_is_decided_on_its_contraction():
    res = stribeck_pin(0.0875)
    assert res.outcome == "stick_slip"
    assert "contracts geometrically" in res.reason or "repeats" in res.reason


# seed 1, scene 11 of the well-posedness study: a Stribeck disk from rest
SPINNING_UP_DISK = {
    "scene": "disk",
    "params": {
        "x_ms": 0.10002156041412706,
        "x0": 0.012722845174837918,
        "m_s": 1.4661115767544837,
        "omega_m": 0.6567790248679494,
        "J_s": 0.12643285052985825,
        "phidot0": 0.0,
        "beta_b": 0.0,
        "mu": 0.14504,
    },
    "contact": {"stribeck": {"r": 0.6085002829460746, "v_s": 0.009646864701386119}},
    "numerics": {"rtol": 1e-4, "atol": 1e-7, "t_decide": 30.0, "horizon_budget": 8.0},
}


def test_a_disk_spinning_up_is_not_a_sliding_state():
    """Its slip per revolution rises now and then while its spin climbs towards the
    master's at every revolution: the old sliding test read `slide` at 145 s; it sticks at
    about 162 s (settled at rtol 1e-6 and a 240 s horizon: sticks)."""
    res = simulate(scene_from_dict(SPINNING_UP_DISK))
    assert res.outcome == "stick", res.reason
    spin = res.revolutions["w"]
    before = spin[res.revolutions["slip"] > 1e-3]
    assert len(before) >= 8 and np.all(np.diff(before) > 0)  # it spun up at every one


# seed 1, scene 43 of the well-posedness study just below its jump, with the numerics that
# a find_jump campaign at tol 1e-4 gives it
STRIBECK_SPIN_UP = {
    "scene": "disk",
    "params": {
        "x_ms": 0.08151636348382833,
        "x0": -0.009292144119577062,
        "m_s": 0.721844207963218,
        "omega_m": 0.8887836793461847,
        "J_s": 0.19584579332901425,
        "phidot0": 0.0,
        "beta_b": 0.0046556319561811875,
        "mu": 0.17500976562499998,
    },
    "contact": {"stribeck": {"r": 0.6050418428444387, "v_s": 0.0067820550459571395}},
    "numerics": {"rtol": 1e-6, "atol": 1e-12, "t_decide": 60.0, "horizon_budget": 8.0},
}


def test_a_stribeck_disk_spinning_up_is_extended_not_called_sliding():
    """The certified default read `slide` at 350 s (its retry at t_decide 60 s); the
    study's settling run (eps / 100, rtol / 100, watched) sticks for good at 1 265 s."""
    res = simulate(scene_from_dict(STRIBECK_SPIN_UP))
    assert res.outcome == "undetermined", res.reason
    slip = res.revolutions["slip"]
    assert slip[-1] < 0.95 * slip[-30]  # still falling: over 5 % in its last 30 revolutions


# seed 0, scene 0 of the well-posedness study: a pin whose slip per revolution falls like a
# power law for 80 s, then levels off at a stick-slip cycle slipping 3.5e-7 m a revolution
LEVELLING_PIN = {
    "scene": "pin",
    "params": {
        "x_ms": 0.07697867137638703,
        "x0": -0.027541588563828316,
        "m_s": 0.5247914532927936,
        "omega_m": 1.2369616873214544,
        "mu": 0.08,
    },
    "numerics": {"rtol": 1e-6, "atol": 1e-9, "t_decide": 30.0, "horizon_budget": 32.0},
}


@pytest.mark.parametrize("evidence", ["extrapolate", "observe"])
def test_an_extrapolated_shakedown_is_a_prediction_that_watching_can_refute(evidence):
    """The shakedown rule reads stick at 81 s; watched (numerics.evidence observe, what
    certify.observe asks of certification), the run never sticks within its budget: the
    study settled it as a cycle repeating at 1 500 s. docs/model.md section 6."""
    data = {**LEVELLING_PIN, "numerics": {**LEVELLING_PIN["numerics"], "evidence": evidence}}
    res = simulate(scene_from_dict(data))
    if evidence == "extrapolate":
        assert res.outcome == "stick" and "shakes down" in res.reason, res.reason
        assert res.t_end < 120.0
    else:
        assert res.outcome != "stick", res.reason
        assert res.t_end > 10 * 81.0


# seed 6, scene 10 of the well-posedness study: a Stribeck pin just above its jump
SADDLE_PIN = {
    "scene": "pin",
    "params": {
        "x_ms": 0.13762500093246943,
        "x0": 0.02928388496890242,
        "m_s": 0.6309643472975814,
        "omega_m": 1.1703882498218685,
        "mu": 0.151858,
    },
    "contact": {"stribeck": {"r": 0.9042914930715614, "v_s": 0.001881213208528522}},
    "numerics": {"rtol": 1e-5, "atol": 1e-8, "t_decide": 30.0, "horizon_budget": 8.0},
}


def test_a_contraction_towards_an_unstable_cycle_is_extended_until_it_sticks():
    """The old rule read `slide` at 46 s ("contracts geometrically by 0.665 a revolution
    ... towards a cycle that still slips"); watched for 1 500 s (the study's settling run)
    it sticks at 102 s."""
    res = simulate(scene_from_dict(SADDLE_PIN))
    assert res.outcome == "stick", res.reason
    assert res.t_end > 90.0


def test_a_creep_below_the_repeat_tolerance_is_no_cycle_until_its_slip_is_steady():
    """Seed 0 scene 0 of the well-posedness study at mu = 0.085, watched: a pin creeping
    onto its sticking disc moves its section by its slip, 1.5e-8 m a revolution (far
    within cycle_tol), switching irregularly between two levels while both fall 0.13 % a
    revolution; the old rule read it as a cycle repeating within 2e-8 m. A walk whose slip
    is as small but steady (a pin at eps = 1e-3 m/s below its Coulomb bound) repeats."""
    rng = np.random.default_rng(1)
    n = 128
    low = rng.random(n) < 0.4
    slip = 1.45e-8 * 0.9987 ** np.arange(n) * np.where(low, 0.885, 1.0)
    stick = np.where(low, 5.004, 4.996)
    code, _ = evidence(along(slip[:-1]), slip, stick)
    assert code != rc.EV_REPEAT
    walk = 3e-7 * np.where(np.arange(n) % 2 == 0, 1.0, 1.006)
    code, _ = evidence(along(1.1 * walk[:-1]), walk, np.full(n, 5.59))
    assert code == rc.EV_REPEAT
    # summed per period: a period-2 creep alternating long and short sticking phases
    # (seed 2 scene 24, mu = 0.105: steps of 1.2e-8 and 2.2e-13 m) is no cycle either
    pair = np.where(np.arange(n) % 2 == 0, 1.2e-8, 2.2e-13) * 0.9985 ** np.arange(n)
    points = np.array([[0.03, 0.02], [0.05, -0.01]] * (n // 2)) + along(pair[:-1]) - 0.05
    code, _ = evidence(points, pair, np.where(np.arange(n) % 2 == 0, 6.1, 0.02))
    assert code != rc.EV_REPEAT


def test_a_slip_growing_below_the_repeat_tolerance_is_no_repeat():
    """Generator 1's 1/42 at mu_lo 0.0666492 (a Stribeck pin): its section moves 2e-8 m a
    step, far within cycle_tol, while its slip per step grows 1.2 % a step (and the step
    with it) and its sticking time shrinks; 100 revolutions later one large slip lands it
    on a sticking circle (it sticks at 435 s). A slip shown to grow is a departure in
    progress, not a cycle; the same section with a level slip repeats."""
    n = 20
    slip = 1.25e-7 * 1.012 ** np.arange(n)
    stick = 3.9527 - 3.5e-4 * np.arange(n)
    code, _ = evidence(along(2e-8 * 1.012 ** np.arange(n - 1)), slip, stick, rtol=1e-7)
    assert code == rc.EV_DEPART
    level = np.full(n, 1.25e-7)
    code, _ = evidence(along(np.full(n - 1, 2e-8)), level, np.full(n, 3.95), rtol=1e-7)
    assert code == rc.EV_REPEAT


def test_a_growth_within_the_slip_that_counts_as_none_does_not_refuse_a_repeat():
    """Below S0 a step slips nothing: the Coulomb pin at its jump slips 1e-13 m a
    revolution at roundoff, and that noise may drift either way."""
    n = 20
    slip = 1e-13 * 1.05 ** np.arange(n)
    code, _ = evidence(along(np.full(n - 1, 1e-10)), slip, np.full(n, 6.28), rtol=1e-7)
    assert code == rc.EV_REPEAT


def _followed(stick, t_stop, until=960.0):
    """The evidence of a departing section followed until `until` [s]
    (numerics.follow_departures_until), the run's horizon at t_stop and a budget four times
    as long [s] (one revolution: 1 s)."""
    n = 6
    rules, _, vs = records(S0)
    rules["follow_until"] = until
    rules["budget"] = 4.0 * until
    vs["t_stop"] = t_stop
    steps = 0.0175 * 1.09 ** np.arange(n - 1)
    slip = 0.0073 * 1.25 ** np.arange(n)
    seq = sequence(along(steps), slip, stick)
    return int(section_evidence(DEFAULT, rules, vs, seq, n, S0))


def test_a_followed_departure_decides_only_at_its_last_horizon_and_only_from_sticking():
    """A certification check of an extrapolated verdict follows a departure to where it
    lands: before the last horizon of its following it is no evidence; at it and after it
    (the check's budget reaches further), a departure from sticking decides, and a sliding
    slave's (no sticking in its steps) does not."""
    sticking = 3.52 - 0.12 * np.arange(6)
    assert _followed(sticking, t_stop=500.0) == rc.EV_NONE
    assert _followed(sticking, t_stop=959.5) == rc.EV_DEPART
    assert _followed(sticking, t_stop=2000.0) == rc.EV_DEPART
    assert _followed(np.zeros(6), t_stop=959.5) == rc.EV_NONE
    assert _followed(sticking, t_stop=959.5, until=0.0) == rc.EV_DEPART  # not followed
