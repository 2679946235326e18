"""Physics oracles for the simulation kernel (docs/model.md sections 3 and 6).

Every check here is a law the model must obey (admissibility of a sticking circle,
homogeneity, the Coulomb limit, pin/disk equivalence, objectivity of the contact rate),
not a stored number.
"""

import math

import numpy as np
import pytest
from conftest import g_factor

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate

OMEGA = 1.1
REV = 2 * math.pi / OMEGA
# g = sqrt((c_s - m_s omega^2)^2 + (beta_s omega)^2) with the default parameters
G = g_factor(omega_m=OMEGA)


def pin(**params):
    return scene_from_dict({"scene": "pin", "params": params})


def admissibility_margin(mu, radius, x_ms=0.1):
    """mu F_n - (c_s x_ms + g R) [N]: >= 0 iff a Coulomb sticking circle of radius R holds."""
    return mu * 1.0 - (1.0 * x_ms + G * radius)


def test_pin_sticks_at_high_mu_with_an_admissible_circle():
    for mu in (0.14, 0.13):
        res = simulate(pin(mu=mu))
        assert res.outcome == "stick", res.reason
        # The final sticking circle satisfies mu F_n >= c_s x_ms + g R (docs/model.md section 6);
        # with c = 2.53e5 N/m the regularized circle deviates from Coulomb by ~|Z|/c ~ 1e-6 m.
        assert admissibility_margin(mu, res.size) >= -G * 1e-6
        assert abs(res.size - res.R1) < 1e-6  # it stays on its first sticking circle


def test_pin_reaches_outer_stick_slip_cycle_at_low_mu():
    cfg = pin(mu=0.11).with_overrides({"numerics.mode": "converge"})
    res = simulate(cfg)
    assert res.outcome == "stick_slip", res.reason
    assert res.cycle_converged
    # The cycle's sticking segment lies outside every admissible sticking circle: that is
    # why it slips again; and it lies outside the first sticking circle (outer cycle).
    assert admissibility_margin(0.11, res.size) < 0
    assert res.size > res.R1
    assert res.a > 0


def test_homogeneity_scales_orbit_and_R1():
    """x_ms, x0, the contact layout and mu scaled by lambda scale the orbit by lambda.

    eps is a velocity threshold and scales with lambda too, which makes the scaling exact.
    """
    lam = 2.0
    for scene in ("pin", "disk"):
        base = {"mu": 0.12, "x_ms": 0.1, "x0": 0.02, "phidot0": OMEGA}
        scaled = {"mu": 0.12 * lam, "x_ms": 0.1 * lam, "x0": 0.02 * lam, "phidot0": OMEGA}
        contact = {"eps": 1e-9} if scene == "pin" else {"eps": 1e-9, "ring_radius": 0.05}
        contact_s = {k: v * lam for k, v in contact.items()}
        numerics = {"t_decide": 20.0, "rtol": 1e-9, "atol": 1e-12}
        numerics_s = {"t_decide": 20.0, "rtol": 1e-9, "atol": 1e-12 * lam}
        if scene == "pin":
            base.pop("phidot0")
            scaled.pop("phidot0")
        a = simulate(
            scene_from_dict(
                {"scene": scene, "params": base, "contact": contact, "numerics": numerics}
            ),
            record=True,
            dt_out=0.05,
        )
        b = simulate(
            scene_from_dict(
                {"scene": scene, "params": scaled, "contact": contact_s, "numerics": numerics_s}
            ),
            record=True,
            dt_out=0.05,
        )
        assert a.outcome == b.outcome
        assert b.R1 == pytest.approx(lam * a.R1, rel=1e-6)
        assert b.t_R1 == pytest.approx(a.t_R1, abs=1e-6)
        ta, tb = a.trajectory, b.trajectory
        n = min(len(ta.t), len(tb.t), 200)
        np.testing.assert_allclose(tb.t[:n], ta.t[:n], atol=1e-6)
        np.testing.assert_allclose(tb.x[:n], lam * ta.x[:n], atol=1e-6 * lam)
        np.testing.assert_allclose(tb.y[:n], lam * ta.y[:n], atol=1e-6 * lam)


def test_coulomb_limit_R1_converges_with_contact_stiffness():
    """R1 converges as c grows (critical damping kept): successive changes shrink."""
    radii = []
    for mult in (1, 10, 100):
        cfg = pin(mu=0.14).with_overrides(
            {"contact.stiffness": 2.53e5 * mult, "numerics.rtol": 1e-9, "numerics.atol": 1e-12}
        )
        res = simulate(cfg)
        assert res.outcome == "stick"
        radii.append(res.R1)
    d1 = abs(radii[1] - radii[0])
    d2 = abs(radii[2] - radii[1])
    assert d2 < d1 / 3  # at least first-order convergence in 1/c (observed ~ 10x)
    assert admissibility_margin(0.14, radii[-1]) > 0


@pytest.mark.parametrize("mu", [0.14, 0.12])
def test_disk_without_brake_co_rotating_moves_like_the_pin(mu):
    p = simulate(pin(mu=mu))
    d = simulate(
        scene_from_dict({"scene": "disk", "params": {"mu": mu, "phidot0": OMEGA, "beta_b": 0.0}})
    )
    assert d.outcome == p.outcome
    assert d.R1 == pytest.approx(p.R1, abs=1e-6)
    assert d.t_R1 == pytest.approx(p.t_R1, abs=1e-6)


def _regular_samples(tr, dt_out):
    """Indices of the samples at multiples of dt_out (drops the extra rows at switches)."""
    k = np.round(tr.t / dt_out)
    regular = np.abs(tr.t - k * dt_out) < 1e-9
    _, first = np.unique(k[regular], return_index=True)
    return np.flatnonzero(regular)[first]


def _stuck_run(scene, params, rtol, revolutions):
    per_rev = 50
    dt_out = REV / per_rev
    cfg = scene_from_dict(
        {
            "scene": scene,
            "params": params,
            "numerics": {
                "stop_on_stick": False,
                "t_decide": (3 + revolutions) * REV,
                "rtol": rtol,
                "atol": rtol * 1e-3,
            },
        }
    )
    res = simulate(cfg, record=True, dt_out=dt_out)
    assert res.outcome == "stick", res.reason
    tr = res.trajectory
    idx = _regular_samples(tr, dt_out)
    i0 = np.searchsorted(tr.t[idx], 3 * REV)  # the runs below stick within 3 revolutions

    def rev_rows(n):
        return idx[i0 + per_rev * n : i0 + per_rev * (n + 1)]

    assert tr.all_stick[idx[i0:]].all()
    return tr, rev_rows


def _glued_radius(tr, scene, contact_stiffness):
    """|q - z|: radius of the master's material point the (first) contact is glued to."""
    qx, qy = tr.x.copy(), tr.y.copy()
    if scene == "disk":
        qx += 0.05 * np.cos(tr.phi)
        qy += 0.05 * np.sin(tr.phi)
    return np.hypot(qx - tr.Zx[:, 0] / contact_stiffness, qy - tr.Zy[:, 0] / contact_stiffness)


def test_stuck_pin_keeps_its_circle_over_100_revolutions():
    """With u = v + omega e_z x z the glued master point moves on an exact circle, so the
    pin cannot drift. The missing rotation term would move it by about
    omega |z_tangential| per second, |z_t| = beta_s omega R / c (docs/model.md section 3)."""
    drifts = []
    for rtol in (1e-6, 1e-8):
        tr, rows = _stuck_run("pin", {"mu": 0.14}, rtol, 100)
        glued = _glued_radius(tr, "pin", 2.53e5)
        drifts.append(abs(glued[rows(99)].mean() - glued[rows(0)].mean()))
    radius = 0.1095
    drift_without_term = OMEGA * (0.1 * OMEGA * radius / 2.53e5) * 99 * REV
    assert drifts[0] < 0.01 * drift_without_term
    # what remains is integration error: it falls with the tolerance
    assert drifts[1] < drifts[0] / 30


@pytest.mark.slow  # > 10 s on 2 shared cores (selected out by -m 'not slow')
def test_braked_stuck_disk_has_periodic_contact_forces_without_growing_self_stress():
    """A disk stuck under a brake torque carries it through its contacts; the contact force
    pattern repeats every revolution (it is constant in the rotating frame up to the fixed
    spring preload c_s x_ms) and nothing grows: the change after n revolutions is
    integration error, falling with the tolerance."""
    params = {"mu": 0.5, "beta_b": 0.002, "phidot0": OMEGA}
    growth = []
    for rtol in (1e-6, 1e-8):
        tr, rows = _stuck_run("disk", params, rtol, 30)
        a, b = rows(0), rows(29)
        growth.append(max(np.abs(tr.Zx[b] - tr.Zx[a]).max(), np.abs(tr.Zy[b] - tr.Zy[a]).max()))
        scale = np.abs(tr.Zx[a]).max()
    assert growth[0] < 1e-3 * scale
    assert growth[1] < growth[0] / 30
    # Without the rotation term a brake torque beta_b omega = 2.2e-3 N m would load the
    # contacts by more than that within one revolution.


def test_concentric_stuck_disk_forces_are_constant_in_the_rotating_frame():
    params = {"mu": 0.5, "beta_b": 0.002, "phidot0": OMEGA, "x_ms": 0.0, "x0": 0.1}
    tr, rows = _stuck_run("disk", params, 1e-8, 10)
    rows_all = np.concatenate([rows(n) for n in range(10)])
    phi = tr.phi[rows_all][:, None]
    bx = np.cos(phi) * tr.Zx[rows_all] + np.sin(phi) * tr.Zy[rows_all]
    by = -np.sin(phi) * tr.Zx[rows_all] + np.cos(phi) * tr.Zy[rows_all]
    scale = np.abs(bx).max()
    assert np.ptp(bx, axis=0).max() < 1e-6 * scale
    assert np.ptp(by, axis=0).max() < 1e-6 * scale
    # The contacts carry the brake torque: sum_i a_i x F_i = beta_b omega_m, with
    # F_i = -k_i = -(Z_i + (beta omega / c) e_z x Z_i) in steady co-rotation (v_i = 0).
    w = 2.0 * math.sqrt(2.53e5) * OMEGA / 2.53e5
    theta = tr.phi[rows_all][:, None] + 2 * np.pi * np.arange(12)[None, :] / 12
    ax, ay = 0.05 * np.cos(theta), 0.05 * np.sin(theta)
    zx, zy = tr.Zx[rows_all], tr.Zy[rows_all]
    fx, fy = -(zx - w * zy), -(zy + w * zx)
    torque = (ax * fy - ay * fx).sum(axis=1)
    np.testing.assert_allclose(torque, 0.002 * OMEGA, rtol=1e-4)
