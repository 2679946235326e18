"""The exact Coulomb pin (frictiondisk/simulation/coulomb.py): the c -> infinity limit of the
regularized model, and the located jump against the sticking-circle oracle."""

import pytest
from conftest import coulomb_mu_star, g_factor

from frictiondisk.engine.worker import run_bisection
from frictiondisk.model.scene import ConfigError, scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.tasks.jump_search.bisection import Bisection
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings

G = g_factor()  # default pin [N/m]


def pin(mu, **numerics):
    return scene_from_dict({"scene": "pin", "params": {"mu": mu}, "numerics": numerics})


def bisect(base):
    bis = Bisection((0.05, 0.3), BisectionSettings(1e-4, (1e-6, 10.0), 2))
    bis, _ = run_bisection(bis, base.canonical(), 2.0, campaign_dir="/nonexistent")
    res = bis.result()
    assert res.status == "converged", res.reason
    return res


def test_outcomes_and_the_exact_sticking_circle():
    stick = simulate(pin(0.14, method="coulomb"))
    assert stick.outcome == "stick"
    assert 0.14 >= 0.1 + G * stick.size  # admissibility, exactly (no regularization)
    assert simulate(pin(0.11, method="coulomb")).outcome == "stick_slip"
    assert simulate(pin(1e-6, method="coulomb")).outcome == "slide"


def test_regularized_R1_converges_to_the_coulomb_R1_as_the_contact_stiffens():
    exact = simulate(pin(0.14, method="coulomb")).R1
    errors = []
    for stiffness in (2.53e5, 2.53e6, 2.53e7):
        cfg = pin(0.14, rtol=1e-10, atol=1e-13).with_overrides({"contact.stiffness": stiffness})
        errors.append(abs(simulate(cfg).R1 - exact))
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 1e-9


@pytest.mark.slow  # > 10 s on 2 shared cores (selected out by -m 'not slow')
def test_coulomb_jump_meets_the_oracle_and_the_regularized_bracket():
    coulomb = bisect(pin(0.13, method="coulomb", t_decide=20.0))
    oracle = coulomb_mu_star(coulomb.end_result("hi")["R1"])
    assert coulomb.mu_lo < oracle <= coulomb.mu_hi
    regularized = bisect(pin(0.13, t_decide=20.0))
    # the two jumps agree within the regularized bracket
    assert regularized.mu_lo <= coulomb.mu_star <= regularized.mu_hi


def test_coulomb_is_for_the_pin_only():
    with pytest.raises(ConfigError) as err:
        scene_from_dict({"scene": "disk", "numerics": {"method": "coulomb"}})
    assert "numerics.method" in str(err.value)


def rim_pin(offset, **numerics):
    """Well-posedness study scene 1/48 at mu = c_s |x_ms| / F_n + offset."""
    params = {"x_ms": 0.0551237, "x0": 0.0174313, "m_s": 0.572235, "omega_m": 0.875483}
    base = scene_from_dict({"scene": "pin", "params": params})
    bound = base.params.c_s * abs(base.params.x_ms) / base.params.F_n
    numerics = {"method": "coulomb", "evidence": "observe", **numerics}
    return base.with_overrides(
        {"params.mu": bound + offset, **{f"numerics.{k}": v for k, v in numerics.items()}}
    )


@pytest.mark.slow  # > 10 s on 2 shared cores (selected out by -m 'not slow')
def test_a_pin_creeping_onto_the_rim_of_its_sticking_disc_sticks_in_the_limit():
    config = rim_pin(1.25e-4, t_decide=600.0)
    result = simulate(config)
    assert result.outcome == "stick", result.reason
    assert "in the limit" in result.reason
    p = config.params
    g = g_factor(p.omega_m, p.c_s, p.beta_s, p.m_s)
    # it sticks on the rim: g R* + c_s |x_ms| = mu F_n exactly
    assert g * result.size + p.c_s * abs(p.x_ms) == pytest.approx(p.mu * p.F_n, rel=1e-12)
    assert result.t_end < 600.0


def test_below_its_bound_a_watched_pin_is_shown_not_to_stick():
    result = simulate(rim_pin(-5e-5, t_decide=60.0))
    assert result.outcome in ("slide", "stick_slip")
    assert "it cannot stick" in result.reason


def test_a_watched_stick_slip_cycle_needs_its_onsets_to_repeat():
    # decided stick_slip from its final window (test_outcomes_and_the_exact_sticking_circle),
    # but at 100 s its onsets still move 1e-4 m an onset
    early = simulate(pin(0.11, method="coulomb", evidence="observe", t_decide=100.0))
    assert early.outcome == "undetermined"
    assert "without evidence that it will not stick" in early.reason
