"""numerics auto in a running campaign: the preflight line, the refusal of a tol out of
reach (on run and resume) and `run --tol-floor`,
the choice in results.nc, and a pin line whose tol alone chose numerics that certify."""

from __future__ import annotations

from pathlib import Path

import xarray as xr
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.engine.runner import run_campaign
from frictiondisk.store.cf import flag_meanings
from frictiondisk.tasks.campaign import campaign_from_text

FIXED = """\
name: fixed
scene: pin
numerics: {rtol: 1.0e-6}
find_jump:
  bracket: [0.12, 0.13]
  tol: 1.0e-8
  along: {params.x_ms: [0.1]}
"""


def test_numerics_that_cannot_reach_the_tol_are_refused_before_any_work(tmp_path):
    campaign_file = tmp_path / "c.yaml"
    campaign_file.write_text(FIXED)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["run", str(campaign_file), "-o", str(out)])
    assert result.exit_code == 2, result.output
    assert "cannot start (nothing was created)" in result.stderr
    floor = campaign_from_text(FIXED, "<test>").numerics_choice.floor
    assert (
        "numerics cannot reach find_jump.tol 1e-08: expected mu* error" in result.stderr
        and f"the smallest tol they reach is {floor:.2g}" in result.stderr
        and "leave rtol out to let the tol choose them, or run --tol-floor" in result.stderr
    ), result.stderr
    assert not out.exists()


def test_a_stored_campaign_out_of_reach_is_refused_on_resume(tmp_path):
    """A DIR started before the refusal (its campaign.yaml out of reach) is not resumed:
    the refusal says how to start it again at the floor."""
    from frictiondisk.engine.directory import prepare_directory

    prepare_directory(tmp_path, campaign_from_text(FIXED, "<test>"))
    result = CliRunner().invoke(main, ["resume", str(tmp_path)])
    assert result.exit_code == 2, result.output
    assert "numerics cannot reach find_jump.tol 1e-08" in result.stderr
    assert f"run {tmp_path / 'campaign.yaml'} --tol-floor -o NEW_DIR" in result.stderr
    assert not (tmp_path / "journal").exists()


def test_tol_floor_runs_at_the_smallest_tol_the_numerics_reach(tmp_path):
    campaign_file = tmp_path / "c.yaml"
    campaign_file.write_text(FIXED)
    out = tmp_path / "out"
    floor = campaign_from_text(FIXED, "<test>").numerics_choice.floor
    result = CliRunner().invoke(main, ["run", str(campaign_file), "-o", str(out), "--tol-floor"])
    assert result.exit_code == 0, result.output
    assert f"find_jump.tol 1e-08 raised to {floor:g}" in result.stderr
    stored = campaign_from_text((out / "campaign.yaml").read_text(), "<stored>")
    assert stored.task.tol == floor and stored.numerics_choice.reaches
    with xr.open_dataset(out / "results.nc") as results:
        assert results.attrs["numerics_choice"] == stored.numerics_choice.describe()
        assert results.attrs["numerics_expected_mu_error"] <= results.attrs["numerics_error_bound"]
        width = (results["mu_hi"] - results["mu_lo"]).values
        assert (width <= floor * (1 + 1e-9)).all()


AUTO_LINE = """\
name: auto_line
scene: pin
find_jump:
  bracket: [0.05, 0.5]
  tol: 1.0e-6
  along: {params.x_ms: [0.08, 0.12]}
"""


def test_numerics_chosen_by_the_tol_alone_certify_the_pin(tmp_path: Path):
    campaign = campaign_from_text(AUTO_LINE, "<test>")
    choice = campaign.numerics_choice
    assert choice.chosen == ("rtol", "atol", "t_decide") and choice.reaches
    run_campaign(campaign, tmp_path, workers=2, progress=False)
    with xr.open_dataset(tmp_path / "results.nc") as results:
        flags = flag_meanings(results["certification"])
        certification = [flags[int(v)] for v in results["certification"].values]
        assert certification == ["certified"] * 2, list(results["reason"].values)
        assert results.attrs["numerics_choice"] == choice.describe()
        mu_star = results["mu_star"].values
        width = (results["mu_hi"] - results["mu_lo"]).values
        assert (width <= 1e-6 * (1 + 1e-9)).all()
    # the default pin from x0 = 0: mu* proportional to x_ms (docs/model.md section 6; 1e-8
    # relative), so the two midpoints agree up to their half widths and the expected error
    tol = 1e-6
    scaled = mu_star[0] * 0.12 / 0.08
    assert abs(mu_star[1] - scaled) <= (0.5 + 0.5 * 1.5 + 2.5 * choice.expected / tol) * tol
