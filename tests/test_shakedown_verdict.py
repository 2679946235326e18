"""Melan and Koiter decide a braked disk on its small orbit (frictiondisk/outcome/shakedown_verdict.py).

The oracle is independent of the bound: watching runs (numerics.evidence observe, which
never consults it) at a friction law ten times finer (eps / 10), long enough to see the
answer. Tolerances are in units of the requested accuracy TOL = 1e-4 in mu.
"""

from __future__ import annotations

import math

import pytest

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.outcome import shakedown_verdict as sv
from frictiondisk.simulation.simulate import simulate

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


def test_the_reserve_history_needs_a_monotone_geometric_approach():
    """How far the reserve may still move towards zero: nothing where it moves away, the
    geometric sum of its steps where they shrink, and no answer otherwise."""
    away = [1.0e-3, 0.9e-3, 0.8e-3, 0.7e-3]
    assert sv._still_to_come(away) == 0.0
    shrinking = [100.0, 102.0, 106.0, 114.0]  # steps 2, 4, 8: ratio 1/2, 2 still to come
    assert sv._still_to_come(shrinking) == pytest.approx(2.0)
    steady_approach = [100.0, 102.0, 104.0, 106.0]  # ratio 1: it may reach zero
    assert sv._still_to_come(steady_approach) == math.inf
    crossing = [1e-4, -1e-4, -3e-4, -5e-4]
    assert sv._still_to_come(crossing) == math.inf
    short = [100.0, 102.0]  # one step towards zero: no ratio to extrapolate with
    assert sv._still_to_come(short) == math.inf


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
