"""The O(N) arrow solver of the Rosenbrock stages against the dense LU: random block-arrow
matrices, the model's Jacobian, the O(1) event helpers, and whole runs."""

from __future__ import annotations

import numpy as np
import pytest

from frictiondisk.kernel import linalg, model, rosenbrock
from frictiondisk.kernel.model import SLIDE, STICK
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.pack import initial_state, pack_parameters
from frictiondisk.simulation.simulate import simulate

EPS = np.finfo(float).eps


def _to_dense(arrow, r):
    """The n x n matrix an arrow-form array stands for (kernel/linalg.py docstring)."""
    n = arrow.shape[0]
    a = np.zeros((n, n))
    a[:, :r] = arrow[:, :r]
    for z in range(r, n, 2):
        a[z : z + 2, z : z + 2] = arrow[z : z + 2, r : r + 2]
        a[:r, z : z + 2] = arrow[z : z + 2, r + 2 : 2 * r + 2].T
    return a


def _random_arrow(rng, r, ncon, diag):
    """Random arrow-form matrix: normal entries, contact blocks shifted by `diag`."""
    n = r + 2 * ncon
    arrow = rng.standard_normal((n, 2 * r + 2))
    for z in range(r, n, 2):
        arrow[z, r] += diag
        arrow[z + 1, r + 1] += diag
    arrow[:r, r:] = 0.0  # unused columns of the rigid rows
    return arrow


@pytest.mark.parametrize("r", [4, 6])
@pytest.mark.parametrize("ncon", [1, 12, 60])
@pytest.mark.parametrize("diag", [3.0, 1e4])
def test_arrow_solve_equals_dense_lu_to_round_off(r, ncon, diag):
    """The contacts are eliminated without pivoting across blocks, which is backward
    stable when every 2x2 block D_i is well conditioned: in the stage matrix D_i is
    dominated by 1/(gamma h) + c_i/beta_i (kernel/linalg.py). Here D_i = diag I + noise."""
    rng = np.random.default_rng(ncon * 100 + r + int(diag))
    for _ in range(5):
        arrow = _random_arrow(rng, r, ncon, diag)
        dense = _to_dense(arrow, r)
        n = dense.shape[0]
        b = rng.standard_normal(n)
        lu = np.empty_like(arrow)
        piv = np.empty(r, dtype=np.int64)
        assert linalg.arrow_factor(arrow, lu, piv)
        x = np.empty(n)
        linalg.arrow_solve(lu, piv, b, x)
        dlu, dpiv, xd = dense.copy(), np.empty(n, dtype=np.int64), np.empty(n)
        assert linalg.lu_factor(dlu, dpiv)
        linalg.lu_solve(dlu, dpiv, b, xd)
        # forward error bound of a backward-stable solve: ~ n eps cond(A)
        bound = n * EPS * np.linalg.cond(dense)
        assert np.linalg.norm(x - xd) <= bound * np.linalg.norm(xd)
        # and a small backward error: residual ~ n eps (|A| |x| + |b|)
        scale = np.linalg.norm(dense, 2) * np.linalg.norm(x) + np.linalg.norm(b)
        assert np.linalg.norm(dense @ x - b) <= n * EPS * scale


def test_arrow_factor_reports_a_singular_block():
    rng = np.random.default_rng(3)
    arrow = _random_arrow(rng, 6, 4, 3.0)
    arrow[6 + 4, 6:8] = 0.0  # contact 2's diagonal block loses a row
    arrow[6 + 4, 0:6] = 0.0
    assert not linalg.arrow_factor(arrow, np.empty_like(arrow), np.empty(6, dtype=np.int64))


SCENES = {
    "pin": {"scene": "pin"},
    "disk ring": {"scene": "disk", "params": {"beta_b": 0.01}, "contact": {"points": 5}},
    "disk annulus stribeck": {
        "scene": "disk",
        "params": {"beta_b": 0.01},
        "contact": {
            "layout": "annulus",
            "inner_radius": 0.02,
            "outer_radius": 0.08,
            "points": 9,
            "stribeck": {"r": 0.4, "v_s": 0.05, "delta": 1.5},
        },
    },
}


def _random_case(name, rng):
    cfg = scene_from_dict(SCENES[name])
    p, pts = pack_parameters(cfg)
    y = initial_state(cfg) + rng.normal(scale=0.05, size=initial_state(cfg).size)
    modes = rng.integers(0, 2, pts.shape[0]).astype(np.int8)
    nq = 3 if cfg.scene == "disk" else 2
    return p, pts, y, modes, nq


@pytest.mark.parametrize("name", SCENES)
def test_arrow_jacobian_is_the_dense_jacobian(name):
    rng = np.random.default_rng(11)
    for _ in range(5):
        p, pts, y, modes, nq = _random_case(name, rng)
        n = y.size
        dense = np.empty((n, n))
        model.jacobian(p, pts, modes, y, dense, np.empty((4, n)))
        jac, _, piv = linalg.stage_workspace(n, nq, False)
        jac[:] = np.nan  # every entry the solver reads must be written
        model.jacobian_arrow(p, pts, modes, y, jac, np.empty((4, n)))
        r = 2 * nq
        assert piv.shape == (r,)
        jac[:r, r:] = 0.0  # unused
        np.testing.assert_allclose(_to_dense(jac, r), dense, rtol=4 * EPS, atol=0.0)


@pytest.mark.parametrize("name", SCENES)
def test_o1_stick_rate_and_contact_dense_output_match_the_full_ones(name):
    rng = np.random.default_rng(5)
    for _ in range(5):
        p, pts, y, modes, nq = _random_case(name, rng)
        n = y.size
        f, buf, full = np.empty(n), np.empty(n), np.empty(n)
        model.rhs(p, pts, modes, y, f)
        for i in range(pts.shape[0]):
            fast = model.stick_rate_given(p, pts, modes, y, f, i, buf)
            slow = model.stick_rate(p, pts, modes, y, i, full)
            assert fast == pytest.approx(slow, rel=1e-12, abs=1e-12 * np.abs(f).max())
        wk = rng.standard_normal((rosenbrock.N_WORK_ROWS, n))
        y1 = y + 0.01 * rng.standard_normal(n)
        rosenbrock.dense_eval(y, y1, wk, 0.3, full)
        for i in range(pts.shape[0]):
            part = np.full(n, np.nan)
            rosenbrock.dense_eval_contact(y, y1, wk, 0.3, part, nq, i)
            used = np.r_[0 : 2 * nq, 2 * nq + 2 * i, 2 * nq + 2 * i + 1]
            assert np.array_equal(part[used], full[used])
            for mode in (STICK, SLIDE):
                assert model.switch_value(p, pts, part, i, mode) == model.switch_value(
                    p, pts, full, i, mode
                )


RUNS = {
    "pin": {"scene": "pin", "params": {"mu": 0.13}},
    "disk N=12": {"scene": "disk", "params": {"beta_b": 0.005, "phidot0": 1.1, "mu": 0.2}},
    "disk N=48": {
        "scene": "disk",
        "params": {"beta_b": 0.005, "phidot0": 1.1, "mu": 0.2},
        "contact": {"points": 48},
        "numerics": {"t_decide": 10.0},
    },
}


@pytest.mark.parametrize("name", RUNS)
def test_whole_runs_agree_between_the_arrow_and_the_dense_solver(name):
    config = scene_from_dict(RUNS[name])
    arrow = simulate(config)
    dense = simulate(config, dense_lu=True)
    assert arrow.n_transitions > 0
    assert (arrow.outcome, arrow.n_transitions) == (dense.outcome, dense.n_transitions)
    # the two differ by round-off per step; the located times and radii may move by
    # at most what the requested accuracy allows
    rtol = config.numerics.rtol
    assert abs(arrow.R1 - dense.R1) <= rtol * dense.R1
    assert abs(arrow.t_end - dense.t_end) <= rtol * dense.t_end
