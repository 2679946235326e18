"""Several campaigns in one process (`run A.yaml B.yaml -o DIR`, run_campaigns): each into
DIR/<name>/ with the files it gets on its own, runs scheduled together on one client, a
SIGTERM that stops them all gracefully, and a resume that ends where an uninterrupted run
does; `status` and `resume` of the folder; the refusals. The engine's promises, on the
fake simulate (tests/fake_simulate.py)."""

from __future__ import annotations

import signal

import pytest
import xarray as xr
from click.testing import CliRunner
from conftest import HANG_S, points_done, start_campaign_until
from fake_simulate import install

from frictiondisk import run_campaigns
from frictiondisk.cli import main
from frictiondisk.engine.runner import _partial_note, run_campaign
from frictiondisk.tasks.campaign import campaign_from_text

PIN = """\
name: {name}
scene: pin
numerics: {{t_decide: 8.0}}
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-3
  along: {{params.x_ms: {values}}}
"""
ORBIT = """\
name: orbit
scene: pin
params: {mu: 0.12}
numerics: {t_decide: 5.0}
trajectory: {dt_out: 0.1}
"""
SCAN = """\
name: sizes
scene: pin
numerics: {t_decide: 5.0}
scan: {mu: [0.1, 0.2]}
"""
# a trace: its progress counts curve points, its files are built by tasks/trace/datasets.py
TRACE = """\
name: traced
scene: pin
numerics: {t_decide: 8.0}
trace:
  key: params.x_ms
  range: [0.08, 0.12]
  mu: [0.05, 0.25]
  tol: 1.0e-3
  resolution: 0.5
  first_look: {keys: 2, mu: 6}
"""
# 12 points at tol 1e-8, one in flight at a time: long enough to stop both (runs of 20 ms on
# the fake simulate)
LONG = """\
name: {name}
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-8
  lanes: 1
  along: {{params.x_ms: {{start: {start}, stop: {stop}, num: 12}}}}
"""


def _campaigns():
    texts = [
        PIN.format(name="first", values="[0.08, 0.1]"),
        PIN.format(name="second", values="[0.06, 0.12]"),
        ORBIT,
        SCAN,
        TRACE,
    ]
    return [campaign_from_text(text, "<test>") for text in texts]


def _same_files(dir_a, dir_b, names=("results.nc", "runs.nc")) -> None:
    for name in names:
        with xr.open_dataset(dir_a / name) as a, xr.open_dataset(dir_b / name) as b:
            xr.testing.assert_identical(_untimed(a.load()), _untimed(b.load()))


def _untimed(ds: xr.Dataset) -> xr.Dataset:
    """ds without its wall times, which differ from run to run."""
    ds = ds.drop_vars("wall_s", errors="ignore")
    ds.attrs.pop("wall_s", None)
    return ds


def test_campaigns_run_together_write_what_each_writes_on_its_own(tmp_path, monkeypatch):
    """Every task among them (on the fake simulate: this is the engine's promise, the
    kernel's runs are the tasks' smoke tests)."""
    install(monkeypatch)
    campaigns = _campaigns()
    summaries = run_campaigns(campaigns, tmp_path / "together")
    assert [s.results.parent.name for s in summaries] == [c.name for c in campaigns]
    for campaign in campaigns:
        alone = tmp_path / "alone" / campaign.name
        run_campaign(campaign, alone, progress=False)
        files = ("results.nc", "trajectory.nc" if campaign.kind == "trajectory" else "runs.nc")
        _same_files(tmp_path / "together" / campaign.name, alone, files)
    # each finished when its own last point did, and none after the whole run
    assert all(0 < s.wall_s <= max(x.wall_s for x in summaries) for s in summaries)

    again = run_campaigns(None, tmp_path / "together")  # resume: all from the journals
    assert [s.runs_computed for s in again] == [0] * len(campaigns)

    status = CliRunner().invoke(main, ["status", str(tmp_path / "together")])
    assert status.exit_code == 0, status.output
    assert "5 campaigns: first, second, orbit, sizes, traced" in status.output
    assert status.output.count("state:     complete") == 5


def test_two_campaigns_of_one_name_and_mixed_folders_are_refused(tmp_path):
    a = tmp_path / "a.yaml"
    a.write_text(PIN.format(name="same", values="[0.1]"))
    b = tmp_path / "b.yaml"
    b.write_text(PIN.format(name="same", values="[0.12]"))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["run", str(a), str(b), "-o", str(out)])
    assert result.exit_code == 2
    assert "name: 'same' is the name of 2 of the campaigns" in result.output
    assert not out.exists()  # nothing was written

    single = tmp_path / "single"
    assert CliRunner().invoke(main, ["run", str(a), "-o", str(single)]).exit_code == 0
    b.write_text(PIN.format(name="other", values="[0.12]"))
    result = CliRunner().invoke(main, ["run", str(a), str(b), "-o", str(single)])
    assert result.exit_code == 2 and "holds a single campaign" in result.output

    folder = tmp_path / "folder"
    assert CliRunner().invoke(main, ["run", str(a), str(b), "-o", str(folder)]).exit_code == 0
    result = CliRunner().invoke(main, ["run", str(a), "-o", str(folder)])
    assert result.exit_code == 2 and "holds several campaigns" in result.output
    assert not (folder / "campaign.yaml").exists()


def _folder_points(out, names) -> list[int]:
    return [points_done(out / name) for name in names]


@pytest.fixture(scope="module")
def long_pair(tmp_path_factory):
    """Two long campaigns' files and the folder an uninterrupted run of both writes."""
    root = tmp_path_factory.mktemp("pair")
    specs = []
    for name, start, stop in (("left", 0.05, 0.1), ("right", 0.1, 0.15)):
        spec = root / f"{name}.yaml"
        spec.write_text(LONG.format(name=name, start=start, stop=stop))
        specs.append(spec)
    whole = root / "whole"
    with pytest.MonkeyPatch.context() as mp:
        install(mp)  # on the fake simulate, as the stopped run below
        result = CliRunner().invoke(main, ["run", *map(str, specs), "-o", str(whole)])
    assert result.exit_code == 0, result.output
    return specs, whole


def test_sigterm_stops_every_campaign_and_resume_finishes_them_identically(
    long_pair, tmp_path, monkeypatch
):
    """On the fake simulate (tests/fake_cli.py: the real command line, driver and journal)."""
    specs, whole = long_pair
    names = ["left", "right"]
    out = tmp_path / "stopped"
    started = lambda: min(_folder_points(out, names)) >= 1  # noqa: E731
    proc = start_campaign_until(specs, out, until=started, fake_delay=0.02)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=HANG_S)
    assert proc.returncode == 143, err
    assert "terminated" in err and f"frictiondisk resume {out}" in err

    for name in names:  # each stopped with its finished points in a partial results.nc
        with xr.open_dataset(out / name / "results.nc") as part:
            assert part.attrs["partial"] == 1
            done = part["status"].values != "pending"
            assert 1 <= done.sum() < done.size
    status = CliRunner().invoke(main, ["status", str(out)])
    assert status.exit_code == 0, status.output
    assert status.output.count("state:     interrupted") == 2

    install(monkeypatch)
    resumed = CliRunner().invoke(main, ["resume", str(out)])
    assert resumed.exit_code == 0, resumed.output
    assert "all 2 campaigns done" in resumed.output
    for name in names:
        with xr.open_dataset(out / name / "results.nc") as a:
            assert "partial" not in a.attrs
        _same_files(out / name, whole / name)


def test_a_stop_says_where_the_partial_results_are():
    """A stopped run names the partial results.nc of its campaigns, also those written
    before their first point was finished (every point pending)."""
    assert _partial_note({}, 1) == ""
    assert _partial_note({"a": 3}, 1) == ", the 3 finished points in results.nc (partial)"
    assert _partial_note({"a": 0}, 1) == (
        "; no point is finished yet (results.nc: every point pending)"
    )
    assert _partial_note({"a": 2, "b": 0}, 2) == (
        ", the finished points in each campaign's results.nc (partial: a 2, b 0)"
    )
    assert _partial_note({"a": 0, "b": 0}, 2) == (
        "; no point is finished yet (each campaign's results.nc: every point pending)"
    )
