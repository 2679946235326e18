"""Admissibility of permanent co-rotation (frictiondisk/verdict/admissibility.py).

Checks: the pin reduction to docs/model.md's oracle; the ordering and limits of the four demands;
the rigid-plastic capacity against its static certificate and a brute-force search; and a
simulated stuck braked disk, whose contact forces must add up to the required force and
torque and can never beat the best redistribution.
"""

import math

import numpy as np
import pytest
from conftest import g_factor

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.numpy_model import NumpyModel
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict import admissibility as ad

OMEGA = 1.1
REV = 2 * math.pi / OMEGA
G = g_factor(omega_m=OMEGA)
RING = ad.ring_points(12, 0.05)


def test_pin_reduces_to_the_model_oracle():
    pin = np.zeros((1, 2))
    for radius, x_ms in ((0.11, 0.1), (0.05, 0.2), (0.3, 0.0)):
        case = ad.LoadCase(R=radius, x_ms=x_ms)
        oracle = 1.0 * x_ms + G * radius
        d = ad.demands(case, pin, rho=0.0)
        for value in (d.collapse, d.shakedown, d.elastic, d.additive):
            assert value == pytest.approx(oracle, rel=1e-9)
        assert case.force_range()[1] == pytest.approx(oracle, rel=1e-12)
        theta = np.linspace(0, 2 * np.pi, 721)
        assert np.linalg.norm(case.force(theta), axis=1).max() == pytest.approx(oracle, rel=1e-5)


def test_required_force_balances_the_circular_motion():
    """F = m r'' - F_s on r = R e(theta), r' = omega e_z x r, r'' = -omega^2 r."""
    case = ad.LoadCase(R=0.1, x_ms=0.1, beta_b=0.003)
    theta = 0.7
    r = 0.1 * np.array([math.cos(theta), math.sin(theta)])
    v = OMEGA * np.array([-r[1], r[0]])
    spring = -1.0 * (r - np.array([0.1, 0.0])) - 0.1 * v
    np.testing.assert_allclose(case.force(theta), -(OMEGA**2) * r - spring, atol=1e-15)
    assert case.torque == pytest.approx(0.003 * OMEGA)


def test_unbraked_ring_needs_exactly_the_pin_value():
    case = ad.LoadCase(R=0.11)
    d = ad.demands(case, RING, rho=0.05)
    oracle = 0.1 + G * 0.11
    for value in (d.collapse, d.shakedown, d.elastic, d.additive):
        assert value == pytest.approx(oracle, rel=1e-6)


@pytest.mark.parametrize("beta_b", [0.001, 0.005, 0.02])
def test_braked_demands_are_ordered_and_differ(beta_b):
    d = ad.demands(ad.LoadCase(R=0.1, beta_b=beta_b), RING, rho=0.05)
    assert d.collapse < d.shakedown < d.elastic <= d.additive + 1e-12
    # 12 points: the worst point of the elastic sharing is the continuous-ring value
    assert d.elastic == pytest.approx(d.additive, rel=1e-9)
    # redistribution buys something real: more than 2 % of the demand
    assert d.shakedown < 0.98 * d.elastic


def test_pure_torque_and_pure_force_capacities_of_a_ring():
    assert ad.limit_capacity([0.0, 0.0], 0.002, RING) == pytest.approx(0.002 / 0.05, rel=1e-6)
    assert ad.limit_capacity([0.3, -0.4], 0.0, RING) == pytest.approx(0.5, rel=1e-6)


@pytest.mark.parametrize(
    "force,torque", [([1.0, 0.0], 0.05), ([0.1, 0.2], 0.004), ([0.0, 0.3], 0.1)]
)
def test_limit_capacity_has_a_static_certificate_and_beats_brute_force(force, torque):
    lam, f = ad.limit_pattern(force, torque, RING)
    # the optimal pattern carries the load (to the solver's tolerance) with no point
    # above lam / N (static side: lam is enough)
    np.testing.assert_allclose(f.sum(axis=0), force, atol=1e-5 * lam)
    moment = (RING[:, 0] * f[:, 1] - RING[:, 1] * f[:, 0]).sum()
    assert moment == pytest.approx(torque, abs=1e-5 * lam * 0.05)
    assert 12 * np.linalg.norm(f, axis=1).max() == pytest.approx(lam, rel=1e-5)
    # kinematic side: no rigid slip motion (instantaneous centre p) demands more
    best = np.linalg.norm(force)
    grid = np.linspace(-0.3, 0.3, 121)
    for px in grid:
        for py in grid:
            p = np.array([px, py])
            num = torque - (force[0] * (-py) + force[1] * px)
            best = max(best, 12 * abs(num) / np.linalg.norm(RING - p, axis=1).sum())
    assert best <= lam * (1 + 1e-9)
    assert best >= lam * (1 - 2e-3)  # the grid gets close to the optimum
    # and the elastic sharing is never better than the optimum
    elastic = ad.elastic_pattern(np.asarray(force), torque, RING)
    assert 12 * np.linalg.norm(elastic, axis=1).max() >= lam * (1 - 1e-9)


def _static_limit(force, torque, pts, weights, sides=256):
    """min over patterns carrying (force, torque) of N max_i |f_i| / W_i by a linear
    programme: each |f_i| <= t W_i / N on a circumscribed polygon of `sides` sides, so a
    lower bound within 1 / cos(pi / sides) of the true value (scipy's HiGHS, independent of
    the kernel's IRLS)."""
    from scipy.optimize import linprog

    n = pts.shape[0]
    ang = 2 * np.pi * np.arange(sides) / sides
    # unknowns: f_1x, f_1y, ..., f_nx, f_ny, t (t = the demand N max |f_i| / W_i)
    rows, rhs = [], []
    for i in range(n):
        for a in ang:
            row = np.zeros(2 * n + 1)
            row[2 * i : 2 * i + 2] = math.cos(a), math.sin(a)
            row[-1] = -weights[i] / n
            rows.append(row)
            rhs.append(0.0)
    eq = np.zeros((3, 2 * n + 1))
    eq[0, 0 : 2 * n : 2] = 1.0
    eq[1, 1 : 2 * n : 2] = 1.0
    eq[2, 0 : 2 * n : 2] = -pts[:, 1]
    eq[2, 1 : 2 * n : 2] = pts[:, 0]
    cost = np.zeros(2 * n + 1)
    cost[-1] = 1.0
    found = linprog(
        cost,
        A_ub=np.array(rows),
        b_ub=rhs,
        A_eq=eq,
        b_eq=[force[0], force[1], torque],
        bounds=[(None, None)] * (2 * n) + [(0, None)],
        method="highs",
    )
    assert found.status == 0, found.message
    return found.fun


@pytest.mark.parametrize(
    "force,torque", [([1.0, 0.0], 0.05), ([0.1, 0.2], 0.004), ([0.0, 0.3], 0.1)]
)
def test_weighted_limit_matches_a_static_linear_programme(force, torque):
    """Points of unequal weight W_i (mean 1), each with its share of mu F_n: an annulus's
    points, weighted 1 : 3 in turn (an annulus's own weights differ by a few per cent). The
    kernel's weighted Lambda (verdict/limit_analysis.py, as the shakedown bound reads it on
    the run) equals the static optimum of a linear programme to the polygon's resolution,
    and weights 1 give the unweighted value bit for bit."""
    from frictiondisk.model import layouts
    from frictiondisk.verdict.limit_analysis import limit_motion

    positions, _ = layouts.annulus(16, 0.03, 0.08)
    weights = layouts.relative_weights(np.tile([1.0, 3.0], 8))
    pts = np.column_stack((positions, weights))
    value = limit_motion(force[0], force[1], torque, pts)[3]
    lam = 16 / value
    static = _static_limit(force, torque, positions, weights)
    assert static <= lam * (1 + 1e-6)
    assert static >= lam * math.cos(math.pi / 256) * (1 - 1e-6)
    # the weights change the answer by more than the programme resolves: it tells them apart
    equal = 16 / limit_motion(force[0], force[1], torque, positions)[3]
    assert abs(equal - lam) > 2 * (1 - math.cos(math.pi / 256)) * lam
    ones = np.column_stack((positions, np.ones(16)))
    assert 16 / limit_motion(force[0], force[1], torque, ones)[3] == equal


def test_stuck_braked_disk_carries_the_required_load():
    """A simulated stuck disk: sum F_i and sum a_i x F_i equal the required force and torque
    (steady co-rotation, up to the contact transient), its worst point is within the
    limit, and no instant beats the rigid-plastic optimum."""
    mu, beta_b = 0.5, 0.004
    dt = REV / 40
    cfg = scene_from_dict(
        {
            "scene": "disk",
            "params": {"mu": mu, "beta_b": beta_b, "phidot0": OMEGA},
            "numerics": {"stop_on_stick": False, "t_decide": 4 * REV, "rtol": 1e-8, "atol": 1e-11},
        }
    )
    res = simulate(cfg, record=True, dt_out=dt)
    assert res.outcome == "stick", res.reason
    tr = res.trajectory
    rows = np.flatnonzero((tr.t > 2 * REV) & tr.all_stick)
    model = NumpyModel.from_config(cfg)
    radius = math.hypot(tr.x[rows[0]], tr.y[rows[0]])
    case = ad.LoadCase(R=radius, x_ms=0.1, beta_b=beta_b)
    worst = 0.0
    for j in rows[::4]:
        y = np.concatenate(
            (
                [tr.x[j], tr.y[j], tr.phi[j], tr.vx[j], tr.vy[j], tr.phidot[j]],
                np.column_stack((tr.Zx[j], tr.Zy[j])).ravel(),
            )
        )
        ax, ay, *_, kx, ky, _, _, _ = model.contacts(y[:, None])
        fx, fy = -kx[:, 0], -ky[:, 0]  # contact forces on the slave (stick: F = -k)
        theta = math.atan2(tr.y[j], tr.x[j])
        np.testing.assert_allclose([fx.sum(), fy.sum()], case.force(theta), atol=2e-6)
        torque = (ax[:, 0] * fy - ay[:, 0] * fx).sum()
        assert torque == pytest.approx(case.torque, rel=1e-5)
        per_point = np.hypot(fx, fy).max()
        assert per_point <= mu / 12 * (1 + 1e-9)
        a = np.column_stack((ax[:, 0], ay[:, 0]))
        lam = ad.limit_capacity(np.array([fx.sum(), fy.sum()]), torque, a)
        assert 12 * per_point >= lam * (1 - 1e-6)
        worst = max(worst, 12 * per_point)
    # on the circle of this run the elastic (additive) demand is what the pattern needs
    assert worst <= mu
    # the circle is exact up to the elastic displacement under the turning preload,
    # |d| = |F| / c: its radius breathes by at most 2 c_s x_ms / c = 7.9e-7 m
    assert np.ptp(np.hypot(tr.x[rows], tr.y[rows])) < 1.05 * 2 * 0.1 / 2.53e5
