"""The public API of `frictiondisk/__init__.py`: seven names, cheap to import."""

from __future__ import annotations

import subprocess
import sys

import pytest

import frictiondisk
from frictiondisk import load_campaign, load_scene, open_results, run_campaign, simulate
from frictiondisk.model.yamlio import ConfigError

TINY_LINE = """\
name: tiny_api_line
scene: pin
numerics: {t_decide: 20.0}
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-2
  along:
    params.x_ms: [0.1]
"""


def test_import_is_cheap():
    code = (
        "import sys, frictiondisk; "
        "bad = [m for m in ('numba', 'xarray', 'dask', 'matplotlib', 'scipy') if m in sys.modules];"
        "assert not bad, bad"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_simulate_stays_the_function_after_the_simulation_package_is_imported():
    from frictiondisk.simulation.pack import pack_parameters

    assert callable(pack_parameters)
    assert frictiondisk.simulate is simulate and callable(frictiondisk.simulate)
    public = "__version__ load_campaign load_scene open_results plot_orbit plot_results"
    api = [*public.split(), "run_campaign", "run_campaigns", "simulate"]
    assert sorted(frictiondisk.__all__) == sorted(api)


def test_load_scene_and_simulate(tmp_path):
    path = tmp_path / "pin.yaml"
    path.write_text("scene: pin\nparams: {x_ms: 0.1}\nnumerics: {t_decide: 20.0}\n")
    # the Coulomb oracle puts the pin's jump at mu* = c_s x_ms + g R1 = 0.1267 (docs/model.md)
    assert simulate(load_scene(path, ["params.mu=0.3"])).outcome == "stick"
    assert simulate(load_scene(path, ["params.mu=0.05"])).outcome != "stick"
    with pytest.raises(ConfigError, match="params.mu"):
        load_scene(path, ["params.mu=-1"])


def test_campaign_round_trip(tmp_path):
    spec = tmp_path / "line.yaml"
    spec.write_text(TINY_LINE)
    summary = run_campaign(spec, tmp_path / "out")
    assert summary is not None
    results = open_results(tmp_path / "out")
    lo, hi = float(results["mu_lo"][0]), float(results["mu_hi"][0])
    assert hi - lo <= 1e-2 and lo < 0.1267 < hi
    assert open_results(tmp_path / "out", "runs").sizes["run"] > 0
    assert load_campaign(spec).name == "tiny_api_line"


def test_one_override_given_as_a_string_is_one_clear_error(tmp_path):
    """A string is not a list of overrides: one error saying so, not one "malformed
    override" per character."""
    path = tmp_path / "pin.yaml"
    path.write_text("scene: pin\n")
    with pytest.raises(TypeError) as info:
        load_scene(path, "params.mu=0.2")
    text = str(info.value)
    assert "not one string" in text and "['params.mu=0.2']" in text
    assert "malformed" not in text
    assert load_scene(path, ("params.mu=0.2",)).params.mu == 0.2  # a tuple is a sequence
