"""A Coulomb pin grazing its sticking circle (verdict/grazing.py; docs/model.md section 6).

Stuck, the pin is carried on a circle about the master axis whose largest demand is
g R + c_s |x_ms|, g = |c_s - m_s omega_m^2 + i beta_s omega_m|. Where that exceeds mu F_n
by a little, the pin leaves sticking there for a moment, and its slip has the outward
share (m_s omega_m^2 - c_s) / g. The pin of these tests (x_ms 0.1 m, omega_m 1.1 rad/s,
c_s 1 N/m, m_s 1 kg: 0.886 outward) is watched long enough to see where that leads, and
the rule that reads it decides the tol 1e-8 line's grazing ends, which no trend can. A pin
below its critical speed (seed 11's scene 42 of the well-posedness study) creeps inward
onto the rim of its sticking disc, just above Melan's bound c_s |x_ms| / F_n.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from frictiondisk.engine.runner import run_campaign
from frictiondisk.kernel.records import REV_RING
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.pack import pack_parameters
from frictiondisk.simulation.simulate import simulate
from frictiondisk.store.cf import flag_meanings
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.verdict.grazing import outward_share

ROOT = Path(__file__).resolve().parents[1]
X_MS = 0.1  # [m]
# mu* / x_ms of the pin line from x0 = 0 at rtol 1e-10, atol 1e-14, tol 1e-10
# (benchmarks/lines/pin_line_tol1e-8.yaml; the pin's jump is linear in x_ms)
REFERENCE_SLOPE = 1.26723443  # [1/m]


def pin(mu: float, **numerics) -> dict:
    return {"scene": "pin", "params": {"x_ms": X_MS, "mu": mu}, "numerics": numerics}


def watched(mu: float, t_max: float):
    """The pin at mu watched to t_max [s], named on what it shows alone."""
    return simulate(
        scene_from_dict(pin(mu, mode="converge", evidence="observe", t_max=t_max, rtol=1e-9))
    )


def grazing_mu() -> float:
    """mu at which the circle the pin first sticks on just holds: the zero of its friction
    reserve mu - (g R1 + c_s |x_ms|) / F_n (verdict/reserve.py), R1 the first circle's
    radius, which moves with mu (secant steps from 0.12 and 0.13)."""
    a, b = 0.12, 0.13
    f_a, f_b = (watched(mu, 20.0).reserve for mu in (a, b))
    while abs(b - a) > 1e-10:
        a, b, f_a = b, b - f_b * (b - a) / (f_b - f_a), f_b
        f_b = watched(b, 20.0).reserve
    return b


def test_the_slip_s_outward_share_changes_sign_at_the_critical_speed():
    """(m_s omega_m^2 - c_s) / g: outward above the spring's critical speed sqrt(c_s / m_s),
    inward below it, and no share for a Stribeck law or a disk."""
    for omega_m, sign in ((1.1, 1.0), (0.9, -1.0)):
        p, _ = pack_parameters(scene_from_dict({"scene": "pin", "params": {"omega_m": omega_m}}))
        k_re = 1.0 - omega_m**2
        assert outward_share(p) == pytest.approx(-k_re / math.hypot(k_re, 0.1 * omega_m))
        assert math.copysign(1.0, outward_share(p)) == sign
    stribeck = {"scene": "pin", "contact": {"stribeck": {"r": 0.5, "v_s": 0.01, "delta": 1.0}}}
    assert math.isnan(outward_share(pack_parameters(scene_from_dict(stribeck))[0]))
    assert math.isnan(outward_share(pack_parameters(scene_from_dict({"scene": "disk"}))[0]))


@pytest.fixture(scope="module")
def grazing_pair():
    """The pin 1e-4 below and above the mu at which its first circle just holds, watched to
    4 000 s (a few seconds)."""
    mu_g = grazing_mu()
    return mu_g, watched(mu_g - 1e-4, 4000.0), watched(mu_g + 1e-4, 4000.0)


def test_a_slip_that_carries_the_pin_outward_departs_from_sticking(grazing_pair):
    """1e-4 below, the pin leaves its circle at every revolution; every slip carries it
    outward onto a circle that demands more, so the slip grows revolution after revolution
    until the pin reaches the large stick-slip cycle. 1e-4 above, it sticks on its circle."""
    mu_g, below, above = grazing_pair
    assert above.outcome == "stick", above.reason
    revs = below.revolutions
    assert len(revs) < REV_RING  # the ring holds every revolution from the first
    early = revs[1:60]
    assert np.all(~early["all_stuck"]) and np.all(early["switches"] >= 1)
    assert np.all(early["stick_t"] > 0.9 * 2.0 * math.pi / 1.1)  # a short break a revolution
    assert np.all(np.diff(early["slip"]) > 0.0)  # the slip grows at every revolution
    radius = np.hypot(early["x"], early["y"])
    outward = np.diff(radius) / early["slip"][1:]
    # each slip moves the circle outward by a share of itself near the slip's outward share
    assert np.all(outward > 0.5) and np.all(outward < 1.0)
    # where it leads: the large stick-slip cycle, far from the circle it grazed
    assert below.outcome == "stick_slip", below.reason
    assert below.stick_fraction < 0.5 and revs[-1]["slip"] > 1e4 * revs[1]["slip"]


def test_the_tol_1e8_line_s_grazing_ends_are_certified(tmp_path):
    """At tol 1e-8 each mu_lo end slips some 1e-15 m a revolution, below what rtol 1e-9
    resolves (a stuck pin drifts 2e-11 m a revolution there), so no trend of its slip can
    be read; its check names it by the grazing rule, and every point is certified, its
    bracket holding the reference mu* at the budget of 8 runs a point."""
    text = (ROOT / "benchmarks/lines/pin_line_tol1e-8.yaml").read_text()
    run_campaign(campaign_from_text(text), tmp_path, workers=2, progress=False)
    with (
        xr.open_dataset(tmp_path / "results.nc") as res,
        xr.open_dataset(tmp_path / "runs.nc") as runs,
    ):
        flags = flag_meanings(res["certification"])
        assert {flags[int(v)] for v in res["certification"].values.ravel()} == {"certified"}
        assert float(res["n_runs"].mean()) <= 8.0
        x_ms = res["x_ms"].values
        lo, hi = res["mu_lo"].values.ravel(), res["mu_hi"].values.ravel()
        assert np.all(hi - lo <= 1e-8 * (1 + 1e-9))
        assert np.all((lo <= REFERENCE_SLOPE * x_ms) & (REFERENCE_SLOPE * x_ms <= hi))
        checks = runs.where(runs["role"] == "certification", drop=True)
        graze = checks.where(checks["decided_by"] == "graze", drop=True)
        assert graze.sizes[next(iter(graze.sizes))] == len(x_ms)
        assert set(graze["outcome"].values) == {"stick_slip"}


def test_a_pin_below_its_critical_speed_creeps_onto_its_rim_and_its_jump_is_melan_s(tmp_path):
    """Seed 11's scene 42 (m_s omega_m^2 = 0.803 < c_s): just above c_s |x_ms| / F_n each
    slip carries the pin inward, onto its 0.17 mm sticking disc, its slip falling
    algebraically; its check names that `stick` (rule `rim`, where the every-step
    shakedown test reads nothing in the scattered slips at rtol 1e-6), and the jump is
    certified with its bracket holding the bound."""
    text = """\
name: seed11_scene42
scene: pin
params: {x_ms: 0.12535, m_s: 1.3717, omega_m: 0.7652, x0: -0.00293}
find_jump:
  bracket: [0.05, 0.5]
  tol: 1.0e-4
  along: {params.x0: [-0.00293]}
"""
    run_campaign(campaign_from_text(text), tmp_path, workers=2, progress=False)
    with (
        xr.open_dataset(tmp_path / "results.nc") as res,
        xr.open_dataset(tmp_path / "runs.nc") as runs,
    ):
        flags = flag_meanings(res["certification"])
        assert flags[int(res["certification"].values.ravel()[0])] == "certified"
        lo, hi = float(res["mu_lo"].values.ravel()[0]), float(res["mu_hi"].values.ravel()[0])
        assert lo <= 1.0 * 0.12535 / 1.0 <= hi and hi - lo <= 1e-4 * (1 + 1e-9)
        checks = runs.where(runs["role"] == "certification", drop=True)
        hi_check = checks.where(checks["mu"] == hi, drop=True)
        assert list(hi_check["decided_by"].values) == ["rim"]
        assert list(hi_check["outcome"].values) == ["stick"]
