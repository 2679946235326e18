"""A campaign on a real Dask cluster: `dask scheduler` and `dask worker` processes on
127.0.0.1 (loopback only), one worker killed mid-run; results identical to a local run on
1 worker (runs below a point: a prescan and a 3-way multisection). Other worker counts:
tests/test_task_contract.py."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
import xarray as xr

import frictiondisk
from frictiondisk.engine.runner import run_campaign
from frictiondisk.store.journal import Journal
from frictiondisk.tasks.campaign import campaign_from_text

REPO = Path(frictiondisk.__file__).resolve().parent.parent
START_TIMEOUT_S = 120.0  # scheduler and workers up (imports, on a busy machine)

# not-stick pin runs take ~0.1 s at this horizon: long enough to kill a worker mid-run
PIN_PRESCAN = """\
name: cluster_pin
scene: pin
numerics: {t_decide: 100.0}
find_jump:
  tol: 1.0e-4
  split: 3
  prescan:
    mu: {start: 0.04, stop: 0.3, num: 8}
  along:
    params.x_ms: {start: 0.06, stop: 0.14, num: 3}
"""


def _identical(dir_a: Path, dir_b: Path) -> None:
    with xr.open_dataset(dir_a / "results.nc") as a, xr.open_dataset(dir_b / "results.nc") as b:
        xr.testing.assert_identical(a.load(), b.load())
    with xr.open_dataset(dir_a / "runs.nc") as a, xr.open_dataset(dir_b / "runs.nc") as b:
        xr.testing.assert_identical(a.drop_vars("wall_s").load(), b.drop_vars("wall_s").load())


def _stop(procs: list[subprocess.Popen]) -> None:
    for proc in procs:
        if proc.poll() is None:
            proc.terminate()
    for proc in procs:
        try:
            proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=15)


@contextlib.contextmanager
def loopback_cluster(tmp_path: Path, n_workers: int):
    """A `dask scheduler` and n single-threaded `dask worker` processes (no nanny: a
    killed worker stays dead) on 127.0.0.1; yields (address, worker processes)."""
    from distributed import Client

    env = dict(
        os.environ, PYTHONPATH=os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")])
    )
    scheduler_file = tmp_path / "scheduler.json"
    dask = [sys.executable, "-m", "dask"]
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL, "env": env}
    procs = [
        subprocess.Popen(
            [
                *dask,
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--no-dashboard",
                "--scheduler-file",
                str(scheduler_file),
            ],
            **quiet,
        )
    ]
    try:
        deadline = time.monotonic() + START_TIMEOUT_S
        while not scheduler_file.exists():
            assert time.monotonic() < deadline, "dask scheduler did not start"
            assert procs[0].poll() is None, "dask scheduler exited"
            time.sleep(0.1)
        workers = [
            subprocess.Popen(
                [
                    *dask,
                    "worker",
                    "--scheduler-file",
                    str(scheduler_file),
                    "--host",
                    "127.0.0.1",
                    "--nthreads",
                    "1",
                    "--no-nanny",
                    "--no-dashboard",
                ],
                **quiet,
            )
            for _ in range(n_workers)
        ]
        procs += workers
        with Client(scheduler_file=str(scheduler_file), timeout=START_TIMEOUT_S) as client:
            client.wait_for_workers(n_workers, timeout=START_TIMEOUT_S)
            address = client.scheduler.address
        yield address, workers
    finally:
        _stop(procs)


@pytest.fixture(scope="module")
def local_reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("local") / "w1"
    run_campaign(campaign_from_text(PIN_PRESCAN, "<test>"), out, workers=1, progress=False)
    return out


def test_remote_scheduler_with_a_killed_worker_gives_the_local_results(local_reference, tmp_path):
    n_runs = len(Journal(local_reference))
    out = tmp_path / "remote"
    with loopback_cluster(tmp_path, n_workers=2) as (address, workers):
        errors: list[BaseException] = []

        def target():
            try:
                campaign = campaign_from_text(PIN_PRESCAN, "<test>")
                run_campaign(campaign, out, scheduler=address, progress=False)
            except BaseException as exc:  # surfaced below
                errors.append(exc)

        thread = threading.Thread(target=target)
        thread.start()
        deadline = time.monotonic() + START_TIMEOUT_S
        while len(Journal(out)) < 3 and thread.is_alive() and time.monotonic() < deadline:
            time.sleep(0.02)
        done_at_kill = len(Journal(out))
        assert thread.is_alive() and done_at_kill < n_runs, "the campaign ended before the kill"
        workers[0].send_signal(signal.SIGKILL)  # its tasks go to the other worker
        thread.join(timeout=300)
        assert not thread.is_alive(), "the campaign did not finish after the kill"
        assert workers[0].wait(timeout=10) == -signal.SIGKILL
    assert not errors, errors
    _identical(local_reference, out)
    assert max(Journal(out).computed_counts().values()) == 1


def test_two_local_clusters_at_once_never_fight_over_a_port():
    """Each local cluster's HTTP routes bind a free port: a second campaign started while
    another runs (or any other Dask on port 8787) gets no 'Port 8787 is already in use'."""
    import warnings

    import dask

    from frictiondisk.engine.cluster import start_client

    scheduler_before = dask.config.get("scheduler", None)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        first = start_client(1, None, False, False)
        second = start_client(1, None, False, False)
        for client, cluster in (second, first):  # last in, first out: as nested `with`s
            client.close()
            cluster.close()
    assert not [w for w in caught if "already in use" in str(w.message)]
    # each client restores the default scheduler it found, so the last closed leaves it
    # as it was (closed in another order, dask would keep "dask.distributed" with no
    # client behind it, and xarray's netCDF writes would fail)
    assert dask.config.get("scheduler", None) == scheduler_before
