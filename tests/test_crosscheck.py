"""scipy-radau cross-check (frictiondisk/simulation/radau.py) against the numba kernel.

Tolerances are in units of the requested accuracy, as in scipy's test_ivp.py: a length
difference is measured in units of atol + rtol |value|, a time difference in units of
rtol t (both integrators run at rtol = 1e-8, atol = 1e-11).
* R1, t_R1 and the pin's switching instants must agree within 1 unit: each side controls
  its local error to 1 unit, and the first sticking and the pin's switches are simple
  crossings of a smooth switching function. Measured (this machine): R1 2e-4, t_R1 1e-4,
  the switching instants of the mu = 0.11 pin 6e-3 units.
* A re-entry of a disk contact (slide -> stick after a refused entry) is the zero of a
  rate, i.e. an extremum of the switching function s: a value error delta moves it by
  ~ sqrt(delta / |s''|), so it is located to ~ sqrt(rtol) / omega_m (9e-5 s), not to
  rtol t. Measured: 1.5e-5 s.
"""

import math

import numpy as np
import pytest

from frictiondisk.kernel import model as km
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation import radau as crosscheck
from frictiondisk.simulation.pack import pack_parameters
from frictiondisk.simulation.radau import NumpyModel, simulate_radau
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict.horizon import revolution
from frictiondisk.verdict.outcomes import is_stick

RTOL, ATOL = 1e-8, 1e-11
OMEGA_M = 1.1  # [rad/s], the default master
TOL_REENTRY = math.sqrt(RTOL) / OMEGA_M  # [s]


def length_error(a, b):
    """|a - b| in units of atol + rtol |b| (lengths in m)."""
    return np.max(np.abs(np.asarray(a) - np.asarray(b)) / (ATOL + RTOL * np.abs(b)))


def time_error(a, b):
    """|a - b| in units of rtol t (times in s)."""
    return np.max(np.abs(np.asarray(a) - np.asarray(b)) / (RTOL * np.abs(b)))


N_SWITCHES = 6  # switches of the mu = 0.11 pin run in its first 20 s


def numerics(method, **overrides):
    """The compared runs' numerics: same tolerances and largest step on both sides."""
    return {
        "method": method,
        "rtol": RTOL,
        "atol": ATOL,
        "h_max": 0.02,
        "t_decide": 20.0,
        # the cross-check measures no slip per revolution: both sides use the contacts rule
        "stick_rule": "contacts",
        **overrides,
    }


def over_the_same_span(make, record=False):
    """Kernel and scipy-radau on the scene `make(method, **numerics overrides)`. The kernel
    extends its horizon until its verdict has evidence (revolution measures scipy-radau
    does not keep), so scipy-radau is given the span the kernel ran."""
    kernel = simulate(make("rodas4"), record=record)
    radau = simulate(make("scipy-radau", t_decide=kernel.t_end), record=record)
    return kernel, radau


def disk_pair(params, contact=None, record=False):
    """The same disk scene run by the kernel and by scipy-radau."""

    def make(method, **overrides):
        spec = {"scene": "disk", "params": params, "numerics": numerics(method, **overrides)}
        if contact:
            spec["contact"] = contact
        return scene_from_dict(spec)

    return over_the_same_span(make, record)


def pin(mu, method, **overrides):
    num = numerics(method, **overrides)
    return scene_from_dict(
        {"scene": "pin", "params": {"mu": mu, "x_ms": 0.1, "x0": 0.0}, "numerics": num}
    )


def switch_times(trajectory):
    """Times where the recorded mode of some contact changes (first sample in the new mode)."""
    changed = np.any(np.diff(trajectory.mode.astype(int), axis=0) != 0, axis=1)
    return trajectory.t[1:][changed]


# ---- the independent right-hand side ---------------------------------------------------

SCENES = [
    {"scene": "pin"},
    {"scene": "disk", "contact": {"points": 5}},
    {
        "scene": "disk",
        "params": {"beta_b": 0.01, "phidot0": 0.3},
        "contact": {"points": 3, "stribeck": {"r": 0.6, "v_s": 0.01, "delta": 1.5}},
    },
    {"scene": "pin", "contact": {"stribeck": {"r": 0.5, "v_s": 0.02, "delta": 2.0}}},
]


@pytest.mark.parametrize(
    "scene", SCENES, ids=["pin", "disk5", "disk3-stribeck-brake", "pin-stribeck"]
)
def test_numpy_model_matches_kernel(scene):
    """rhs, switching function and its rate agree with kernel/model.py on random states."""
    config = scene_from_dict(scene)
    model = NumpyModel.from_config(config)
    p, pts = pack_parameters(config)
    rng = np.random.default_rng(7)
    n, ncon = model.n_states, model.n_contacts
    mode_sets = [np.full(ncon, km.STICK), np.full(ncon, km.SLIDE)]
    mode_sets += [rng.integers(0, 2, ncon) for _ in range(4)]
    for trial in range(50):
        y = rng.normal(scale=0.1, size=n)
        y[0] += 0.1
        for modes in mode_sets:
            modes = modes.astype(np.int8)
            f_kernel = np.empty(n)
            km.rhs(p, pts, modes, y, f_kernel)
            f_numpy = model.rhs(y, modes)
            scale = np.max(np.abs(f_kernel))
            np.testing.assert_allclose(
                f_numpy, f_kernel, rtol=1e-12, atol=1e-12 * scale, err_msg=f"trial {trial} {modes}"
            )
            s_kernel = np.array([km.switch_value(p, pts, y, i, modes[i]) for i in range(ncon)])
            np.testing.assert_allclose(model.switch(y, modes), s_kernel, rtol=1e-12, atol=1e-15)
            rate_kernel = np.array([km.switch_rate(p, pts, y, f_kernel, i) for i in range(ncon)])
            np.testing.assert_allclose(
                model.switch_rate(y, f_numpy),
                rate_kernel,
                rtol=1e-9,
                atol=1e-12 * np.max(np.abs(rate_kernel)),
            )


def test_numpy_rhs_is_vectorized():
    """Columns of a (n, k) state give the rhs of each column (scipy's vectorized Jacobian)."""
    model = NumpyModel.from_config(scene_from_dict({"scene": "disk", "contact": {"points": 4}}))
    rng = np.random.default_rng(3)
    ys = rng.normal(scale=0.1, size=(model.n_states, 5))
    modes = np.array([1, 0, 1, 0], dtype=np.int8)
    fs = model.rhs(ys, modes)
    for k in range(ys.shape[1]):
        np.testing.assert_array_equal(fs[:, k], model.rhs(ys[:, k], modes))


def test_initial_modes_follow_the_rule():
    """Stick iff |k(0)| < F_St: the pin at rest on a turning master starts sliding."""
    config = scene_from_dict({"scene": "pin"})
    model = NumpyModel.from_config(config)
    from frictiondisk.simulation.pack import initial_modes, initial_state

    y0 = initial_state(config)
    p, pts = pack_parameters(config)
    np.testing.assert_array_equal(model.initial_modes(y0), initial_modes(p, pts, y0))
    assert model.initial_modes(y0)[0] == km.SLIDE


# ---- agreement of the two integrators ---------------------------------------------------


# (mu, the outcome both give): at mu 0.11 sticking and sliding alternate in the final
# window, which both name `stick_slip` (the kernel's section shows a departure from
# sticking; scipy-radau keeps no section)
@pytest.fixture(
    scope="module",
    params=[(0.14, "stick"), (0.11, "stick_slip")],
    ids=["mu0.14", "mu0.11"],
)
def pin_pair(request):
    mu, expected = request.param
    decide = dict(
        zip(
            ("rodas4", "scipy-radau"),
            over_the_same_span(lambda m, **o: pin(mu, m, **o)),
            strict=False,
        )
    )
    recorded = over_the_same_span(lambda m, **o: pin(mu, m, stop_on_stick=False, **o), True)
    recorded = dict(zip(("rodas4", "scipy-radau"), recorded, strict=False))
    return expected, decide, recorded


def _outcomes(kernel, radau):
    """The pair's outcomes as the fixture gives them: one name where both agree."""
    return kernel.outcome if kernel.outcome == radau.outcome else (kernel.outcome, radau.outcome)


def test_pin_outcome_and_first_sticking_agree(pin_pair):
    expected, decide, _ = pin_pair
    kernel, radau = decide["rodas4"], decide["scipy-radau"]
    assert radau.method == "scipy-radau"
    assert _outcomes(kernel, radau) == expected, (kernel.reason, radau.reason)
    assert is_stick(kernel.outcome) == is_stick(radau.outcome)
    assert math.isfinite(radau.R1)
    assert length_error(kernel.R1, radau.R1) <= 1.0
    assert time_error(kernel.t_R1, radau.t_R1) <= 1.0
    assert kernel.n_transitions == radau.n_transitions
    assert kernel.n_refused == radau.n_refused == 0
    assert radau.n_rejected == 0  # unknown for solve_ivp: reported as 0
    assert radau.n_steps > 0


def test_pin_switching_instants_agree(pin_pair):
    expected, _, recorded = pin_pair
    kernel, radau = recorded["rodas4"], recorded["scipy-radau"]
    assert radau.t_end == pytest.approx(kernel.t_end, abs=1e-9) and kernel.t_end >= 20.0
    assert _outcomes(kernel, radau) == expected
    t_kernel = switch_times(kernel.trajectory)
    t_radau = switch_times(radau.trajectory)
    if expected == "stick":
        assert len(t_kernel) == len(t_radau) == 1  # slide -> stick, then permanent sticking
    else:
        assert len(t_kernel) == len(t_radau) >= N_SWITCHES
    assert time_error(t_kernel, t_radau) <= 1.0
    # the modes alternate the same way on both sides
    m_kernel = kernel.trajectory.mode[1:][np.any(np.diff(kernel.trajectory.mode, axis=0), axis=1)]
    m_radau = radau.trajectory.mode[1:][np.any(np.diff(radau.trajectory.mode, axis=0), axis=1)]
    np.testing.assert_array_equal(m_kernel, m_radau)


def test_disk_agrees():
    """Disk on 4 points, co-rotating at start: same outcome and R1."""
    kernel, radau = disk_pair({"mu": 0.14, "phidot0": 1.1}, contact={"points": 4})
    assert kernel.outcome == radau.outcome == "stick", (kernel.reason, radau.reason)
    assert length_error(kernel.R1, radau.R1) <= 1.0
    assert time_error(kernel.t_R1, radau.t_R1) <= 1.0
    # the 4 symmetric contacts switch together (within the simultaneity window)
    assert kernel.n_transitions == radau.n_transitions == 4


@pytest.mark.slow  # > 10 s on 2 shared cores (selected out by -m 'not slow')
def test_disk_at_rest_with_refused_entries_agrees():
    """12-point disk starting at rest: contacts stick one by one, some entries are refused
    and re-enter stick later (a located event on both sides). Same switches, same
    refusals, same instants."""
    kernel, radau = disk_pair({"mu": 0.14, "phidot0": 0.0}, record=True)
    assert kernel.outcome == radau.outcome, (kernel.reason, radau.reason)
    assert "grazing contacts" in kernel.reason  # its evidence (scipy-radau has no section)
    assert kernel.n_refused == radau.n_refused > 0
    assert length_error(kernel.R1, radau.R1) <= 1.0
    # over the common span: at its horizon each side finishes an open sticking phase its own way
    span = min(kernel.t_end, radau.t_end) - 1e-6
    t_kernel = np.unique(switch_times(kernel.trajectory))
    t_radau = np.unique(switch_times(radau.trajectory))
    t_kernel, t_radau = t_kernel[t_kernel < span], t_radau[t_radau < span]
    assert len(t_kernel) == len(t_radau)
    # a re-entry is the zero of a rate (one derivative more than s): located less sharply
    np.testing.assert_allclose(t_kernel, t_radau, rtol=0.0, atol=TOL_REENTRY)


# ---- stopping rules, budget, recording, failure ----------------------------------------


def test_horizon_extended_to_finish_sticking():
    """A sticking phase that starts before the horizon is held to the end of one revolution."""
    radau = simulate_radau(pin(0.14, "scipy-radau", t_decide=4.0))
    assert radau.outcome == "stick"
    assert radau.t_end == pytest.approx(radau.t_R1 + revolution(1.1), abs=1e-9)


def test_work_budgets_give_undetermined():
    steps = simulate_radau(pin(0.14, "scipy-radau", max_steps=50))
    assert steps.outcome == "undetermined"
    assert "max_steps = 50" in steps.reason
    assert steps.n_steps == 50
    events = simulate_radau(pin(0.11, "scipy-radau", max_events=1))
    assert events.outcome == "undetermined"
    assert "max_events = 1" in events.reason
    assert events.n_transitions == 1


def test_dense_recording_includes_switching_points():
    config = pin(0.11, "scipy-radau", t_decide=5.0, stop_on_stick=False)
    result = simulate_radau(config, record=True, dt_out=0.1)
    tr = result.trajectory
    assert result.t_end == 5.0
    assert tr.t[0] == 0.0
    assert np.all(np.diff(tr.t) >= 0.0)
    assert tr.mode.shape == (tr.t.size, 1) and tr.mode.dtype == np.int8
    assert tr.phi is None and tr.Zx.shape == (tr.t.size, 1)
    # dense samples on the dt_out grid, plus the switching instant twice (old, new mode),
    # plus the ends of bookkeeping segments (a new stick contact leaving the hysteresis
    # band: no mode change)
    on_grid = np.isclose(tr.t / 0.1, np.round(tr.t / 0.1), rtol=0.0, atol=1e-9)
    off = tr.t[~on_grid]
    assert np.count_nonzero(off == result.t_R1) == 2
    assert np.all(np.diff(tr.mode[:, 0])[np.diff(tr.t) > 0] == 0)  # switches only at repeats
    k = np.nonzero(tr.t == result.t_R1)[0]
    assert list(tr.mode[k, 0]) == [km.SLIDE, km.STICK]
    assert np.count_nonzero(on_grid) == 50 + 1  # 0.0, 0.1, ..., 5.0


def test_numerical_failure_never_raises(monkeypatch):
    """A right-hand side that turns NaN ends the run as undetermined, with the reason."""
    honest = NumpyModel.rhs

    def poisoned(self, y, modes):
        f = honest(self, y, modes)
        return np.where(np.asarray(y)[1] < -0.01, np.nan, f)  # reached at t ~ 4 s

    monkeypatch.setattr(crosscheck.NumpyModel, "rhs", poisoned)
    result = simulate_radau(pin(0.11, "scipy-radau", t_decide=5.0))
    assert result.outcome == "undetermined"
    assert result.reason.startswith("integrator failed")
    assert 0.0 < result.t_end < 5.0
