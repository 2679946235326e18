"""find_jump and scan campaigns end to end (the tasks' smoke tests; their contract with the
engine, stop and resume, worker counts and failing jobs, is tests/test_task_contract.py):
located jumps against physics, corruption repair, refusals, a scan's sizes."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
import xarray as xr
from click.testing import CliRunner
from conftest import coulomb_mu_star

from frictiondisk.cli import main
from frictiondisk.engine.runner import run_campaign
from frictiondisk.store.journal import Journal
from frictiondisk.store.lock import CampaignLock
from frictiondisk.tasks.campaign import campaign_from_text

# The bracket's low end is no x_ms of the lines below: at mu = c_s x_ms / F_n exactly
# the pin creeps onto the master axis and sticks there (an isolated sticking value).
PIN_LINE = """\
name: pin_line
scene: pin
numerics: {{t_decide: 20.0}}
find_jump:
  bracket: [0.045, 0.3]
  tol: 1.0e-4
  lanes: {lanes}
  along:
    params.x_ms: {values}
"""

# Disk runs take tens of milliseconds: slow enough to interrupt a campaign mid-way.
DISK_LINE = """\
name: disk_line
scene: disk
params: {phidot0: 1.1}
contact: {points: 6}
numerics: {t_decide: 15.0}
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-3
  along:
    params.x_ms: {start: 0.04, stop: 0.14, num: 6}
"""


def pin_line(values, lanes=2):
    return campaign_from_text(PIN_LINE.format(values=values, lanes=lanes), "<test>")


def _identical(dir_a: Path, dir_b: Path) -> None:
    with xr.open_dataset(dir_a / "results.nc") as a, xr.open_dataset(dir_b / "results.nc") as b:
        xr.testing.assert_identical(a.load(), b.load())
    with xr.open_dataset(dir_a / "runs.nc") as a, xr.open_dataset(dir_b / "runs.nc") as b:
        xr.testing.assert_identical(a.drop_vars("wall_s").load(), b.drop_vars("wall_s").load())


def test_pin_jump_satisfies_the_sticking_circle_oracle(tmp_path):
    run_campaign(pin_line("[0.1]"), tmp_path, workers=1, progress=False)
    with xr.open_dataset(tmp_path / "results.nc") as ds:
        lo, hi = float(ds.mu_lo[0]), float(ds.mu_hi[0])
        r1 = float(ds.R1_hi[0])
        assert ds.status.values[0] == "converged"
        assert ds.outcome_hi.values[0] == "stick"
        assert ds.outcome_lo.values[0] in ("stick_slip", "slide")
        assert ds.mu_star.attrs["long_name"] and ds.x_ms.attrs["units"] == "m"
    assert hi - lo <= 1e-4 * (1 + 1e-9)
    oracle = coulomb_mu_star(r1)  # c_s x_ms + g R1 (docs/model.md section 6)
    assert lo - 2e-5 < oracle <= hi + 2e-5


def test_jump_scales_with_the_offset(tmp_path):
    run_campaign(pin_line("[0.05, 0.1]"), tmp_path, workers=2, progress=False)
    with xr.open_dataset(tmp_path / "results.nc") as ds:
        lo, hi = ds.mu_lo.values, ds.mu_hi.values
    # mu*(0.1) = 2 mu*(0.05): the intervals [lo2, hi2] and 2 [lo1, hi1] overlap
    assert max(lo[1], 2 * lo[0]) <= min(hi[1], 2 * hi[0])


def _cli(*args, env=None):
    return subprocess.Popen(
        [sys.executable, "-m", "frictiondisk.cli", *map(str, args)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
    )


def _wait_for_entries(journal_dir: Path, count: int, proc, timeout=300.0) -> bool:
    """Wait until the journal holds `count` entries (True), the process ends or `timeout`
    s pass (False); the timeout only bounds a hang, a busy machine just takes longer."""
    t0 = time.time()
    while time.time() - t0 < timeout and proc.poll() is None:
        n = sum(1 for _ in journal_dir.glob("*/*.json")) if journal_dir.exists() else 0
        if n >= count:
            return True
        time.sleep(0.02)
    return False


def test_corrupted_entry_and_truncated_results_are_repaired(tmp_path):
    campaign = pin_line("[0.08, 0.1]")
    run_campaign(campaign, tmp_path / "reference", workers=1, progress=False)
    out = tmp_path / "out"
    run_campaign(campaign, out, workers=1, progress=False)
    entry = sorted((out / "journal").glob("*/*.json"))[3]
    text = entry.read_text()
    entry.write_text(text.replace('"stick', '"stuck', 1) if '"stick' in text else text[:-20])
    results = out / "results.nc"
    results.write_bytes(results.read_bytes()[: results.stat().st_size // 2])

    status = CliRunner().invoke(main, ["status", str(out)])
    assert "damaged" in status.output

    summary = run_campaign(None, out, workers=1, progress=False)
    assert summary.runs_computed == 1  # only the corrupted run
    assert Journal(out).n_corrupt == 0  # a fresh journal object sees a clean journal
    assert (out / "journal" / "corrupt").is_dir()
    _identical(tmp_path / "reference", out)
    status = CliRunner().invoke(main, ["status", str(out)])
    assert "complete" in status.output


def test_second_run_on_a_locked_directory_is_refused(tmp_path):
    campaign_file = tmp_path / "c.yaml"
    campaign_file.write_text(PIN_LINE.format(values="[0.1]", lanes=2))
    out = tmp_path / "out"
    out.mkdir()
    with CampaignLock(out):
        result = CliRunner().invoke(main, ["run", str(campaign_file), "-o", str(out)])
    assert result.exit_code == 3
    assert str(os.getpid()) in result.output


def test_resuming_with_a_changed_campaign_names_the_difference(tmp_path):
    campaign_file = tmp_path / "c.yaml"
    campaign_file.write_text(PIN_LINE.format(values="[0.1]", lanes=2))
    out = tmp_path / "out"
    assert CliRunner().invoke(main, ["run", str(campaign_file), "-o", str(out)]).exit_code == 0
    campaign_file.write_text(PIN_LINE.format(values="[0.1]", lanes=2).replace("1.0e-4", "2.0e-4"))
    result = CliRunner().invoke(main, ["run", str(campaign_file), "-o", str(out)])
    assert result.exit_code == 2
    assert "find_jump.tol" in result.output


@pytest.mark.parametrize(
    "edit, path",
    [
        (
            lambda t: t.replace("tol: 1.0e-4", "tol: 1.0e-4\n  frobnicate: 1"),
            "find_jump.frobnicate",
        ),
        (lambda t: t.replace("[0.045, 0.3]", "[0.3, 0.045]"), "find_jump.bracket"),
        (lambda t: t.replace("tol: 1.0e-4", "tol: 0"), "find_jump.tol"),
        (lambda t: t.replace("tol: 1.0e-4", "tol: .nan"), "find_jump.tol"),
        (lambda t: t.replace("params.x_ms", "params.nope"), "params.nope"),
    ],
)
def test_bad_campaign_files_exit_2_naming_the_path(tmp_path, edit, path):
    campaign_file = tmp_path / "c.yaml"
    campaign_file.write_text(edit(PIN_LINE.format(values="[0.1]", lanes=2)))
    result = CliRunner().invoke(main, ["run", str(campaign_file), "-o", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert path in result.output
    assert "Traceback" not in result.output


def test_scan_shows_the_jump_in_size(tmp_path):
    text = """\
name: pin_scan
scene: pin
numerics: {t_max: 2000.0}
scan:
  mu: [0.124, 0.126, 0.128]
"""
    run_campaign(campaign_from_text(text, "<test>"), tmp_path, workers=2, progress=False)
    with xr.open_dataset(tmp_path / "results.nc") as ds:
        assert ds.mu.attrs["scene_key"] == "params.mu"
        assert list(ds.outcome.values) == ["stick_slip", "stick_slip", "stick"]
        assert ds.cycle_converged.values[:2].all()
        size = ds["size"].values
        # the outer cycle is far larger than the sticking circle: the jump of docs/model.md section 7
        assert size[0] < size[1] and size[1] > 2 * size[2]
        assert ds["a"].values[1] > ds["a"].values[0] > 0  # a grows with mu (paper Fig. 6)
        assert ds["size"].attrs["units"] == "m"
