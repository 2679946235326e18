"""Melan and Koiter decide a braked disk on its small orbit (frictiondisk/verdict/shakedown_verdict.py).

The oracle is independent of the bound: watching runs (numerics.evidence observe, which
never consults it) at a friction law ten times finer (eps / 10), long enough to see the
answer. Tolerances are in units of the requested accuracy TOL = 1e-4 in mu.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from verdict_records import DEFAULT

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.pack import pack_parameters
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict import admissibility as ad
from frictiondisk.verdict import shakedown_bound as sdb
from frictiondisk.verdict import shakedown_verdict as sv
from frictiondisk.verdict.params import VerdictParams

TOL = 1e-4
# Well-posedness study seed 8 scene 21: a braked disk from a co-rotating start. The rules
# alone (slip <= eps T a revolution counts as none) leave mu = 0.4098 ... 0.4138 undecided
# at the 240-s horizon; its Melan bound lies near 0.41185.
BRAKED = {
    "scene": "disk",
    "params": {
        "x_ms": 0.12712077135431815,
        "x0": 0.021069256510105522,
        "m_s": 1.1014399507224302,
        "omega_m": 1.470803755847602,
        "J_s": 0.026996583467822834,
        "phidot0": 1.470803755847602,
        "beta_b": 0.004705457858108205,
    },
    "numerics": {"rtol": 1e-6, "atol": 1e-12, "t_decide": 30.0},
}


def _scene(mu: float, **overrides):
    return scene_from_dict(BRAKED).with_overrides({"params.mu": mu, **overrides})


def _watch(mu: float):
    """The oracle: observe only, eps / 10, up to 12 000 s."""
    return simulate(
        _scene(
            mu,
            **{
                "numerics.evidence": "observe",
                "numerics.t_decide": 1500.0,
                "numerics.horizon_budget": 8.0,
                "contact.eps": 1e-10,
            },
        )
    )


@pytest.fixture(scope="module")
def bound() -> float:
    """The scene's Melan bound in mu: the zero of the reserve, interpolated between two runs
    that the bound decides either side of it (the reserve is linear in mu there)."""
    lo, hi = 0.4114, 0.4121
    r_lo, r_hi = _reserve_of(simulate(_scene(lo))), _reserve_of(simulate(_scene(hi)))
    assert r_lo < 0.0 < r_hi
    return lo - r_lo * (hi - lo) / (r_hi - r_lo)


def _still_to_come(history) -> float:
    return sdb.still_to_come(DEFAULT, np.asarray(history, dtype=float), len(history))


def test_the_reserve_history_needs_a_monotone_geometric_approach():
    """How far the reserve may still move towards zero: nothing where it moves away, the
    geometric sum of its steps where they shrink, and no answer otherwise."""
    away = [1.0e-3, 0.9e-3, 0.8e-3, 0.7e-3]
    assert _still_to_come(away) == 0.0
    shrinking = [100.0, 102.0, 106.0, 114.0]  # steps 2, 4, 8: ratio 1/2, 2 still to come
    assert _still_to_come(shrinking) == pytest.approx(2.0)
    steady_approach = [100.0, 102.0, 104.0, 106.0]  # ratio 1: it may reach zero
    assert _still_to_come(steady_approach) == math.inf
    crossing = [1e-4, -1e-4, -3e-4, -5e-4]
    assert _still_to_come(crossing) == math.inf
    short = [100.0, 102.0]  # one step towards zero: no ratio to extrapolate with
    assert _still_to_come(short) == math.inf


def test_the_kernel_stops_once_the_bound_decides_and_reads_admissibilitys_reserve(bound):
    """Three tol above the bound the kernel stops at the revolution end where three blocks
    of 5 revolutions on the small orbit back Melan's verdict, long before its horizon
    budget; the reserve it wrote there is admissibility.py's shakedown demand at that state
    (layout angle from C = A r and the spin angle, assembled independently)."""
    config = _scene(bound + 3 * TOL)
    res = simulate(config, record=True)  # every step: the last is the stop
    assert res.outcome == "stick" and "Melan" in res.reason, res.reason
    assert "the rules said" not in res.reason
    rows = res.revolutions
    assert res.t_end == pytest.approx(rows[-1]["t"], abs=1e-9)
    budget = config.numerics.t_decide * config.numerics.horizon_budget
    assert res.t_end < budget / 2
    vp = VerdictParams()
    on_orbit = rows[-vp.bound_blocks * vp.on_orbit_revs :]["any_stuck"]
    assert np.all(on_orbit)
    traj = res.trajectory
    assert traj.t[-1] == pytest.approx(res.t_end, abs=1e-9)
    x, y, phi = traj.x[-1], traj.y[-1], traj.phi[-1]
    assert math.hypot(x - rows[-1]["x"], y - rows[-1]["y"]) < 1e-12
    par = config.params
    k = par.c_s - par.m_s * par.omega_m**2
    d = par.beta_s * par.omega_m
    angle = math.atan2(k * y + d * x, k * x - d * y) - phi
    case = ad.LoadCase.of(par, math.hypot(x, y), par.beta_b)
    demand = ad.shakedown_demand(case, config.contact_positions(), angle)
    assert rows[-1]["reserve"] == pytest.approx(par.mu - demand / par.F_n, abs=1e-6 * TOL)


def test_the_bound_decides_both_sides_where_the_rules_cannot(bound):
    """Three tol either side of the bound the rules leave the run undecided at its horizon;
    the bound decides it, and its answer does not move with eps."""
    for offset, expected, law in (
        (+3 * TOL, "stick", "Melan"),
        (-3 * TOL, "creep", "Koiter"),
    ):
        for eps in (1e-9, 1e-10):
            res = simulate(_scene(bound + offset, **{"contact.eps": eps}))
            assert res.outcome == expected, res.reason
            assert law in res.reason
        rules = simulate(_scene(bound + offset, **{"numerics.evidence": "observe"}))
        assert rules.outcome == "undetermined", rules.reason


def test_the_watching_oracle_agrees_with_the_bound(bound):
    """Independent of the bound: at eps / 10, watched, the disk sticks 20 tol above the
    bound and ratchets 20 tol below it."""
    above = _watch(bound + 20 * TOL)
    below = _watch(bound - 20 * TOL)
    assert above.outcome == "stick", above.reason
    assert below.outcome == "creep", below.reason


def test_within_the_margin_the_rules_keep_their_verdict(bound):
    """A reserve inside the bound's margin decides nothing: the verdict is the rules'."""
    config = _scene(bound)
    res = simulate(config)
    assert "Melan" not in res.reason and "Koiter" not in res.reason
    assert sv.margin(config) < TOL / 2


def _reserve_of(res) -> float:
    """The reserve the bound read, from the reason it wrote (every run here is decided by
    it or quotes it)."""
    text = res.reason
    key = "friction reserve mu - shakedown demand / F_n = "
    assert key in text, text
    return float(text.split(key)[1].split(" ")[0])


@pytest.mark.parametrize(
    "positions",
    [None, [[0.05, 0.0], [-0.02, 0.04], [-0.03, -0.045]]],
    ids=["ring", "three points off centre"],
)
def test_the_floor_is_the_least_shakedown_demand_of_any_circle(positions):
    """floor_reserve against admissibility.py's shakedown demand scanned over circles and
    layout angles: the floor is never above a scanned demand, and the scan comes within its
    resolution of it (at R = 0 for the centrally symmetric ring)."""
    data = {**BRAKED, "params": {**BRAKED["params"], "mu": 0.3}}
    if positions is not None:
        data["contact"] = {"layout": "points", "positions": positions}
    config = scene_from_dict(data)
    p, pts = pack_parameters(config)
    floor_demand = (config.params.mu - sdb.floor_reserve(p, pts)) * config.params.F_n
    par = config.params
    g = ad.g_factor(par.omega_m, par.c_s, par.m_s, par.beta_s)
    # the resultant of equal tangential forces carrying T: where the least demand lies
    arms = np.asarray(config.contact_positions(), dtype=float)
    tangents = np.column_stack((-arms[:, 1], arms[:, 0])) / np.hypot(*arms.T)[:, None]
    best = par.beta_b * par.omega_m / np.hypot(*arms.T).sum() * tangents.sum(axis=0)
    lowest, nearest = math.inf, math.inf
    for radius in np.linspace(0.0, 0.2, 201):
        case = ad.LoadCase.of(par, radius, par.beta_b)
        for angle in np.linspace(0.0, 2 * math.pi, 73):
            demand = ad.shakedown_demand(case, config.contact_positions(), angle)
            assert demand >= floor_demand * (1 - 1e-9)
            lowest = min(lowest, demand)
            c_vec = g * radius * np.array([math.cos(angle), math.sin(angle)])
            nearest = min(nearest, float(np.hypot(*(c_vec - best))))
    # Lambda(C, T) moves by at most |dC| (spread dC over the N points): the scan comes
    # within its distance from the best resultant
    assert lowest - floor_demand <= nearest + 1e-9 * floor_demand


def test_below_the_floor_the_disk_is_decided_not_to_stick_at_once():
    """Study scene 8/13 (floor 0.13338) at mu = 0.12: the rules followed its centre drifting
    inwards 3e-5 m a revolution, undecided for 960 s; no circle can hold it, so it is not
    stick at its t_decide, and a stick of the rules there becomes Koiter's creep."""
    scene = {
        "scene": "disk",
        "params": {
            "x_ms": 0.0766148418966727,
            "x0": 0.027719596859956258,
            "m_s": 0.8119763169685195,
            "omega_m": 0.6808955167804953,
            "J_s": 0.14929698284274945,
            "phidot0": 0.6808955167804953,
            "beta_b": 0.004168245707039673,
            "mu": 0.12,
        },
        "numerics": {"rtol": 1e-6, "atol": 1e-12, "t_decide": 30.0},
    }
    config = scene_from_dict(scene)
    res = simulate(config)
    assert res.outcome in ("stick_slip", "slide"), res.reason
    assert "least shakedown demand" in res.reason and res.t_end == pytest.approx(30.0)
    observed = simulate(config.with_overrides({"numerics.evidence": "observe"}))
    assert observed.outcome == "undetermined", observed.reason  # the rules alone cannot
    outcome, reason = sv.decide(config, "stick", "the rules' stick", None, -1e-2, VerdictParams())
    assert outcome == "creep" and "Koiter" in reason


def test_a_stick_of_the_rules_waits_while_its_own_circle_cannot_hold_it():
    """Fig 11 from a co-rotating start at beta_b = 0.0275 and mu = 0.705794, 15 tol below
    the Melan bound of its own circle: its slip per revolution falls below eps T within
    80 s, which the rules alone read as `stick`. A disk stuck for good is shaken down on
    its own circle, so that stick waits while the circle cannot hold it, and 15
    revolutions on the small orbit later Koiter decides: it ratchets."""
    scene = {
        "scene": "disk",
        "params": {"x_ms": 0.1, "phidot0": 1.1, "beta_b": 0.0275, "mu": 0.705794},
        "numerics": {"rtol": 1e-6, "atol": 1e-12, "t_decide": 30.0},
    }
    config = scene_from_dict(scene)
    res = simulate(config)
    assert res.outcome == "creep" and "Koiter" in res.reason, res.reason
    assert res.revolutions[-1]["reserve"] < -10 * sv.margin(config)
    rules = simulate(config.with_overrides({"numerics.evidence": "observe"}))
    assert rules.outcome == "stick" and rules.t_end < res.t_end, rules.reason


# Well-posedness study, generator 2, seed 3 scene 29: a braked disk from rest on a 16-point
# annulus (weights 0.98 and 1.01). Left to the rules (before NUMERICS_VERSION 11) its
# certified stick end 0.1066638 co-rotated at eps = 1e-9 m/s with a slip of 96 % of eps T a
# revolution, and ratchets at eps / 100. The weighted bound puts the jump near 0.10691.
ANNULUS = {
    "scene": "disk",
    "params": {
        "J_s": 0.027257297042697037,
        "beta_b": 0.0008649380265505754,
        "m_s": 1.3866889746378783,
        "omega_m": 0.8355400137256128,
        "x0": -0.006091341376040765,
        "x_ms": 0.09263328072164023,
    },
    "contact": {
        "layout": "annulus",
        "inner_radius": 0.026422572699741267,
        "outer_radius": 0.07627772809853586,
        "points": 16,
    },
    "numerics": {"rtol": 1e-6, "atol": 1e-12, "t_decide": 30.0},
}


def test_an_annulus_is_decided_by_its_weighted_bound_and_the_watch_agrees():
    """The bound reads the weights of a centred layout, so it decides the annulus, and the
    oracle (watching at eps / 100, rtol and atol / 100, which never consults the bound)
    agrees on both sides: 3 tol above the bound the disk sticks; the old stick end, 2.4 tol
    below it, ratchets for good."""
    config = scene_from_dict(ANNULUS)
    assert sv.applies(config.with_overrides({"params.mu": 0.1}))
    assert not np.all(config.contact_weights() == config.contact_weights()[0])
    watch = {
        "numerics.evidence": "observe",
        "numerics.rtol": 1e-8,
        "numerics.atol": 1e-14,
        "numerics.t_decide": 1500.0,
        "contact.eps": 1e-11,
    }
    above, below = 0.10691 + 3 * TOL, 0.1066638
    run = simulate(config.with_overrides({"params.mu": above}))
    assert run.outcome == "stick" and "Melan" in run.reason, run.reason
    seen = simulate(config.with_overrides({"params.mu": above, **watch}))
    assert seen.outcome == "stick", seen.reason
    run = simulate(config.with_overrides({"params.mu": below}))
    assert run.outcome != "stick", run.reason
    seen = simulate(config.with_overrides({"params.mu": below, **watch}))
    assert seen.outcome == "creep", seen.reason
