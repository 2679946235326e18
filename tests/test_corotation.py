"""stick_rule corotation: permanent sticking is co-rotation without net slip (issue 9).

Oracles: the Melan shakedown and collapse bounds of frictiondisk/verdict/admissibility.py, which
the classifier never reads, and the pin, for which both stick rules must agree.
"""

import math

import numpy as np
import pytest

from frictiondisk.model.scene import ConfigError, scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict import admissibility as ad

BRAKE = 0.005  # beta_b [N m s/rad]


def braked_disk(mu: float, rule: str = "corotation", **numerics) -> dict:
    """The braked disk of Fig 11 from a co-rotating start (12 points on 0.05 m)."""
    return {
        "scene": "disk",
        "params": {"mu": mu, "beta_b": BRAKE, "phidot0": 1.1},
        "numerics": {"stick_rule": rule, **numerics},
    }


def bounds_at(radius: float) -> ad.Demands:
    """Collapse / shakedown demands on mu F_n (F_n = 1 N) at the run's orbit radius."""
    case = ad.LoadCase(R=radius, beta_b=BRAKE)
    return ad.demands(case, ad.ring_points(12, 0.05), 0.05)


def test_above_shakedown_with_grazing_contacts_is_stick():
    """Above the Melan bound the disk co-rotates while contacts still graze their limit
    every revolution: `corotation` says stick, the old `contacts` rule does not."""
    mu = 0.25
    new = simulate(scene_from_dict(braked_disk(mu)))
    old = simulate(scene_from_dict(braked_disk(mu, "contacts")))
    assert mu > bounds_at(new.R1).shakedown
    assert new.outcome == "stick", new.reason
    tol = 1e-9 * 2 * math.pi / 1.1  # eps T [m]: no slip per revolution
    assert min(new.slip_per_rev, new.slip_limit) <= tol
    assert old.outcome != "stick", old.reason  # a graze breaks "every contact stuck"
    assert old.n_transitions > 0


def test_between_collapse_and_shakedown_is_creep():
    """Between the bounds the disk keeps its small orbit but ratchets at a steady rate."""
    mu = 0.20
    run = simulate(scene_from_dict(braked_disk(mu)))
    bounds = bounds_at(run.R1)
    assert bounds.collapse < mu < bounds.shakedown
    assert run.outcome == "creep", run.reason
    # a steady ratchet: slip and spin drift per revolution well above atol
    assert run.slip_per_rev > 100 * 1e-9
    assert abs(run.spin_drift_per_rev) * 0.05 > 1e-9
    assert run.drift_per_rev < 1e-3 * run.R1  # ... on its small orbit
    assert "ratchets" in run.reason


@pytest.mark.parametrize("seed", range(6))
def test_rules_agree_on_the_pin(seed):
    """For one contact `co-rotation without slip` is `the contact sticks for a revolution`."""
    rng = np.random.default_rng(seed)
    x_ms = float(rng.uniform(0.03, 0.15))
    x0 = float(rng.uniform(-0.04, 0.04))
    g = ad.g_factor(1.1, 1.0, 1.0, 0.1)
    oracle = x_ms + g * (x_ms + x0)  # the order of mu*: sample around it
    mu = float(oracle * rng.uniform(0.7, 1.3))
    outcomes = {}
    for rule in ("corotation", "contacts"):
        scene = {
            "scene": "pin",
            "params": {"mu": mu, "x_ms": x_ms, "x0": x0},
            "numerics": {"stick_rule": rule},
        }
        outcomes[rule] = simulate(scene_from_dict(scene)).outcome
    stick = {rule: outcome == "stick" for rule, outcome in outcomes.items()}
    assert stick["corotation"] == stick["contacts"], (mu, x_ms, x0, outcomes)
    assert outcomes["corotation"] != "creep"  # one contact cannot ratchet on an orbit


def test_measures_reported():
    run = simulate(scene_from_dict({"scene": "pin"}))
    summary = run.summary()
    for key in ("slip_per_rev", "drift_per_rev", "spin_drift_per_rev", "n_revolutions"):
        assert key in summary
    assert run.n_revolutions >= 1
    assert summary["spin_drift_per_rev"] is None  # a pin has no spin
    assert math.isfinite(run.slip_total)


def test_slip_per_revolution_converges_with_rtol():
    """The creeping disk's slip per revolution is a converged quantity, not noise."""
    slips = [
        simulate(scene_from_dict(braked_disk(0.20, rtol=rtol, atol=1e-3 * rtol))).slip_per_rev
        for rtol in (1e-6, 1e-8)
    ]
    assert abs(slips[0] - slips[1]) <= 1e-2 * slips[1]


def test_crosscheck_refuses_corotation_for_the_disk():
    with pytest.raises(ConfigError, match="numerics.stick_rule"):
        scene_from_dict(braked_disk(0.3, method="scipy-radau"))


@pytest.mark.parametrize("mu", [0.21, 0.2146])
def test_the_verdict_does_not_move_with_atol(mu):
    """The slip that counts as none is eps T, a property of the friction law, not of the
    integrator: the braked disk from rest ratchets 1.1e-7 m a revolution at mu = 0.21 and
    1.8e-8 m at 0.2146 (still falling at 235 s), and preset fast (atol 1e-7) must read it
    as atol 1e-12 does. With atol in the threshold it called 0.2146 `stick` at 46 s, and
    Fig 11's mu* at preset fast lay 0.0076 below the default's."""

    def run(numerics):
        scene = {
            "scene": "disk",
            "params": {"mu": mu, "beta_b": BRAKE, "phidot0": 0.0},
            "numerics": {"mode": "decide", "t_decide": 30.0, **numerics},
        }
        return simulate(scene_from_dict(scene))

    loose, tight = run({"preset": "fast"}), run({"rtol": 1e-6, "atol": 1e-12})
    assert tight.outcome != "stick", tight.reason
    assert loose.outcome == tight.outcome, (loose.reason, tight.reason)
