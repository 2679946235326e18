"""The contract every registered task keeps with the engine (frictiondisk.tasks.protocol),
checked for each one on the real driver, journal and Dask workers, with a fake simulate
(tests/fake_simulate.py): deterministic verdicts in microseconds, no kernel (no numba
compile, no runs).

* stop and resume: a campaign stopped mid-way (the stop a signal handler notes) leaves
  its finished runs in the journal and a partial results.nc; a resume, also over a crash's
  leftovers (a torn temporary entry, a status.json still `running`), ends with the files
  of an uninterrupted run, and computes no journaled run again;
* worker count: 1 and 3 workers give identical results.nc and runs.nc (but wall times);
* failing jobs: a job whose worker keeps failing fails its points with the reason and
  journals nothing of it; a resume without the fault ends with the uninterrupted files.

A task without a journal (its files are its record: a trajectory) keeps the same promises
its own way (test_a_task_without_a_journal_keeps_its_files_as_its_record).

One end-to-end smoke test per task runs the real kernel (test_campaign_run.py,
test_basin_run.py, test_map_run.py, test_trace_campaign.py, test_trajectory_campaign.py, and for scan
test_campaign_run.py::test_scan_shows_the_jump_in_size).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from fake_simulate import install

from frictiondisk.engine import runner
from frictiondisk.engine.runner import run_campaign
from frictiondisk.engine.signals import CampaignInterrupted
from frictiondisk.store.journal import Journal
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.registry import TASKS

# One small campaign per registered task (and variants that take other paths through a
# planner: a find_jump with a prescan runs JumpSearch chains and batches).
CAMPAIGNS = {
    "find_jump": """\
name: contract_line
scene: pin
find_jump:
  bracket: [0.03, 0.4]
  tol: 1.0e-4
  lanes: 2
  along: {params.x_ms: {start: 0.06, stop: 0.14, num: 5}}
""",
    "find_jump_prescan": """\
name: contract_prescan
scene: pin
find_jump:
  tol: 1.0e-4
  split: 3
  prescan: {mu: {start: 0.03, stop: 0.3, num: 10}}
  along: {params.x_ms: [0.06, 0.1, 0.14], params.x0: [0.0, 0.04]}
""",
    "scan": """\
name: contract_scan
scene: pin
scan:
  mu: {start: 0.05, stop: 0.2, num: 7}
  along: {params.x_ms: [0.06, 0.1]}
""",
    "basin": """\
name: contract_basin
scene: pin
params: {x_ms: 0.1}
basin:
  sample: {params.x0: {uniform: [-0.2, 0.2]}}
  target_se: 0.08
  max_samples: 60
  batch: 10
  seed: 3
  along: {params.mu: [0.14, 0.16]}
""",
    "trace": """\
name: contract_trace
scene: pin
trace:
  key: params.x_ms
  range: [0.05, 0.15]
  mu: [0.03, 0.3]
  tol: 1.0e-3
  resolution: 0.25
  first_look: {keys: 2, mu: 8}
""",
    "map": """\
name: contract_map
scene: pin
params: {x_ms: 0.1}
map:
  over: {params.mu: {start: 0.06, stop: 0.2, num: 8}, params.x0: [-0.1, 0.0, 0.1]}
  mode: decide
  stride: 4
""",
    "trajectory": """\
name: contract_orbit
scene: pin
params: {mu: 0.11}
trajectory: {dt_out: 0.5}
""",
}
JOURNALED = sorted(name for name in CAMPAIGNS if TASKS[name.split("_prescan")[0]].journaled)
WARM_UP_RUNS = 2  # engine.worker.warm_up: a pin and a disk


@pytest.fixture
def fake(monkeypatch):
    """Install a FakeSimulate for this test (workers run in this process: threads)."""
    return lambda **kwargs: install(monkeypatch, **kwargs)


def campaign(name: str):
    return campaign_from_text(CAMPAIGNS[name], "<contract>")


def files_of(out: Path) -> dict[str, xr.Dataset]:
    """results.nc and runs.nc, loaded; wall times and volatile attributes left out."""
    found = {}
    for name in ("results.nc", "runs.nc"):
        with xr.open_dataset(out / name) as ds:
            ds = ds.load().drop_vars([v for v in ("wall_s",) if v in ds.variables])
        ds.attrs.pop("history", None)
        found[name] = ds
    return found


def assert_same_files(a: Path, b: Path) -> None:
    for name, ds in files_of(a).items():
        xr.testing.assert_identical(ds, files_of(b)[name])


@pytest.fixture(scope="module")
def references(tmp_path_factory):
    """Each journaled campaign run uninterrupted on 1 worker, and its run count."""
    root = tmp_path_factory.mktemp("contract")
    mp = pytest.MonkeyPatch()
    simulate = install(mp)
    found = {}
    try:
        for name in JOURNALED:
            out = root / name
            before = simulate.runs
            run_campaign(campaign(name), out, workers=1, progress=False)
            found[name] = (out, simulate.runs - before)
    finally:
        mp.undo()
    return found


def test_every_registered_task_has_a_contract_campaign():
    assert {name.split("_prescan")[0] for name in CAMPAIGNS} == set(TASKS)


@pytest.mark.parametrize("name", JOURNALED)
def test_more_workers_give_identical_files(name, references, fake, tmp_path):
    reference, _ = references[name]
    fake()
    run_campaign(campaign(name), tmp_path, workers=3, progress=False)
    assert_same_files(reference, tmp_path)


@pytest.mark.parametrize("name", JOURNALED)
def test_a_stopped_campaign_resumes_to_the_uninterrupted_files(name, references, fake, tmp_path):
    reference, runs = references[name]
    fake(stop_after=WARM_UP_RUNS + 5)  # on one worker: two jobs in flight, then none
    with pytest.raises(CampaignInterrupted) as stop:
        run_campaign(campaign(name), tmp_path, workers=1, progress=False)
    journaled = len(Journal(tmp_path))
    assert 0 < journaled < runs
    # every run finished before the stop is journaled, those of the jobs in flight too
    assert f"interrupted; {journaled} finished runs are in the journal" in str(stop.value)
    with xr.open_dataset(tmp_path / "results.nc") as partial:
        assert partial.attrs["partial"] == 1
    # a crash's leftovers besides: a torn temporary entry, a status still `running`
    (tmp_path / "journal" / "00").mkdir(exist_ok=True)
    (tmp_path / "journal" / "00" / ".torn.json.tmp").write_text('{"version": 1, "ke')
    status = json.loads((tmp_path / "status.json").read_text())
    (tmp_path / "status.json").write_text(json.dumps({**status, "state": "running"}))
    fake()
    summary = run_campaign(None, tmp_path, workers=2, progress=False)
    assert summary.runs_computed == summary.runs_total - journaled
    assert_same_files(reference, tmp_path)
    assert max(Journal(tmp_path).computed_counts().values()) == 1  # none computed twice
    assert not list((tmp_path / "journal").glob("??/.*.tmp"))


FAULTS = {  # the runs whose worker keeps crashing (none of engine.worker.warm_up's scenes)
    "find_jump": lambda p, record: abs(p["x_ms"] - 0.08) < 1e-9,
    "find_jump_prescan": lambda p, record: p["x_ms"] == 0.14 and p["x0"] == 0.04,
    "scan": lambda p, record: p["x_ms"] == 0.06 and p["mu"] > 0.12,
    "basin": lambda p, record: p["mu"] == 0.16,
    "trace": lambda p, record: 0.11 < p["x_ms"] < 0.13,
    "map": lambda p, record: p["mu"] > 0.19 and p["x0"] == 0.1,
}


@pytest.mark.parametrize("name", JOURNALED)
def test_a_job_that_keeps_failing_loses_no_run_and_invents_none(name, references, fake, tmp_path):
    reference, _ = references[name]
    fails = FAULTS[name]
    fake(fails=fails)
    summary = run_campaign(campaign(name), tmp_path, workers=1, progress=False)
    # the task says which points failed, and why (a scan's point is `undetermined`)
    with xr.open_dataset(tmp_path / "results.nc") as results:
        reasons = results["reason"].values if "reason" in results else []
        text = " ".join(map(str, np.ravel(reasons))) + str(results.attrs.get("reason", ""))
        outcomes = str(results["outcome"].values) if "outcome" in results else ""
    assert "worker failed 4 times" in text and "fake worker crash" in text, text
    assert summary.points_failed >= 1 or "undetermined" in outcomes
    # nothing of a failing run is journaled
    journal = Journal(tmp_path)
    for key in journal.keys():
        entry = journal.entry(key)
        assert not fails(entry["inputs"]["params"], False), entry["inputs"]["params"]
    fake()  # the fault is gone: a resume ends where an uninterrupted run does
    run_campaign(None, tmp_path, workers=1, progress=False)
    assert_same_files(reference, tmp_path)


def test_a_run_that_keeps_failing_fails_alone_in_its_batch(fake, tmp_path):
    """A failed batch is cut in halves until the failing runs stand alone: only their
    points fail (the fake claims 0.1 s a run, so the driver batches them by two or more)."""
    fails = FAULTS["scan"]
    fake(fails=fails)
    run_campaign(campaign("scan"), tmp_path, workers=1, progress=False)
    with xr.open_dataset(tmp_path / "results.nc") as results:
        mu, x_ms = np.meshgrid(results["mu"], results["x_ms"], indexing="ij")
        failed = np.char.find(results["reason"].values.astype(str), "worker failed") >= 0
    expected = np.vectorize(lambda m, x: fails({"mu": m, "x_ms": x}, False))(mu, x_ms)
    assert expected.sum() == 4
    np.testing.assert_array_equal(failed, expected)
    assert len(Journal(tmp_path)) == expected.size - expected.sum()


def test_a_job_whose_worker_fails_now_and_then_is_retried(references, fake, tmp_path):
    """A job that fails (its worker died) is submitted again, up to MAX_WORKER_FAILURES
    times; one that then succeeds leaves the files of a run without failures."""
    reference, _ = references["find_jump"]
    failed: set[tuple] = set()

    def first_time(params, record):
        key = (params["x_ms"], params["mu"])
        fails = abs(params["x_ms"] - 0.12) < 1e-9 and key not in failed
        failed.add(key)
        return fails

    fake(fails=first_time)
    summary = run_campaign(campaign("find_jump"), tmp_path, workers=1, progress=False)
    assert failed and summary.points_failed == 0
    assert_same_files(reference, tmp_path)


def test_a_task_without_a_journal_keeps_its_files_as_its_record(fake, tmp_path):
    """A trajectory: run alone it runs here; run again it recomputes nothing while its
    files are whole, and recomputes a damaged one; beside another campaign it is one job
    on the workers, whose failure writes nothing (a resume runs it)."""
    assert not TASKS["trajectory"].journaled
    simulate = fake()
    alone = tmp_path / "alone"
    assert run_campaign(campaign("trajectory"), alone, progress=False).runs_computed == 1
    assert run_campaign(None, alone, progress=False).runs_computed == 0
    (alone / "trajectory.nc").write_bytes(b"torn")
    assert run_campaign(None, alone, progress=False).runs_computed == 1
    assert simulate.runs == 2
    together = tmp_path / "together"
    line = campaign("find_jump")
    fake(fails=lambda p, record: record)
    first = runner.run_campaigns([campaign("trajectory"), line], together, 2, progress=False)
    assert first[0].points_failed == 1 and not (together / "contract_orbit" / "results.nc").exists()
    fake()
    again = runner.run_campaigns(None, together, 2, progress=False)
    assert again[0].runs_computed == 1
    for name in ("results.nc", "trajectory.nc"):
        with (
            xr.open_dataset(alone / name) as a,
            xr.open_dataset(together / "contract_orbit" / name) as b,
        ):
            xr.testing.assert_equal(a.load(), b.load())
