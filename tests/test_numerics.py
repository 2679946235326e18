"""The integrator and the event machinery: Jacobian, convergence order, event location,
grazes and work budgets."""

import math

import numpy as np
import pytest
from scipy.linalg import expm

from frictiondisk.kernel import coefficients_rodas5 as co5
from frictiondisk.kernel import events, model, rosenbrock, tableaux
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


def _fixed_steps(step, p, pts, modes, y0, t_end, steps, error_row):
    """Integrate with `steps` fixed steps of `step`; the end state and the largest error
    estimate of a step."""
    n = y0.size
    h = t_end / steps
    y, y1, f = y0.copy(), np.empty(n), np.empty(n)
    jac, lu = np.empty((n, n)), np.empty((n, n))
    piv = np.empty(n, dtype=np.int64)
    wk = np.empty((rosenbrock.N_WORK_ROWS, n))
    estimate = 0.0
    for _ in range(steps):
        model.rhs(p, pts, modes, y, f)
        assert step(p, pts, modes, y, f, h, jac, lu, piv, wk, y1)
        estimate = max(estimate, np.abs(wk[error_row]).max())
        y[:] = y1
    return y, estimate


@pytest.mark.parametrize(
    "tableau, order",
    [(tableaux.RODAS4, 4), (tableaux.RODAS5, 5)],
    ids=["rodas4", "rodas5"],
)
def test_rosenbrock_steppers_converge_at_their_order_on_a_smooth_problem(tableau, order):
    step = rosenbrock.make_rosenbrock_step(tableau)
    error_row = rosenbrock.W_K1 + tableau.stages - 1
    p, pts, y0, modes = _linear_stuck_pin()
    t_end = 2.0
    exact = _exact_flow(p, pts, modes, y0, t_end)
    runs = [_fixed_steps(step, p, pts, modes, y0, t_end, s, error_row) for s in (20, 40, 80, 160)]
    errors = [np.abs(y - exact).max() for y, _ in runs]
    orders = [math.log2(errors[k] / errors[k + 1]) for k in range(3)]
    assert order - 0.4 < min(orders) and max(orders) < order + 0.6, (errors, orders)
    # the embedded estimate is a local error of the lower order: it falls as h^order
    estimates = [estimate for _, estimate in runs]
    assert math.log2(estimates[-2] / estimates[-1]) > order - 1.0, estimates


def test_rodas5_tableau_is_the_transformed_alpha_gamma_form_of_di_marzo():
    """The transformed coefficients (A, C) follow from the method's (alpha, beta) form:
    a = alpha Gamma^-1, C = diag(1 / gamma) - Gamma^-1, Gamma = beta - alpha."""
    alpha = np.zeros((8, 8))
    beta = np.diag(np.full(8, 0.19))
    alpha[1, 0] = 0.38
    alpha[2, :2] = [0.1899188971074152, 0.1979321027247381]
    alpha[3, :3] = [0.1110729281178426, 0.5456026683145674, -0.1727037026450261]
    alpha[4, :4] = [0.2329444418850307, 0.025099380960713898, 0.1443314046300300,
                    0.054672473406183418]  # fmt: skip
    alpha[5, :5] = [-0.036201017843430883, 4.208448872731939, -7.549674427720996,
                    -0.2076823626400282, 4.585108935472517]  # fmt: skip
    beta[1, 0] = 0.0076920774666285364
    beta[2, :2] = [-0.058129718999580252, -0.063251113355141360]
    beta[3, :3] = [0.7075715596134048, -0.5980299539145789, 0.5294131505610923]
    beta[4, :4] = [-0.034975026573934865, -0.1928476085817357, 0.089839586125126941,
                   0.027613185520411822]  # fmt: skip
    # stiffly accurate: stage 6's beta row is stage 7's alpha row, and so on
    beta[5, :5] = [7.585261698003052, -15.57426208319938, -8.814406895608121,
                   1.534698996826085, 16.07870828397837]  # fmt: skip
    alpha[6, :6] = list(beta[5, :5]) + [0.19]
    beta[6, :6] = [0.4646018839086969, 0.0, -1.720907508837576, 0.2910480220957973,
                   1.821778861539924, -0.046521258706842056]  # fmt: skip
    alpha[7, :7] = list(beta[6, :6]) + [0.19]
    beta[7, :7] = list(beta[6, :5]) + [-0.026744882930135193, -0.019776375776706864]
    gamma_inv = np.linalg.inv(beta - alpha)
    a = alpha @ gamma_inv
    c = np.diag(1.0 / np.diag(beta - alpha)) - gamma_inv
    for i in range(1, 8):
        for j in range(i):
            if i < 6:
                assert getattr(co5, f"A{i + 1}{j + 1}") == pytest.approx(
                    a[i, j], rel=1e-12, abs=1e-12
                )
            assert getattr(co5, f"C{i + 1}{j + 1}") == pytest.approx(c[i, j], rel=1e-12)
    # stages 7 and 8 are evaluated at stage 6's point plus k6 (and k7): a unit there
    assert a[6, 5] == pytest.approx(1.0) and a[7, 6] == pytest.approx(1.0)
    assert co5.GAMMA == 0.19


@pytest.mark.parametrize(
    "tableau, order", [(tableaux.RODAS4, 3), (tableaux.RODAS5, 4)], ids=["rodas4", "rodas5"]
)
def test_dense_output_has_its_order_inside_the_step(tableau, order):
    step = rosenbrock.make_rosenbrock_step(tableau)
    p, pts, y0, modes = _linear_stuck_pin()
    n = y0.size

    def interior_error(h):
        f, y1 = np.empty(n), np.empty(n)
        jac, lu = np.empty((n, n)), np.empty((n, n))
        piv = np.empty(n, dtype=np.int64)
        wk = np.empty((rosenbrock.N_WORK_ROWS, n))
        model.rhs(p, pts, modes, y0, f)
        step(p, pts, modes, y0, f, h, jac, lu, piv, wk, y1)
        out = np.empty(n)
        error = 0.0
        for s in (0.0, 0.37, 0.81, 1.0):
            rosenbrock.dense_eval(y0, y1, wk, s, out)
            error = max(error, np.abs(out - _exact_flow(p, pts, modes, y0, s * h)).max())
        rosenbrock.dense_eval(y0, y1, wk, 1.0, out)
        assert np.array_equal(out, y1)  # it ends where the step does
        return error

    e1, e2 = interior_error(0.04), interior_error(0.02)
    # local error O(h^(order + 1)) of an order-`order` interpolant
    assert math.log2(e1 / e2) > order + 0.5, (e1, e2)


@pytest.mark.parametrize("mu", [0.09, 0.13, 0.25])
def test_rodas5_and_rodas4_agree_on_verdict_and_measures(mu):
    """Two integrators, each at a strict tolerance: the same verdict and decision time, and
    the same measures (first sticking radius, slip per revolution) to within their
    tolerance."""
    runs = []
    for method in ("rodas4", "rodas5"):
        cfg = scene_from_dict(
            {
                "scene": "pin",
                "params": {"mu": mu},
                "numerics": {"method": method, "rtol": 1e-8, "atol": 1e-11},
            }
        )
        runs.append(simulate(cfg))
    four, five = runs
    assert (four.outcome, four.decided_by) == (five.outcome, five.decided_by)
    assert four.t_end == pytest.approx(five.t_end, abs=1e-6)
    assert four.R1 == pytest.approx(five.R1, rel=1e-6, nan_ok=True)
    assert four.slip_per_rev == pytest.approx(five.slip_per_rev, rel=1e-6, nan_ok=True)
    assert five.n_steps < four.n_steps  # the higher order needs fewer steps here


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
    wk = np.zeros((rosenbrock.N_WORK_ROWS, n))
    # y(s) = y0 + s (1 - s) (q1 + s q2) when y1 = y0: add a bump to Z_x of height 4 * 0.14
    wk[rosenbrock.W_Q1, 4] = 4 * 0.14
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
    # at the 30 s horizon sticking and sliding alternate, departing from sticking: what the
    # run has shown is its name, and it has not converged
    assert decide.outcome == "stick_slip" and not decide.cycle_converged
    assert "sticking and sliding alternate in the final window" in decide.reason
    assert math.isnan(decide.size) and math.isnan(decide.a)
    converge = simulate(
        scene_from_dict({"scene": "pin", "params": {"mu": 0.12}, "numerics": {"mode": "converge"}})
    )
    assert converge.outcome == "stick_slip" and converge.cycle_converged
    assert converge.size > converge.R1 and converge.a > 0
