"""Fig 11's bounds (frictiondisk/studies/brake/bounds_figure.py): evaluated at each point's radius."""

from pathlib import Path

import numpy as np
import xarray as xr
from conftest import coulomb_mu_star

from frictiondisk.studies.brake.bounds_figure import bounds_for, plot_brake

CAMPAIGN = Path(__file__).resolve().parents[1] / "campaigns" / "fig11_betab_mu.yaml"


def _results(beta_b, size_hi, r1_hi, mu_lo, mu_hi):
    return xr.Dataset(
        {
            "size_hi": ("beta_b", np.asarray(size_hi, float)),
            "R1_hi": ("beta_b", np.asarray(r1_hi, float)),
            "mu_lo": ("beta_b", np.asarray(mu_lo, float)),
            "mu_hi": ("beta_b", np.asarray(mu_hi, float)),
        },
        coords={"beta_b": np.asarray(beta_b, float)},
        attrs={"campaign_yaml": CAMPAIGN.read_text()},
    )


def test_bounds_at_each_radius():
    radius = 0.104
    results = _results(
        [0.0, 0.005, 0.01], [radius, np.nan, radius], [0.1, radius, 0.1], [0.1] * 3, [0.2] * 3
    )
    bounds = bounds_for(results)
    # size_hi where present, else R1_hi
    np.testing.assert_allclose(bounds["radius"], [radius, radius, radius])
    # no brake: both bounds are the pin's oracle c_s x_ms + g R (F_n = 1 N)
    oracle = coulomb_mu_star(radius)
    np.testing.assert_allclose([bounds["collapse"][0], bounds["shakedown"][0]], oracle, rtol=1e-6)
    # a brake raises both, and shakedown is never below collapse
    assert np.all(np.diff(bounds["shakedown"]) > 0) and np.all(np.diff(bounds["collapse"]) > 0)
    assert np.all(bounds["shakedown"] >= bounds["collapse"] - 1e-12)


def test_figure_draws_both_series():
    results = _results([0.0, 0.005], [0.104, 0.104], [0.1, 0.1], [0.12, 0.21], [0.1201, 0.2101])
    fig = plot_brake({"rest": results, "corotating": results})
    labels = [line.get_label() for line in fig.axes[0].get_lines()]
    assert any("shakedown" in label for label in labels)
    assert any("collapse" in label for label in labels)
    assert fig.axes[1].get_ylabel().startswith("μ* − shakedown")
