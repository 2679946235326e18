"""The kernel and the bisection at extreme parameters (issue 5, item 4).

Each case either ends with a physically sensible outcome that is asserted, or ends
`undetermined` with a reason within its work budget. Never a hang (every run has a step
and event budget), never NaN in a decided result, never a silent misclassification.
"""

import math

import pytest
from conftest import coulomb_mu_star, g_factor

from frictiondisk.engine.worker import run_bisection
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.tasks.jump_search.bisection import Bisection
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.verdict.outcomes import OUTCOMES, is_not_stick

G = g_factor()  # default pin [N/m]
BUDGET = {"max_steps": 2_000_000, "max_events": 200_000}


def run(spec):
    spec = {**spec, "numerics": {**BUDGET, **spec.get("numerics", {})}}
    res = simulate(scene_from_dict(spec))
    assert res.outcome in OUTCOMES
    assert res.reason
    if res.outcome != "undetermined":
        for name in ("t_end", "stick_fraction"):
            assert math.isfinite(getattr(res, name)), name
    if res.outcome == "stick":
        assert math.isfinite(res.R1) and math.isfinite(res.size)
    return res


def test_very_stiff_contact_tends_to_coulomb():
    stiff = run({"scene": "pin", "contact": {"stiffness": 2.53e9}})
    ref = run({"scene": "pin", "contact": {"stiffness": 2.53e7}})
    assert stiff.outcome == ref.outcome == "stick"
    assert abs(stiff.R1 - ref.R1) < 1e-6


def test_very_soft_contact_still_decides():
    res = run({"scene": "pin", "contact": {"stiffness": 2.53e3}})
    assert res.outcome == "stick"
    # a soft contact deflects by |Z|/c ~ 5e-5 m: the circle moves by about that much
    assert abs(res.R1 - run({"scene": "pin"}).R1) < 1e-4


@pytest.mark.parametrize("eps", [1e-15, 1e-3])
def test_extreme_stick_thresholds(eps):
    res = run({"scene": "pin", "contact": {"eps": eps}})
    ref = run({"scene": "pin"})
    assert res.outcome == ref.outcome == "stick"
    # eps only moves the switching surface by beta eps: <= 1 N s/m x 1e-3 m/s ~ 1e-3 N
    assert abs(res.R1 - ref.R1) < 1e-4


def test_vanishing_friction_slides():
    res = run({"scene": "pin", "params": {"mu": 1e-6}})
    assert res.outcome == "slide"
    assert math.isnan(res.R1) and res.n_transitions == 0


def test_huge_friction_sticks_at_the_first_instant_at_the_start_radius():
    res = run({"scene": "pin", "params": {"mu": 50.0, "x0": 0.02}})
    assert res.outcome == "stick"
    assert res.t_R1 < 0.05  # the contact force builds up in ~ beta/c seconds
    assert res.R1 == pytest.approx(0.12, abs=1e-6)  # |r(0)| = x_ms + x0


def test_concentric_axes_stick_on_the_admissible_circle():
    res = run({"scene": "pin", "params": {"x_ms": 0.0, "x0": 0.05}})
    assert res.outcome == "stick"
    assert 0.13 >= G * res.size  # mu F_n >= c_s x_ms + g R with x_ms = 0


@pytest.mark.parametrize("x0", [0.05, 0.3])
def test_master_at_rest(x0):
    """omega_m = 0: static friction holds the slave if the spring force c_s x0 is below
    mu F_n; otherwise it slides back and stops inside the band |r - r0| <= mu F_n / c_s."""
    res = run({"scene": "pin", "params": {"omega_m": 0.0, "x0": x0}})
    assert res.outcome == "stick"
    band = 0.13 * 1.0 / 1.0
    if x0 < band:
        assert res.size == pytest.approx(0.1 + x0, abs=1e-6)
    else:
        assert abs(res.size - 0.1) <= band + 1e-6


def test_nearly_massless_disk_rotation_moves_like_the_pin():
    res = run({"scene": "disk", "params": {"J_s": 1e-6}})
    assert res.outcome == "stick"
    assert abs(res.R1 - run({"scene": "pin"}).R1) < 1e-6


def test_heavy_disk_and_strong_brake_cannot_co_rotate():
    """Friction torque <= mu F_n rho = 6.5e-3 N m cannot spin up J_s = 1e3 kg m^2 within the
    horizon, nor hold a brake torque beta_b omega_m = 11 N m."""
    for params in ({"J_s": 1e3}, {"beta_b": 10.0}):
        res = run({"scene": "disk", "params": params})
        assert res.outcome == "slide", params


def test_one_and_ninety_six_contact_points():
    # one contact: the disk tumbles irregularly (no cycle its section could show), so it
    # ends on evidence or undetermined for want of it, never in an integrator failure
    res = run({"scene": "disk", "contact": {"points": 1}})
    assert res.outcome in ("stick", "stick_slip") or (
        res.outcome == "undetermined" and "without evidence" in res.reason
    ), res.reason
    many = run({"scene": "disk", "contact": {"points": 96}, "params": {"phidot0": 1.1}})
    assert many.outcome == "stick"
    assert abs(many.R1 - run({"scene": "pin"}).R1) < 1e-6


def test_long_horizon_finishes_within_budget():
    res = run({"scene": "pin", "params": {"mu": 0.12}, "numerics": {"t_decide": 1e4}})
    assert res.outcome == "stick_slip"
    # extended past the horizon only while the cycle's beat looks like a trend to stick
    assert 1e4 <= res.t_end <= 1e4 + 10 * 2 * math.pi / 1.1
    assert res.n_steps < BUDGET["max_steps"]


def test_exhausted_budget_is_undetermined_not_guessed():
    res = run(
        {"scene": "pin", "params": {"mu": 0.12}, "numerics": {"t_decide": 1e4, "max_steps": 5000}}
    )
    assert res.outcome == "undetermined"
    assert "max_steps" in res.reason


def test_steep_stribeck_curve_is_classified():
    res = run({"scene": "pin", "contact": {"stribeck": {"r": 0.3, "v_s": 1e-4}}})
    assert res.outcome != "undetermined"
    # with kinetic friction 0.3 mu the slave never comes to relative rest here: it slides
    # (to its sliding rest point: self_centring, docs/model.md section 6)
    assert is_not_stick(res.outcome) and math.isnan(res.R1)


def bisect(contact):
    base = scene_from_dict({"scene": "pin", "contact": contact})
    bis = Bisection((0.05, 0.3), BisectionSettings(1e-4, (1e-6, 10.0), 2))
    bis, _ = run_bisection(bis, base.canonical(), 2.0, campaign_dir="/nonexistent")
    res = bis.result()
    assert res.status == "converged"
    return res


@pytest.mark.parametrize(
    "contact",
    [{"stiffness": 2.53e9}, {"eps": 1e-12}, {"eps": 1e-3}],
    ids=["c=2.53e9", "eps=1e-12", "eps=1e-3"],
)
def test_located_jump_meets_the_coulomb_oracle(contact):
    """The stick limit is exactly F_St (eps only ends sliding), so neither a near-rigid
    contact (beta eps ~ 1e-4 N) nor a large eps (beta eps ~ 1 N) moves mu*."""
    res = bisect(contact)
    oracle = coulomb_mu_star(res.end_result("hi")["R1"])
    assert res.mu_lo - 2e-5 < oracle <= res.mu_hi + 2e-5
