"""`frictiondisk simulate` end to end, as the issue's acceptance lines state it."""

import json

import matplotlib.image as mpimg
import numpy as np
import xarray as xr
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.figures.plotting import SLIDE_COLOR, STICK_COLOR


def _run(tmp_path, text, *args):
    scene = tmp_path / "scene.yaml"
    scene.write_text(text)
    return CliRunner().invoke(main, ["simulate", str(scene), *args])


def _pixels_of(image, hex_color, tol=0.03):
    rgb = np.array([int(hex_color[k : k + 2], 16) / 255 for k in (1, 3, 5)])
    return int((np.abs(image[..., :3] - rgb).max(axis=-1) < tol).sum())


def test_mu_013_sticks_and_mu_012_does_not(tmp_path):
    out = _run(tmp_path, "scene: pin\nparams: {mu: 0.13}\n", "--json")
    assert out.exit_code == 0, out.output
    assert json.loads(out.output)["outcome"] == "stick"

    plot = tmp_path / "orbit.png"
    traj = tmp_path / "traj.nc"
    out = _run(
        tmp_path, "scene: pin\nparams: {mu: 0.12}\n", "--json", "--plot", str(plot), "-o", str(traj)
    )
    assert out.exit_code == 0, out.output
    summary = json.loads(out.output)
    # not stick: at the 30 s horizon sticking and sliding alternate (it departs from sticking)
    assert summary["outcome"] == "stick_slip"
    for key in ("reason", "R1", "t_R1", "size", "a", "n_transitions", "stick_fraction"):
        assert key in summary
    for key in ("t_end", "n_steps", "wall_s"):
        assert summary[key] > 0

    # both regimes are drawn, in their colours
    image = mpimg.imread(plot)
    assert _pixels_of(image, STICK_COLOR) > 500
    assert _pixels_of(image, SLIDE_COLOR) > 500

    with xr.open_dataset(traj) as ds:
        assert set(np.unique(ds["mode"].values)) == {0, 1}
        assert ds["x"].attrs["units"] == "m"
        assert "mu: 0.12" in ds.attrs["scene_yaml"]


def test_set_override_changes_the_outcome(tmp_path):
    out = _run(tmp_path, "scene: pin\nparams: {mu: 0.12}\n", "--json", "--set", "params.mu=0.14")
    assert out.exit_code == 0, out.output
    assert json.loads(out.output)["outcome"] == "stick"
