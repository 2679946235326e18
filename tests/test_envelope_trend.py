"""The trend of a modulation's depth (verdict/envelope_trend.py) and the motions it names
(rule envelope_trend, verdict/motion_evidence.py): the growth or decay of the envelope near
the torus bifurcation of the braked axisymmetric disk, read as Re(lambda) of the whirl's
slow pair.

The recorded rows (tests/data/own_section_torus_*.npz, the newest 300 rows of
`SimulationResult.own_section`) are the issue-49 example disk (x_ms 0, mu 0.05, omega_m 1.5,
beta_s 0.3, beta_b 0.003, ring 0.1 m of 48 points, mode converge, 3 000 s) started near the
whirl (x0 = 0.117569 m + 0.5 mm at J_s 0.2695, + 0.2 mm at J_s 0.2712; vy0 0.117569 m/s,
phidot0 0.94358 rad/s), on either side of J_NS ~ 0.2706.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from own_rows import recorded_rows
from scipy.optimize import curve_fit

from frictiondisk.verdict import motion_evidence as me
from frictiondisk.verdict import own_evidence
from frictiondisk.verdict.envelope_trend import depth_trend
from frictiondisk.verdict.params import VerdictParams

PERIOD = 107.0  # envelope period near J_NS [s]


def _envelopes(depth, count=12, noise=0.0, seed=0):
    middles = PERIOD * np.arange(count, dtype=float)
    depths = np.array([depth(t) for t in middles])
    rng = np.random.default_rng(seed)
    return middles, depths * (1.0 + noise * rng.standard_normal(count))


def test_a_geometric_decay_dies_out_with_its_rate():
    vp = VerdictParams()
    middles, depths = _envelopes(lambda t: 3e-4 * math.exp(-2e-5 * t), noise=1e-4)
    trend = depth_trend(middles, depths, vp.env_trend_count)
    assert trend.rate == pytest.approx(-2e-5, abs=4 * trend.rate_error)
    assert trend.rate_error < 2e-6  # 1e-4 noise over 12 envelopes: ~3e-7 1/s
    assert trend.dies_out(vp.env_trend_sigmas, vp.env_trend_limit)
    assert not trend.grows(vp.env_trend_sigmas)


def test_a_decay_towards_a_modulation_does_not_die_out():
    """depth = L + C exp(b t), L from 0.5 to 0.76 of the depth over the window: its rate
    weakens as it approaches L; the bend says so (L / (depth - L) = curvature / rate^2)."""
    vp = VerdictParams()
    middles, depths = _envelopes(lambda t: 0.02 + 0.02 * math.exp(-1e-3 * t), noise=1e-4)
    trend = depth_trend(middles, depths, vp.env_trend_count)
    assert trend.rate < -vp.env_trend_sigmas * trend.rate_error  # it does fall
    assert 0.02 / depths[0] <= trend.limit_share(0.0) <= 0.02 / depths[-1]
    assert not trend.dies_out(vp.env_trend_sigmas, vp.env_trend_limit)


def test_a_growth_grows_and_noise_alone_decides_nothing():
    vp = VerdictParams()
    middles, depths = _envelopes(lambda t: 1e-4 * math.exp(2e-5 * t), noise=1e-4)
    assert depth_trend(middles, depths, 12).grows(vp.env_trend_sigmas)
    flat_middles, flat = _envelopes(lambda t: 1e-4, noise=1e-3, seed=3)
    flat_trend = depth_trend(flat_middles, flat, 12)
    assert not flat_trend.grows(vp.env_trend_sigmas)
    assert not flat_trend.dies_out(vp.env_trend_sigmas, vp.env_trend_limit)


def test_too_few_envelopes_give_no_trend():
    middles, depths = _envelopes(lambda t: 1e-4, count=3)
    assert depth_trend(middles, depths, 3) is None
    assert depth_trend(middles, depths, 12) is None


# --- the example disk on either side of the torus bifurcation ----------------------------


def _scene() -> me.OwnScene:
    return me.OwnScene(
        omega0=1.0, arm=0.1, eps=1e-9, n_contacts=48, cycle_tol=1e-6, atol=1e-9, rtol=1e-6
    )


def _sinusoid_rate(rows: np.ndarray, span: float) -> float:
    """Re(lambda) from an independent estimator: r0 + a exp(b t) cos(w t + p) fitted to the
    step-mean |r| over the newest `span` seconds (not to the envelope's extremes)."""
    t = rows["t"] - 0.5 * rows["dt"]
    keep = t > t[-1] - span
    t, s = t[keep] - np.mean(t[keep]), rows["r_mean"][keep]

    def model(t, r0, a, b, w, p):
        return r0 + a * np.exp(b * t) * np.cos(w * t + p)

    fits = []
    for phase in np.linspace(0.0, 2.0 * math.pi, 8, endpoint=False):
        start = [np.mean(s), 0.5 * np.ptp(s), 0.0, 2.0 * math.pi / PERIOD, phase]
        try:
            p, _ = curve_fit(model, t, s, p0=start, maxfev=20000)
        except RuntimeError:
            continue
        fits.append((float(np.sum((model(t, *p) - s) ** 2)), float(p[2])))
    return min(fits)[1]


@pytest.mark.parametrize(
    "name, motion",
    [("torus_below_disk", "slide_cycle"), ("torus_above_disk", "modulated")],
)
def test_near_the_torus_bifurcation_the_trend_names_the_side(name, motion):
    """Within 1e-3 of J_NS the envelope changes by 0.1-0.9 % an envelope: three envelopes
    agree within env_tol, yet neither is a settled modulation; the trend names the side,
    and its rate is the one a decaying sinusoid fitted to |r| itself gives (Re(lambda)
    -7.5e-5 and +3.9e-5 1/s; the two estimators differ by ~6e-6 1/s, 1e-4 in J_s)."""
    rows = recorded_rows(name)
    ev = me.judge(rows, _scene(), VerdictParams())
    assert ev.motion == motion and ev.rule == own_evidence.ENVELOPE_TREND, ev.reason
    assert not ev.converged
    rate = -ev.decay_rate
    reference = _sinusoid_rate(rows, 1300.0)
    assert math.copysign(1.0, rate) == math.copysign(1.0, reference)
    assert rate == pytest.approx(reference, rel=0.2)


def test_a_slow_decay_that_three_envelopes_call_steady_is_no_settled_depth():
    """At 3e-4 of J_s from J_NS the whirl's slow pair decays at ~2e-5 1/s: three envelopes
    agree within env_tol (0.4 %), as a modulated cycle's do; the bound on the depth's
    trend over env_trend_count envelopes refuses to call that depth steady."""
    vp = VerdictParams()
    middles, depths = _envelopes(lambda t: 3e-4 * math.exp(-2e-5 * t), noise=1e-4)
    newest = depths[-vp.env_count :]
    assert np.ptp(newest) <= vp.env_tol * newest[-1]
    trend = depth_trend(middles, depths, vp.env_trend_count)
    assert trend.change_bound(vp.env_trend_sigmas) > vp.env_tol
