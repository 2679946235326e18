"""The `trajectory` task (paper Figs 4-5): run, files, figure, resume."""

import matplotlib
import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.engine.runner import run_campaign
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.trajectory.figure import cycle_window

CYCLE = """\
name: cycle
scene: pin
params: {mu: 0.115, x_ms: 0.1}
numerics: {mode: converge, t_max: 3000.0}
trajectory: {dt_out: 0.01, show: cycle}
"""


@pytest.fixture(scope="module")
def cycle_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("traj") / "cycle"
    summary = run_campaign(campaign_from_text(CYCLE), out, progress=False)
    assert summary.runs_computed == 1
    return out


def test_files_hold_the_run_and_its_trajectory(cycle_dir):
    res = xr.open_dataset(cycle_dir / "results.nc").load()
    traj = xr.open_dataset(cycle_dir / "trajectory.nc").load()
    assert res.attrs["task"] == "trajectory" and res.attrs["show"] == "cycle"
    assert str(res["outcome"].values) == "stick_slip"
    assert res["size"].attrs["units"] == "m"
    assert float(traj["time"].values[-1]) == pytest.approx(float(res["t_end"].values))


def test_the_drawn_cycle_is_the_kernels_converged_cycle(cycle_dir):
    """The last cycle of the record sticks on the circle of radius `size` and its largest
    excess while sliding is the kernel's `a` (to the recording interval)."""
    res = xr.open_dataset(cycle_dir / "results.nc").load()
    traj = xr.open_dataset(cycle_dir / "trajectory.nc").load()
    t = traj["time"].values
    stick = np.all(traj["mode"].values == 1, axis=1)
    t0, t1 = cycle_window(t, stick)
    keep = (t >= t0) & (t <= t1)
    r = np.hypot(traj["x"].values, traj["y"].values)[keep]
    size, a = float(res["size"].values), float(res["a"].values)
    # sticking arc: a circle about the master axis (cycle_tol = 1e-6 m)
    assert np.ptp(r[stick[keep]]) < 1e-5
    assert np.mean(r[stick[keep]]) == pytest.approx(size, abs=1e-5)
    # a, from samples every 0.01 s: |v| ~ 0.4 m/s near the maximum, where r is flat
    assert np.max(r[~stick[keep]]) - size == pytest.approx(a, abs=1e-5)


def test_plot_and_rerun(cycle_dir, tmp_path):
    target = tmp_path / "orbit.png"
    result = CliRunner().invoke(main, ["plot", str(cycle_dir), "-o", str(target)])
    assert result.exit_code == 0, result.output
    assert matplotlib.image.imread(target).shape[0] > 500
    again = run_campaign(campaign_from_text(CYCLE), cycle_dir, progress=False)
    assert again.runs_computed == 0  # both files valid: nothing recomputed
    (cycle_dir / "trajectory.nc").write_bytes(b"torn")
    assert run_campaign(None, cycle_dir, progress=False).runs_computed == 1


def test_a_cycle_needs_two_sticking_phases():
    t = np.linspace(0.0, 1.0, 5)
    with pytest.raises(ValueError, match="a complete cycle needs 2"):
        cycle_window(t, np.array([False, True, True, True, True]))
