"""A campaign stopped by a real signal: a documented exit code, the finished points in a
partial results.nc that `status` prints, and a resume that completes them, the finished
points as they were (that a resume ends where an uninterrupted run does, for every task:
tests/test_task_contract.py). The campaigns run on the fake simulate (tests/fake_cli.py:
the real command line, signal handlers, driver and journal; runs of 20 ms instead of the
kernel's), but for a trajectory's one run, which must sit in the kernel."""

import json
import signal
import subprocess
import time

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner
from conftest import (
    HANG_S,
    LONG_CAMPAIGN,
    cli_command,
    points_done,
    start_campaign_until,
    wait_for_cpu,
)
from fake_simulate import install

from frictiondisk.cli import main

CAMPAIGN = LONG_CAMPAIGN
FAKE_RUN_S = 0.02  # [s] a fake run: the 48 points take seconds, time enough to stop them


@pytest.fixture
def spec(tmp_path):
    path = tmp_path / "c.yaml"
    path.write_text(CAMPAIGN)
    return path


def test_a_stopped_campaign_keeps_its_finished_points_and_resumes(spec, tmp_path, monkeypatch):
    """SIGTERM (a batch scheduler, `kill`); Ctrl-C and SIGHUP take the same path to their
    own exit codes (signals.describe_stop, and test_a_closed_terminal_... below)."""
    out = tmp_path / "stopped"
    proc = start_campaign_until(spec, out, fake_delay=FAKE_RUN_S)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=HANG_S)
    assert proc.returncode == 143, err
    assert "terminated" in err and "frictiondisk resume" in err
    assert "Ctrl-C again" not in err, err  # a drain notice names the signal that was sent

    with xr.open_dataset(out / "results.nc") as part:
        part = part.load()
    assert part.attrs["partial"] == 1
    done = part["status"].values != "pending"
    assert part.attrs["points_done"] == done.sum() >= 2
    assert (~done).any()  # stopped before the end
    assert np.isnan(part["mu_star"].values[~done]).all()
    assert set(part["certification"].values[~done]) == {-1}  # flag "pending"

    status = CliRunner().invoke(main, ["status", str(out)])
    assert status.exit_code == 0, status.output
    assert "(partial: " in status.output and "pending" in status.output
    assert "mu* per point" in status.output

    install(monkeypatch)  # the same fake here, without its delay
    resumed = CliRunner().invoke(main, ["resume", str(out)])
    assert resumed.exit_code == 0, resumed.output
    with xr.open_dataset(out / "results.nc") as whole:
        assert "partial" not in whole.attrs
        assert "pending" not in set(whole["status"].values)
        # every finished point is the point the whole campaign has
        np.testing.assert_array_equal(part["mu_star"].values[done], whole["mu_star"].values[done])


# a disk from rest, prescanned: a point takes a dozen runs (of 0.3 s on the fake)
SLOW_DISK = """\
name: slow_disk
scene: disk
params: {phidot0: 0.0}
find_jump:
  tol: 1.0e-4
  prescan: {mu: {start: 0.05, stop: 0.3, num: 12}}
  along: {params.x_ms: [0.08, 0.1, 0.12]}
"""


def test_a_stop_before_the_first_point_leaves_every_point_pending(tmp_path):
    """README: results.nc is always written, unfinished points pending. A SIGTERM a few
    seconds into a disk campaign (here: once its first run is journaled, long before its
    first point) left none: `plot` exited 2 on a missing file, open_results raised."""
    from frictiondisk import open_results

    spec = tmp_path / "disk.yaml"
    spec.write_text(SLOW_DISK)
    out = tmp_path / "out"
    first_run = lambda: any(out.glob("journal/*/*"))  # noqa: E731
    proc = start_campaign_until(spec, out, until=first_run, fake_delay=0.3)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=HANG_S)
    assert proc.returncode == 143, err
    assert "results.nc" in err, err  # the stop names the file it wrote

    results = open_results(out)
    assert results.attrs["partial"] == 1 and results.attrs["points_done"] == 0
    assert list(results["status"].values) == ["pending"] * 3
    assert np.isnan(results["mu_star"].values).all()

    status = CliRunner().invoke(main, ["status", str(out)])
    assert status.exit_code == 0, status.output
    assert "(partial: 0 of 3 points finished)" in status.output, status.output
    plotted = CliRunner().invoke(main, ["plot", str(out), "-o", str(tmp_path / "f.png")])
    assert "not found" not in plotted.output, plotted.output
    assert "no point is finished yet" in plotted.output, plotted.output
    assert f"frictiondisk resume {out}" in plotted.output


def test_the_drain_notice_names_the_action_that_drops_the_runs_in_flight():
    """A second Ctrl-C drops the runs in flight after a Ctrl-C; after a SIGTERM (a batch
    scheduler, `kill`) or a SIGHUP (no terminal left to press Ctrl-C in) it is a SIGTERM."""
    import os

    from frictiondisk.engine.signals import HungUp, Terminated, drop_hint

    assert drop_hint(KeyboardInterrupt()) == "Ctrl-C again to drop them"
    assert drop_hint(Terminated()) == f"SIGTERM again, kill {os.getpid()}, to drop them"
    assert drop_hint(HungUp()) == f"SIGTERM, kill {os.getpid()}, to drop them"
    # what a stop says and its exit code (the real signals: the tests above and below)
    from frictiondisk.engine.signals import describe_stop

    assert describe_stop(KeyboardInterrupt()) == ("interrupted", 130)
    assert describe_stop(Terminated()) == ("terminated (SIGTERM)", 143)
    assert describe_stop(HungUp()) == ("hung up (SIGHUP: the terminal closed)", 129)


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
def test_a_stop_raised_inside_a_finalizer_still_stops_the_campaign_loop():
    """A signal that lands while the main thread runs a finalizer (Dask's Future.__del__
    did, on CI) has its exception printed and lost; the noted stop must survive it."""
    import gc
    import os

    from frictiondisk.cli.campaign import _signals_stop_the_campaign
    from frictiondisk.engine import signals

    class SignalledWhileFinalized:
        def __del__(self):
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(0.05)  # the handler runs here, inside __del__

    before = signal.getsignal(signal.SIGTERM)
    with _signals_stop_the_campaign():
        obj = SignalledWhileFinalized()
        del obj
        gc.collect()
        with pytest.raises(signals.Terminated):
            signals.raise_if_stop_requested()
    signals.clear_stop_requests()
    assert signal.getsignal(signal.SIGTERM) is before


@pytest.mark.parametrize(
    ("stop", "code", "word"), [("Terminated", 143, "terminated"), ("KeyboardInterrupt", 130, "")]
)
def test_a_stop_outside_the_campaign_loop_keeps_the_documented_exit_code(
    tmp_path, monkeypatch, stop, code, word
):
    """A trajectory campaign runs its one run outside the loop that turns a stop into
    CampaignInterrupted; so does the set-up before it. Click alone would say 'Aborted!' and
    exit 1 there."""
    from frictiondisk.engine import runner
    from frictiondisk.engine.signals import Terminated

    raised = {"Terminated": Terminated, "KeyboardInterrupt": KeyboardInterrupt}[stop]

    def stopped(*args, **kwargs):
        raise raised()

    monkeypatch.setattr(runner, "run_campaign", stopped)
    spec = tmp_path / "c.yaml"
    spec.write_text(CAMPAIGN)
    result = CliRunner().invoke(main, ["run", str(spec), "-o", str(tmp_path / "out")])
    assert result.exit_code == code, result.output
    assert (word or "interrupted") in result.output
    assert "Run the same command again" in result.output


LONG_TRAJECTORY = """\
name: long_trajectory
scene: disk
params: {mu: 0.05}
contact: {points: 96}
numerics: {mode: converge, t_max: 300000.0, cycle_tol: 1.0e-12}
trajectory: {dt_out: 5.0, show: whole}
"""


def test_a_trajectory_run_stops_at_once_on_sigterm(tmp_path):
    """A trajectory campaign's one run (minutes: a sliding disk that never converges) sits
    in the numba kernel, which never returns to the interpreter; the run waits in another
    thread, so the SIGTERM handler runs at once instead of when the run ends."""
    spec = tmp_path / "t.yaml"
    spec.write_text(LONG_TRAJECTORY)
    out = tmp_path / "out"
    # campaign.yaml is written after the handlers are installed
    proc = start_campaign_until(spec, out, until=(out / "campaign.yaml").exists)
    wait_for_cpu(proc.pid, 1.0)  # into the run: a second of its work, not of the clock
    assert proc.poll() is None, "the trajectory finished before the signal"
    proc.send_signal(signal.SIGTERM)
    try:
        _, err = proc.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail("SIGTERM did not stop the trajectory run within 30 s")
    assert proc.returncode == 143, err
    assert "terminated" in err and "Run the same command again" in err
    assert not (out / "trajectory.nc").exists()  # nothing half-written


def test_a_closed_terminal_stops_the_campaign_gracefully(spec, tmp_path):
    """The real thing behind SIGHUP: the campaign's terminal goes away, so besides the
    signal every later write to it fails (EIO). Progress and messages are lost; the
    finished points are not."""
    import os
    import pty
    import select

    out = tmp_path / "hung_up"
    pid, terminal = pty.fork()
    if pid == 0:  # the child: its controlling terminal is the pty
        os.environ["FAKE_SIMULATE_DELAY_S"] = str(FAKE_RUN_S)
        command = cli_command(FAKE_RUN_S)
        os.execv(command[0], [*command, "run", str(spec), "-o", str(out)])
    t0 = time.time()
    while time.time() - t0 < HANG_S and points_done(out) < 2:
        if select.select([terminal], [], [], 0.02)[0]:
            try:
                os.read(terminal, 65536)  # keep the terminal drained, as a terminal does
            except OSError:
                break
    os.close(terminal)  # the terminal closes: the kernel hangs up its session
    _, status = os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == 129
    with xr.open_dataset(out / "results.nc") as part:
        assert part.attrs["partial"] == 1
        assert part.attrs["points_done"] >= 2
    assert json.loads((out / "status.json").read_text())["state"] == "interrupted"
