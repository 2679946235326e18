"""The pure-sliding motions from the motion's own section (kernel/own_section.py,
verdict/motion_evidence.py; docs/model.md section 6): one hand-checked scene per motion.

The pins run here (a pin's 300 s take well under a second). The disks replay rows of the
own section recorded from the issue-49 example scenes (tests/data/own_section_*.npz: the
newest 160 or 80 rows of `SimulationResult.own_section`, the fields the evidence reads),
so the suite does not integrate a 48-contact disk for 1 500-3 000 s. The scenes: a braked
disk x_ms 0, mu 0.05, omega_m 1.5, beta_s 0.3, beta_b 0.003, from x0 0.15, vy0 0.15,
phidot0 1.5 on a ring of radius 0.1 m, mode converge: J_s 0.3 and 48 points for 3 000 s
(modulated), J_s 0.1 and 48 points for 1 500 s (the whirl); J_s 0.1 and 12 points started
on the whirl (x0 = vy0 = 0.117569, phidot0 0.94358) for 1 500 s (the layout ripple).
The reference numbers were measured on recorded trajectories in the issue's study.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from own_rows import recorded_rows

from frictiondisk.kernel.records import OWN_STEP
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict import motion_evidence as me
from frictiondisk.verdict import own_evidence
from frictiondisk.verdict.outcomes import is_not_stick
from frictiondisk.verdict.params import VerdictParams

CYCLE_TOL = 1e-6  # numerics.cycle_tol default [m]


def pin(mu: float, omega_m: float, t_max: float, **params) -> dict:
    return {
        "scene": "pin",
        "params": {"mu": mu, "omega_m": omega_m, **params},
        "numerics": {"mode": "converge", "t_max": t_max},
    }


@pytest.fixture(scope="module")
def self_centring():
    return simulate(scene_from_dict(pin(0.095, 0.8, 300.0)))


def test_the_self_centring_pin_rests_on_its_exact_sliding_equilibrium(self_centring):
    """c_s (r - r0) = mu F_n e_theta with r at right angles to r - r0 (docs/model.md): in
    the Coulomb limit |r_eq| = sqrt(x_ms^2 - d^2), d = mu F_n / c_s, at angle asin(d / x_ms);
    the contact stiffness c puts the slip direction along r - z, |z| = delta = mu F_n / c."""
    res = self_centring
    assert res.outcome == "self_centring", res.reason
    assert res.cycle_converged and is_not_stick(res.outcome)
    x_ms, d, delta = 0.1, 0.095, 0.095 / 2.53e5
    regularized = math.sqrt(x_ms**2 - (d + delta) ** 2 + delta**2)
    assert abs(res.r_eq - regularized) <= CYCLE_TOL
    assert abs(res.r_eq - math.sqrt(x_ms**2 - d**2)) <= 2.0 * CYCLE_TOL  # 1.1e-6 apart
    assert abs(res.r_eq_angle - math.asin(d / x_ms)) <= 1e-4
    assert math.hypot(res.r_eq_x, res.r_eq_y) == pytest.approx(res.r_eq)


def test_the_self_centring_pin_decays_at_beta_s_over_2_m_s(self_centring):
    """The slowest mode is the tangential one friction does not touch: -beta_s / 2 m_s."""
    res = self_centring
    assert res.decay_rate == pytest.approx(0.1 / 2.0, rel=1e-3)
    assert "beta_s/2m_s = 0.05 1/s" in res.reason
    assert res.floquet_ratio == pytest.approx(math.exp(-0.05 * res.own_period), rel=1e-3)
    # the damped frequency sqrt(c_s / m_s - 0.05^2) = 0.99875 rad/s sets the own period
    assert res.own_period == pytest.approx(2.0 * math.pi / 0.998749, rel=2e-3)


def test_a_motion_shown_at_rest_self_centres_without_a_steady_ratio(self_centring):
    """Near round-off the ratios of the speed scatter; at rest within tol it is shown."""
    rows = self_centring.own_section.copy()
    rows["v_max"][-3:] = (1e-9, 3e-10, 2e-10)  # ratios 0.3, 0.67: no steady fall
    scene = me.OwnScene(1.0, 0.0, 1e-9, 1, CYCLE_TOL, 1e-9, 1e-6)
    ev = me.judge(rows, scene, VerdictParams())
    assert ev.motion == "self_centring" and ev.converged, ev.reason
    assert math.isnan(ev.decay_rate)
    assert ev.r_eq == pytest.approx(self_centring.r_eq, abs=CYCLE_TOL)  # at rest within tol
    rows["slip"][-1] = 0.0  # a rest that does not slip is sticking, not self-centring
    assert me.judge(rows, scene, VerdictParams()).motion == ""  # nor a cycle: it rests


def test_a_short_run_names_the_motion_before_it_has_settled():
    res = simulate(scene_from_dict(pin(0.095, 0.8, 60.0)))
    assert res.outcome == "self_centring" and not res.cycle_converged, res.reason
    assert "travel left" in res.reason


def test_the_large_cycle_of_the_pin_turns_at_the_support_s_own_frequency():
    """mu 0.05, omega_m 1.5 from x0 0.4, vy0 0.5 (issue 49): period, mean radius and
    contraction measured on the recorded trajectory in the issue's study."""
    res = simulate(scene_from_dict(pin(0.05, 1.5, 300.0, x0=0.4, vy0=0.5)))
    assert res.outcome == "slide_cycle" and res.cycle_converged, res.reason
    assert res.own_period == pytest.approx(2.0 * math.pi, rel=1e-3)  # 6.28025 s
    assert res.own_period == pytest.approx(6.28025, abs=1e-4)
    assert res.mean_radius == pytest.approx(0.44826, abs=1e-5)
    assert res.amplitude == pytest.approx(0.5 * (0.54879 - 0.35186), abs=1e-5)
    assert math.isnan(res.r_eq)


def test_the_large_cycle_contracts_by_its_floquet_ratio():
    res = simulate(scene_from_dict(pin(0.05, 1.5, 90.0, x0=0.4, vy0=0.5)))
    assert res.outcome == "slide_cycle" and not res.cycle_converged, res.reason
    assert res.floquet_ratio == pytest.approx(0.794, abs=0.002)


def test_the_own_section_rows_cover_the_run_and_mark_sticking():
    res = simulate(scene_from_dict(pin(0.2, 1.1, 60.0)))  # sticks at 11.4 s
    assert res.outcome == "stick"
    rows = res.own_section
    assert rows.dtype == OWN_STEP and rows.shape[0] >= 1
    assert rows["locked"][-1]  # while stuck the velocity turns with the master: locked rows
    assert own_evidence.sliding_rows(rows).shape[0] == 0


# --- the disks: rows of the example scenes, replayed ------------------------------------


def _disk_scene(points: int) -> me.OwnScene:
    return me.OwnScene(
        omega0=1.0,
        arm=0.1,
        eps=1e-9,
        n_contacts=points,
        cycle_tol=CYCLE_TOL,
        atol=1e-9,
        rtol=1e-6,
    )


def test_the_example_disk_is_a_modulated_cycle():
    """J_s 0.3 above the torus bifurcation J_NS = 0.2704 (48 points): envelope period
    136.66 s measured on the trajectory by a spline through the step means."""
    ev = me.judge(recorded_rows("modulated_disk"), _disk_scene(48), VerdictParams())
    assert ev.motion == "modulated" and ev.converged, ev.reason
    assert ev.envelope_period == pytest.approx(136.66, rel=VerdictParams().env_tol)
    # |r| 0.07717 ... 0.13959 m on the trajectory: half its range, about its mean 0.11246 m
    assert ev.envelope_depth == pytest.approx(0.5 * (0.13959 - 0.07717), rel=0.01)
    assert ev.mean_radius == pytest.approx(0.11246, rel=0.01)
    assert ev.own_period == pytest.approx(6.28, abs=0.1)


def test_the_whirl_below_the_torus_bifurcation_is_a_sliding_cycle():
    ev = me.judge(recorded_rows("whirl_disk"), _disk_scene(48), VerdictParams())
    assert ev.motion == "slide_cycle" and ev.converged, ev.reason
    assert ev.mean_radius == pytest.approx(0.117569, abs=1e-5)  # a relative equilibrium
    assert ev.own_period == pytest.approx(2.0 * math.pi / 1.000007, abs=1e-3)
    assert ev.spin_rate == pytest.approx(0.94358, abs=1e-4)


def test_the_ripple_of_a_12_point_ring_is_no_modulation():
    """The layout guard: the 12-point ring's 0.69 % ripple at N |Omega - phidot|, aliased by
    a section once a whirl into a 19.5 s beat, is the whirl's, not a fourth motion."""
    rows = recorded_rows("layout_artefact_disk")
    ev = me.judge(rows, _disk_scene(12), VerdictParams())
    assert ev.motion == "slide_cycle" and ev.converged, ev.reason
    assert "inside the ripple of its ring" in ev.reason
    assert ev.mean_radius == pytest.approx(0.117569, abs=1e-4)
    # without the band rule (own_window longer than the run) and with envelopes allowed to
    # scatter by 20 % (over all of them, no trend read ahead), the beat reads as 19.4 s
    # envelopes: the frequency guard refuses it
    jittery = {"own_window": 1000, "env_tol": 0.2, "env_trend_count": 1000}
    guarded = me.judge(rows, _disk_scene(12), VerdictParams(**jittery))
    assert guarded.motion != "modulated", guarded.reason
    unguarded = me.judge(rows, _disk_scene(12), VerdictParams(**jittery, layout_alias=0.0))
    assert unguarded.motion == "modulated", unguarded.reason
    assert unguarded.envelope_period == pytest.approx(19.5, abs=0.5)


# --- the rules on their own ---------------------------------------------------------------


def test_aitken_is_exact_on_a_geometric_sequence():
    assert own_evidence.aitken(np.array([1.0, 0.5, 0.25])) == pytest.approx(0.0, abs=1e-15)
    assert own_evidence.aitken(np.array([3.0, 2.5, 2.25])) == pytest.approx(2.0)
    assert math.isnan(own_evidence.aitken(np.array([1.0, 2.0, 4.0])))  # steps grow: no limit


def test_a_ratio_that_turns_back_and_forth_is_not_steady():
    """Sampled once a master revolution the self-centring approach alternates 0.684/0.665
    (issue 49); its own section gives a steady 0.730."""
    vp = VerdictParams()
    alternating = np.cumprod([1.0, 0.684, 0.665, 0.684, 0.665, 0.684])
    assert math.isnan(own_evidence.steady_ratio(alternating, vp.own_ratios, vp))
    steady = 0.730 ** np.arange(6.0)
    assert own_evidence.steady_ratio(steady, vp.own_ratios, vp) == pytest.approx(0.730)


def test_too_few_sliding_rows_are_no_evidence():
    rows = np.zeros(6, dtype=OWN_STEP)
    rows["locked"][3] = True
    ev = me.judge(rows, _disk_scene(1), VerdictParams())
    assert ev.motion == "" and not ev.converged
    assert "2 own periods of sliding" in ev.reason


# --- names say what was seen; the own section keeps its newest rows -----------------------


def test_the_demo_pin_reads_stick_slip():
    """campaigns/demo_pin.yaml (decide mode, 60 s) promises the paper's stick-slip cycle:
    its final window alternates sticking as a whole and sliding, so it is stick_slip,
    not converged (it departs from sticking), whatever its own section shows."""
    from pathlib import Path

    from frictiondisk import load_scene

    config = load_scene(Path(__file__).resolve().parents[1] / "campaigns" / "demo_pin.yaml")
    res = simulate(config)
    assert res.outcome == "stick_slip" and not res.cycle_converged, res.reason
    assert 0.0 < res.stick_fraction < 1.0
    assert "sticking and sliding alternate in the final window" in res.reason


def test_a_slave_at_rest_keeps_its_newest_rows_without_filling_the_section():
    """An overdamped pin (beta_s 5 > 2 sqrt(c_s m_s)) slides to rest without its velocity
    turning: rows are closed by time (turn 0), each twice as long as the longest before, so
    the newest row ends within a factor two of the run's end and rest adds a handful."""
    res = simulate(scene_from_dict(pin(0.095, 0.8, 2000.0, beta_s=5.0)))
    rows = res.own_section
    assert rows.shape[0] < 40
    assert rows["t"][-1] >= 0.5 * res.t_end
    closed_by_time = rows[rows["turn"] == 0]
    assert closed_by_time.shape[0] >= 3
    assert all(closed_by_time["dt"][1:] >= 2.0 * closed_by_time["dt"][:-1] * (1 - 1e-12))
    assert res.outcome == "self_centring" and res.cycle_converged, res.reason
    # the measures are the newest row's: at rest, no amplitude left
    assert res.amplitude <= CYCLE_TOL
