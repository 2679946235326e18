"""The trace task end to end on the pin (cheap runs; its contract with the engine is
tests/test_task_contract.py): the jump line mu* = 1.26723 x_ms traced within 2 tol,
brackets that simulate true, the files, status and figure; and a Stribeck pin whose gap
between two jumps closes in a fold, located and checked by simulation."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.engine.runner import run_campaign
from frictiondisk.model.scene import ConfigError
from frictiondisk.simulation.simulate import simulate
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.jump_search.bisection import STICK, RunRequest
from frictiondisk.tasks.jump_search.requests import run_config
from frictiondisk.tasks.trace.planner import TracePlanner

# docs/model.md section 7: line campaigns at rtol 1e-10 give mu* = 1.2672345 x_ms to 2e-8
# over x_ms = 0.06 ... 0.14 (issue 31)
SLOPE = 1.26723
PIN = """\
name: trace_pin
scene: pin
trace:
  key: params.x_ms
  range: [0.05, 0.15]
  mu: [0.03, 0.25]
  tol: 1.0e-4
  resolution: 0.25
  first_look: {keys: 2, mu: 12}
"""
# a gap (stick_slip between the sticking window and the main jump) that closes towards
# smaller r, near r = 0.7906, mu = 0.1127 (docs/trace.md)
STRIBECK = """\
name: trace_stribeck_gap
scene: pin
contact:
  stribeck: {r: 0.8, v_s: 0.03}
trace:
  key: contact.stribeck.r
  range: [0.786, 0.80]
  mu: [0.1115, 0.1135]
  tol: 2.0e-5
  resolution: 0.15
  first_look: {keys: 2, mu: 21, stride: 1}
"""


def run_here(campaign) -> TracePlanner:
    """The campaign's planner driven here, one run after the other (no Dask, no journal)."""
    planner = TracePlanner(campaign)
    while not planner.done:
        for i, request in planner.requests():
            planner.feed(i, request, simulate(planner.config_for(i, request)).summary())
    return planner


def sticks_at(campaign, key: float, mu: float, strict: int = 0) -> bool:
    task = campaign.task
    scene = campaign.base.with_overrides({task.key: key})
    config = run_config(scene, RunRequest(mu, strict=strict), task.horizon_factor, task.certify)
    return simulate(config).outcome == STICK


@pytest.fixture(scope="module")
def pin(tmp_path_factory):
    campaign = campaign_from_text(PIN, "<test>")
    out = tmp_path_factory.mktemp("trace") / "pin"
    summary = run_campaign(campaign, out, 2, None, False, progress=False)
    return campaign, out, summary


def test_the_pin_jump_line_is_traced_within_two_tol(pin):
    campaign, out, _ = pin
    with xr.open_dataset(out / "results.nc") as ds:
        assert ds.attrs["status"] == "converged", ds.attrs["reason"]
        assert ds.sizes["curve"] == 1 and ds.sizes["fold"] == 0
        assert list(ds["curve_first_end"].values) == ["edge"] == list(ds["curve_last_end"].values)
        x_ms, mu = ds["x_ms"].values, ds["mu_star"].values
        assert x_ms.min() == 0.05 and x_ms.max() == 0.15  # edge to edge
        assert (ds["bisected"].values == 0).all() and (ds["rising"].values == 1).all()
        assert (ds["mu_hi"] - ds["mu_lo"]).max() <= 1e-4 * (1 + 1e-9)
        error = np.abs(mu - SLOPE * x_ms)
        assert error.max() <= 2e-4, error
        flags = ds["certification"].attrs["flag_meanings"].split()
        assert {flags[int(v) + 1] for v in ds["certification"].values} == {"certified"}


def test_traced_brackets_are_true_brackets(pin):
    """At a sample of points: mu_lo does not stick and mu_hi sticks, at the key of the
    point and the numerics behind its bracket."""
    campaign, out, _ = pin
    with xr.open_dataset(out / "results.nc") as ds:
        rows = [
            (
                float(ds["x_ms"][i]),
                float(ds["mu_lo"][i]),
                float(ds["mu_hi"][i]),
                int(ds["strict"][i]),
            )
            for i in (0, ds.sizes["point"] // 2, ds.sizes["point"] - 1)
        ]
    for key, lo, hi, strict in rows:
        assert not sticks_at(campaign, key, lo, strict)
        assert sticks_at(campaign, key, hi, strict)


def test_a_partial_trace_writes_the_curves_found_so_far(pin):
    campaign, _, _ = pin
    planner = TracePlanner(campaign)
    while planner.progress()[0] < 3:  # the first look and a correction or two
        for i, request in planner.requests()[:1]:
            planner.feed(i, request, simulate(planner.config_for(i, request)).summary())
    assert not planner.done
    ds = planner.snapshot().to_dataset()
    assert ds.attrs["status"] == "pending" and ds.sizes["point"] >= 2


def test_runs_nc_status_and_plot(pin, tmp_path):
    campaign, out, summary = pin
    with xr.open_dataset(out / "runs.nc") as runs:
        assert runs.sizes["run"] == summary.runs_total
        assert set(runs["purpose"].values) == {"first_look", "curve"}
        assert set(runs["role"].values) == {"prescan", "search", "certification"}
    status = CliRunner().invoke(main, ["status", str(out)])
    assert status.exit_code == 0, status.output
    assert "curves of the plane (params.x_ms, mu)" in status.output
    assert "edge / edge" in status.output
    figure = tmp_path / "trace.png"
    plotted = CliRunner().invoke(main, ["plot", str(out), "--runs", "-o", str(figure)])
    assert plotted.exit_code == 0, plotted.output
    assert figure.stat().st_size > 10_000


def test_bad_trace_files_name_every_problem_at_once():
    text = (
        PIN.replace("key: params.x_ms", "key: params.mu")
        .replace("tol: 1.0e-4", "tol: 0.5")
        .replace("resolution: 0.25", "resolution: 0.25\n  min_step: 0.5\n  color: red")
    )
    with pytest.raises(ConfigError) as err:
        campaign_from_text(text, "<test>")
    lines = err.value.problems
    assert "trace.color: unknown key; allowed keys under trace: key, range, mu," in lines[0]
    assert any(line.startswith("trace.key: params.mu is the plane's second axis") for line in lines)
    assert any(
        line.startswith("trace.tol: 0.5 is out of range: must be > 0 and < high - low = 0.22")
        for line in lines
    )
    assert any(
        line.startswith("trace.min_step: 0.5 is out of range: must be > 0 and <= resolution")
        for line in lines
    )
    bad_range = PIN.replace("range: [0.05, 0.15]", "range: [0.05, 1.0e9]")
    with pytest.raises(ConfigError) as err:
        campaign_from_text(bad_range, "<test>")
    assert any(line.startswith("trace.range[1]: ") for line in err.value.problems)


def test_a_stribeck_gap_s_fold_is_located_and_true():
    """The gap closes in one fold, certified, its key to the key's tolerance and its mu to
    tol; simulation confirms it: at key_in the gap is there (its centre does not stick,
    both jumps' outer ends stick), at key_out (beyond the tip) the centre sticks."""
    campaign = campaign_from_text(STRIBECK, "<test>")
    planner = run_here(campaign)
    result = planner.results[0]
    assert result.status == "converged", result.reason
    (curve,) = result.curves  # the gap's two jumps: one curve round the tip
    assert curve.ends == {+1: "edge", -1: "edge"}
    ((_, fold),) = result.folds
    assert fold.status == "located" and not fold.inner_sticks
    assert fold.certification in ("certified", "recertified")
    key_tol = 2e-5 * (0.80 - 0.786) / (0.1135 - 0.1115)
    assert abs(fold.key_out - fold.key_in) <= key_tol * (1 + 1e-9)
    assert fold.upper.lo - fold.lower.hi <= 2e-5 and fold.mu_hi - fold.mu_lo <= 3 * 2e-5
    assert 0.788 < fold.key < 0.793 and 0.1125 < fold.mu < 0.1129  # where the scans put it
    assert not sticks_at(campaign, fold.key_in, fold.mu)
    assert sticks_at(campaign, fold.key_in, fold.lower.lo)
    assert sticks_at(campaign, fold.key_in, fold.upper.hi)
    assert sticks_at(campaign, fold.key_out, fold.mu)
