"""`simulate` and `run` on a clutch-like annulus of 192 contacts (issue 11)."""

import json

import xarray as xr
from click.testing import CliRunner

from frictiondisk.cli import main

# A 2 s horizon keeps these runs short; the co-rotation rule needs five revolutions, so
# the layout is tested under the contacts rule (the rule itself: tests/test_corotation.py).
ANNULUS = "contact: {layout: annulus, inner_radius: 0.063, outer_radius: 0.087, points: 192}"


def test_simulate_and_run_an_annulus_of_192_contacts(tmp_path):
    scene = tmp_path / "scene.yaml"
    scene.write_text(
        "scene: disk\nparams: {beta_b: 0.005, phidot0: 1.1, mu: 0.2}\n"
        f"{ANNULUS}\nnumerics: {{t_decide: 2.0, horizon_budget: 20}}\n"
    )
    out = CliRunner().invoke(main, ["simulate", str(scene), "--json"])
    assert out.exit_code == 0, out.output
    summary = json.loads(out.output)
    assert summary["outcome"] in ("stick", "stick_slip", "slide")
    assert summary["n_transitions"] > 0  # the contacts do switch

    campaign = tmp_path / "clutch.yaml"
    campaign.write_text(
        "name: clutch_test\nscene: disk\nparams: {phidot0: 1.1, beta_b: 0.005}\n"
        f"{ANNULUS}\nnumerics: {{t_decide: 2.0, horizon_budget: 20}}\n"
        "find_jump:\n  bracket: [0.05, 0.6]\n  tol: 0.05\n  along:\n    params.x_ms: [0.1]\n"
    )
    out_dir = tmp_path / "out"
    result = CliRunner().invoke(main, ["run", str(campaign), "-o", str(out_dir), "--workers", "1"])
    assert result.exit_code == 0, result.output
    with xr.open_dataset(out_dir / "results.nc") as ds:
        mu = float(ds["mu_star"].values.ravel()[0])
    assert 0.05 < mu < 0.6


def test_a_bad_annulus_is_refused_with_exit_code_2(tmp_path):
    scene = tmp_path / "scene.yaml"
    scene.write_text(
        "scene: disk\ncontact: {layout: annulus, inner_radius: 0.09, outer_radius: 0.087}\n"
    )
    out = CliRunner().invoke(main, ["simulate", str(scene)])
    assert out.exit_code == 2
    assert "contact.outer_radius: 0.087 is not allowed: must be > inner_radius" in out.output
