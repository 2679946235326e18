"""The integrator and the event machinery: Jacobian, convergence order, event location,
grazes and work budgets."""

import math

import numpy as np
import pytest
from scipy.linalg import expm

from frictiondisk.kernel import events, model, rodas
from frictiondisk.kernel.model import SLIDE, STICK
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.pack import initial_state, pack_parameters
from frictiondisk.simulation.simulate import simulate


def _random_state(rng, cfg):
    p, pts = pack_parameters(cfg)
    y = initial_state(cfg)
    y += rng.normal(scale=0.05, size=y.shape)
    return p, pts, y


@pytest.mark.parametrize("scene", ["pin", "disk"])
@pytest.mark.parametrize("stribeck", [False, True])
def test_analytic_jacobian_matches_finite_differences(scene, stribeck):
    rng = np.random.default_rng(1)
    contact = {"points": 3} if scene == "disk" else {}
    if stribeck:
        contact["stribeck"] = {"r": 0.4, "v_s": 0.05, "delta": 1.5}
    params = {"beta_b": 0.01} if scene == "disk" else {}  # a pin has no brake (no spin)
    cfg = scene_from_dict({"scene": scene, "contact": contact, "params": params})
    for _ in range(4):
        p, pts, y = _random_state(rng, cfg)
        n = y.size
        for mode in (STICK, SLIDE):
            modes = np.full(pts.shape[0], mode, dtype=np.int8)
            jac = np.empty((n, n))
            model.jacobian(p, pts, modes, y, jac, np.empty((4, n)))
            fd = np.empty((n, n))
            fp, fm = np.empty(n), np.empty(n)
            for j in range(n):
                step = 1e-6 * max(1.0, abs(y[j]))
                yp, ym = y.copy(), y.copy()
                yp[j] += step
                ym[j] -= step
                model.rhs(p, pts, modes, yp, fp)
                model.rhs(p, pts, modes, ym, fm)
                fd[:, j] = (fp - fm) / (2 * step)
            scale = np.abs(fd).max()
            np.testing.assert_allclose(jac, fd, atol=1e-6 * scale, err_msg=f"mode {mode}")


def _linear_stuck_pin():
    """A pin that sticks for all time (huge mu) with a soft contact: a linear system."""
    cfg = scene_from_dict(
        {
            "scene": "pin",
            "params": {"mu": 50.0, "x0": 0.05, "vx0": 0.1},
            "contact": {"stiffness": 100.0},
        }
    )
    p, pts = pack_parameters(cfg)
    y0 = initial_state(cfg)
    modes = np.full(1, STICK, dtype=np.int8)
    return p, pts, y0, modes


def _exact_flow(p, pts, modes, y0, t):
    """Exact y(t) of the affine system y' = A y + b (stick mode is linear): matrix exponential."""
    n = y0.size
    b = np.empty(n)
    model.rhs(p, pts, modes, np.zeros(n), b)
    a = np.empty((n, n))
    model.jacobian(p, pts, modes, y0, a, np.empty((4, y0.size)))
    aug = np.zeros((n + 1, n + 1))
    aug[:n, :n] = a
    aug[:n, n] = b
    return (expm(aug * t) @ np.append(y0, 1.0))[:n]


def test_rodas4_shows_fourth_order_convergence_on_a_smooth_problem():
    p, pts, y0, modes = _linear_stuck_pin()
    n = y0.size
    t_end = 2.0
    exact = _exact_flow(p, pts, modes, y0, t_end)

    def integrate(steps):
        h = t_end / steps
        y, y1, f = y0.copy(), np.empty(n), np.empty(n)
        jac, lu = np.empty((n, n)), np.empty((n, n))
        piv = np.empty(n, dtype=np.int64)
        wk = np.empty((rodas.N_WORK_ROWS, n))
        for _ in range(steps):
            model.rhs(p, pts, modes, y, f)
            assert rodas.rodas_step(p, pts, modes, y, f, h, jac, lu, piv, wk, y1)
            y[:] = y1
        return np.abs(y - exact).max()

    errors = [integrate(s) for s in (20, 40, 80, 160)]
    orders = [math.log2(errors[k] / errors[k + 1]) for k in range(3)]
    assert min(orders) > 3.6, (errors, orders)
    assert max(orders) < 4.6, (errors, orders)


def test_dense_output_has_third_order_accuracy_inside_the_step():
    p, pts, y0, modes = _linear_stuck_pin()
    n = y0.size

    def midpoint_error(h):
        f, y1 = np.empty(n), np.empty(n)
        jac, lu = np.empty((n, n)), np.empty((n, n))
        piv = np.empty(n, dtype=np.int64)
        wk = np.empty((rodas.N_WORK_ROWS, n))
        model.rhs(p, pts, modes, y0, f)
        rodas.rodas_step(p, pts, modes, y0, f, h, jac, lu, piv, wk, y1)
        mid = np.empty(n)
        rodas.dense_eval(y0, y1, wk, 0.37, mid)
        exact = _exact_flow(p, pts, modes, y0, 0.37 * h)
        return np.abs(mid - exact).max()

    e1, e2 = midpoint_error(0.1), midpoint_error(0.05)
    assert math.log2(e1 / e2) > 3.5  # local error O(h^4) of an order-3 interpolant


def test_fixed_step_locates_the_first_stick_strictly_inside_a_step():
    """With dt = 0.01 s the first stick is found between step ends, where the fine adaptive
    solution puts it, far more precisely than the step."""
    ref = simulate(
        scene_from_dict(
            {"scene": "pin", "params": {"mu": 0.13}, "numerics": {"rtol": 1e-10, "atol": 1e-13}}
        )
    )
    dt = 0.01
    res = simulate(
        scene_from_dict(
            {
                "scene": "pin",
                "params": {"mu": 0.13},
                "numerics": {"method": "rodas4-fixed", "dt": dt},
            }
        )
    )
    assert res.outcome == ref.outcome == "stick"
    frac = res.t_R1 / dt - math.floor(res.t_R1 / dt)
    assert 1e-3 < frac < 1 - 1e-3  # not at a step end
    assert abs(res.t_R1 - ref.t_R1) < 1e-4 * dt
    assert abs(res.R1 - ref.R1) < 1e-8


def test_graze_inside_a_step_is_found():
    """A switching function negative at both step ends but positive in between."""
    cfg = scene_from_dict({"scene": "pin", "params": {"mu": 0.13}})
    p, pts = pack_parameters(cfg)
    y0 = initial_state(cfg)
    n = y0.size
    # Stuck pin at rest on the master: k = Z + beta u. Build a dense output whose Z bulges
    # above the friction limit between s ~ 0.4 and s ~ 0.6 and is below it at both ends.
    y0[0], y0[1] = 0.1, 0.0
    y0[2], y0[3] = 0.0, 0.11  # moving with the master point
    y1 = y0.copy()
    wk = np.zeros((rodas.N_WORK_ROWS, n))
    # y(s) = y0 + s (1 - s) (q1 + s q2) when y1 = y0: add a bump to Z_x of height 4 * 0.14
    wk[rodas.W_Q1, 4] = 4 * 0.14
    sigma = 1.0  # stick: event when s crosses 0 upwards
    w0 = sigma * model.switch_value(p, pts, y0, 0, STICK)
    w1 = sigma * model.switch_value(p, pts, y1, 0, STICK)
    assert w0 < 0 and w1 < 0
    # slopes of w with respect to s at the ends, by differences on the dense output
    ybuf, fbuf = np.empty(n), np.empty(n)
    modes = np.full(1, STICK, dtype=np.int8)
    kind = events.KIND_SWITCH

    def w_at(s):
        return events.directed_value(p, pts, modes, y0, y1, wk, s, 0, sigma, kind, ybuf, fbuf)

    d0 = (w_at(1e-7) - w_at(0.0)) / 1e-7
    d1 = (w_at(1.0) - w_at(1 - 1e-7)) / 1e-7
    s_hi = events.find_graze(p, pts, modes, y0, y1, wk, 0, sigma, w0, w1, d0, d1, ybuf, fbuf)
    assert 0.0 < s_hi < 1.0 and w_at(s_hi) >= 0.0
    root = events.brent_root(
        p, pts, modes, y0, y1, wk, 0, sigma, kind, 0.0, w0, s_hi, w_at(s_hi), 1e-13, ybuf, fbuf
    )
    assert 0.0 < root < s_hi
    assert w_at(root) >= 0.0 and w_at(root - 1e-9) < 0.0


def test_work_budget_ends_the_run_undetermined_with_a_reason():
    res = simulate(
        scene_from_dict({"scene": "pin", "params": {"mu": 0.12}, "numerics": {"max_steps": 50}})
    )
    assert res.outcome == "undetermined"
    assert "numerics.max_steps" in res.reason
    assert res.n_steps == 50
    res = simulate(
        scene_from_dict({"scene": "pin", "params": {"mu": 0.12}, "numerics": {"max_events": 3}})
    )
    assert res.outcome == "undetermined"
    assert "numerics.max_events" in res.reason


def test_adaptive_error_falls_with_the_tolerance():
    ref = simulate(
        scene_from_dict(
            {"scene": "pin", "params": {"mu": 0.13}, "numerics": {"rtol": 1e-11, "atol": 1e-14}}
        )
    )
    errs = []
    for rtol in (1e-4, 1e-6, 1e-8):
        cfg = scene_from_dict(
            {
                "scene": "pin",
                "params": {"mu": 0.13},
                "numerics": {"rtol": rtol, "atol": rtol * 1e-3},
            }
        )
        errs.append(abs(simulate(cfg).R1 - ref.R1))
    assert errs[0] > errs[1] > errs[2]


# ---- stopping rules ------------------------------------------------------------------


@pytest.mark.parametrize("rule", ["contacts", "corotation"])
@pytest.mark.parametrize("stop_on_stick", [True, False])
def test_a_sticking_phase_open_at_the_horizon_is_finished_before_deciding(stop_on_stick, rule):
    """The pin sticks for good from t ~ 1.85 s; a 4 s horizon falls inside that phase, so
    the run goes on until it is decided (docs/model.md: never guess): `contacts` after one
    revolution of sticking, `corotation` at the end of the first whole revolution (on the
    grid of revolutions from t = 0) spent stuck."""
    rev = 2 * math.pi / 1.1
    res = simulate(
        scene_from_dict(
            {
                "scene": "pin",
                "params": {"mu": 0.14},
                "numerics": {"t_decide": 4.0, "stop_on_stick": stop_on_stick, "stick_rule": rule},
            }
        )
    )
    assert res.outcome == "stick", res.reason
    if rule == "contacts":
        assert res.t_end == pytest.approx(res.t_R1 + rev, abs=1e-9)
    else:
        decided = (math.floor(res.t_R1 / rev) + 2) * rev
        if stop_on_stick:
            assert res.t_end == pytest.approx(decided, abs=1e-9)
        else:  # the horizon, extended a revolution at a time until decided
            assert res.t_end >= decided - 1e-9


def test_size_and_a_come_only_from_a_converged_cycle():
    decide = simulate(scene_from_dict({"scene": "pin", "params": {"mu": 0.12}}))
    # at the 30 s horizon its section only departs from sticking: not stick, not named
    assert decide.outcome == "slide" and not decide.cycle_converged
    assert "a departure from sticking alone names no motion" in decide.reason
    assert math.isnan(decide.size) and math.isnan(decide.a)
    converge = simulate(
        scene_from_dict({"scene": "pin", "params": {"mu": 0.12}, "numerics": {"mode": "converge"}})
    )
    assert converge.outcome == "stick_slip" and converge.cycle_converged
    assert converge.size > converge.R1 and converge.a > 0
