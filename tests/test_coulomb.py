"""The exact Coulomb pin (frictiondisk/simulation/coulomb.py): the c -> infinity limit of the
regularized model, and the located jump against the sticking-circle oracle."""

import pytest
from conftest import coulomb_mu_star, g_factor

from frictiondisk.engine.tasks import run_bisection
from frictiondisk.model.scene import ConfigError, scene_from_dict
from frictiondisk.search.bisection import Bisection
from frictiondisk.simulation.simulate import simulate

G = g_factor()  # default pin [N/m]


def pin(mu, **numerics):
    return scene_from_dict({"scene": "pin", "params": {"mu": mu}, "numerics": numerics})


def bisect(base):
    bis = Bisection((0.05, 0.3), 1e-4, (1e-6, 10.0), 2)
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
