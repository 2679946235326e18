"""The spiral about a braked disk's rest point, its Hopf point and its ring's ripple
(verdict/amplitude_trend.py, self_centring.py, slide_cycle.py; docs/model.md section 6).

The braked disk of campaigns/hopf_braked_disk.yaml (mu 0.05, beta_b 0.01, J_s 0.02, ring of
48 points, radius 0.2 m) rests off the axis at |r| ~ 0.096 m; an independent linearisation
puts its Hopf point omega_H in (1.460, 1.468). Started 1e-3 m/s off its rest point, the
spiral's size grows or decays as exp(rate t) from the first few dozen seconds on (measured
over 3 000 s: -3.813e-4 1/s at 1.455, +3.085e-4 at 1.47, the same to 4 digits from 200 s).
Runs here are 200 s long (~1 000 own-period rows of a 48-point disk: a few seconds).
"""

from __future__ import annotations

import math

import pytest

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict.outcomes import is_not_stick

HOPF_LOW, HOPF_HIGH = 1.460, 1.468  # the linearisation's bracket of omega_H


def braked(omega_m: float, t_max: float, points: int = 48, **params) -> dict:
    start = {"x0": -0.007954, "y0": 0.026906, "vy0": 0.001, "phidot0": 0.710131}
    return {
        "scene": "disk",
        "params": {"mu": 0.05, "beta_b": 0.01, "J_s": 0.02, "omega_m": omega_m, **start, **params},
        "contact": {"ring_radius": 0.2, "points": points},
        "numerics": {"mode": "converge", "t_max": t_max},
    }


@pytest.fixture(scope="module")
def either_side():
    return {om: simulate(scene_from_dict(braked(om, 200.0))) for om in (HOPF_LOW, HOPF_HIGH)}


def test_the_spiral_decays_below_the_hopf_point_and_grows_above(either_side):
    """The rate of the spiral changes sign between the linearisation's bounds: below it the
    run self-centres at its measured rate (read ahead, not yet at rest), above it the motion
    leaves its rest point (a cycle, read ahead); neither is named by a tolerance alone."""
    below, above = either_side[HOPF_LOW], either_side[HOPF_HIGH]
    assert below.outcome == "self_centring" and not below.cycle_converged, below.reason
    assert below.decided_by == "amplitude_trend"
    assert above.outcome == "slide_cycle" and not above.cycle_converged, above.reason
    assert above.decided_by == "amplitude_trend"
    assert below.decay_rate > 0.0 > above.decay_rate
    # the rate is linear in omega_m near omega_H: its zero, interpolated, is omega_H
    hopf = HOPF_LOW + (HOPF_HIGH - HOPF_LOW) * below.decay_rate / (
        below.decay_rate - above.decay_rate
    )
    assert HOPF_LOW < hopf < HOPF_HIGH
    # the slope measured over 3 000 s at 1.455 and 1.47: (3.085e-4 + 3.813e-4) / 0.015
    slope = (below.decay_rate - above.decay_rate) / (HOPF_HIGH - HOPF_LOW)
    assert slope == pytest.approx(0.0460, rel=0.05)
    for res in (below, above):
        assert is_not_stick(res.outcome)
        assert res.own_period == pytest.approx(6.23, abs=0.02)  # the spiral's turn
        assert res.floquet_ratio == pytest.approx(
            math.exp(-res.decay_rate * res.own_period), rel=1e-9
        )


def test_a_run_at_rest_on_its_ring_shows_the_ring_s_ripple_which_falls_with_n():
    """Started on its rest point at omega_m 1.2 (the middle of its path over the newest own
    period of a 400 s run, per ring; 200 s here), the disk's velocity turns once per
    2 pi / (N phidot):
    its contacts passing. The size of that motion falls with the number of contacts (4.7e-7
    m at 48, 6.1e-8 m at 96 after 400 s; 7.1e-7 and 8.6e-8 from vy0 0.1 after 3 000 s), so
    it is the equilibrium's, not a cycle's: self_centring (issue: from vy0 0.1 every run from
    omega_m 1.022 to 1.4 read `slide_cycle` at 48 points and `self_centring` at 96)."""
    rest = {
        48: {"x0": -0.0102599306, "y0": 0.0303457255, "vy0": 0.0, "phidot0": 0.63260758},
        96: {"x0": -0.0102634812, "y0": 0.0303435931, "vy0": 0.0, "phidot0": 0.63259982},
    }
    sizes = {}
    for points in (48, 96):
        res = simulate(scene_from_dict(braked(1.2, 200.0, points, **rest[points])))
        assert res.outcome == "self_centring", res.reason
        rows = res.own_section
        turns = points * rows["spin"][-16:] / (2.0 * math.pi)
        assert abs(turns - 1.0).max() < 0.005  # the ring's ripple (0.0017 measured)
        assert res.r_eq == pytest.approx(0.09473, abs=1e-5)
        sizes[points] = 0.25 * float(
            rows["x_max"][-1] - rows["x_min"][-1] + rows["y_max"][-1] - rows["y_min"][-1]
        )
    assert sizes[96] < sizes[48] / 4.0, sizes  # ~ N^-3: 7.7 x at 200 s, 8.2 x at 3 000 s
