"""Texts a user reads: figure titles and captions, campaign diffs."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import xarray as xr  # noqa: E402

from frictiondisk.figures.shared import (  # noqa: E402
    MU_LABEL,
    caption_text,
    physics_text,
    scene_title,
)
from frictiondisk.model.scene import scene_from_dict  # noqa: E402
from frictiondisk.store import cf  # noqa: E402
from frictiondisk.tasks.campaign import campaign_from_text  # noqa: E402

LINE = """\
name: diff_line
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-4
  along:
    params.x_ms: {start: 0.05, stop: 0.15, num: 5}
"""


def _results(scene: dict, varied: str | None = None) -> xr.Dataset:
    ds = xr.Dataset(attrs={"campaign_name": "fig_x", "task": "find_jump"})
    ds.attrs.update(cf.scene_attrs(scene_from_dict(scene)))
    if varied:
        ds = ds.assign_coords(v=("v", [0.0, 1.0], {"scene_key": varied}))
    return ds


def test_titles_name_the_scene_not_the_file():
    assert scene_title(_results({"scene": "pin"})) == "Pin"
    assert scene_title(_results({"scene": "disk"})) == "Disk (12 contact points)"
    assert "fig_x" not in scene_title(_results({"scene": "pin"}))


def test_captions_give_the_physical_parameters_that_are_not_varied():
    disk = {"scene": "disk", "params": {"beta_b": 0.005, "phidot0": 1.1, "x_ms": 0.1}}
    text = physics_text(_results(disk, varied="params.x0"))
    assert text.startswith("disk, x_ms 0.1 m")
    assert "0.005 N m s/rad" in text and "1.1 rad/s" in text
    assert "x0" not in text  # varied: it is on the axis
    pin = physics_text(_results({"scene": "pin"}))
    assert pin == "pin, x_ms 0.1 m, x0 0 m"  # no brake, no spin for a pin
    assert pin in caption_text(_results({"scene": "pin"}))


def test_mu_is_written_as_the_greek_letter():
    assert MU_LABEL == "friction coefficient \u03bc [-]"


def test_a_changed_campaign_is_shown_rounded():
    a = campaign_from_text(LINE)
    b = campaign_from_text(LINE.replace("num: 5", "num: 6"))
    (line,) = a.diff(b)
    assert line == (
        "find_jump.along.params.x_ms: [0.05, 0.075, 0.1, 0.125, 0.15] -> "
        "[0.05, 0.07, 0.09, 0.11, 0.13, 0.15]"
    )
    assert "9999" not in line
    # a change below the rounding is still shown
    c = campaign_from_text(LINE.replace("tol: 1.0e-4", "tol: 1.0000000000001e-4"))
    (line,) = a.diff(c)
    assert line.startswith("find_jump.tol: 0.0001 -> 0.0001000000000000")


def test_the_mu_star_table_lists_every_point():
    import numpy as np

    from frictiondisk.tasks.find_jump.table import mu_star_table
    from frictiondisk.tasks.registry import TASKS

    ds = xr.Dataset(
        {
            "mu_star": ("x_ms", [0.0633, np.nan]),
            "mu_lo": ("x_ms", [0.0632, np.nan]),
            "mu_hi": ("x_ms", [0.0634, np.nan]),
            "n_runs": ("x_ms", [14, 3]),
            "status": ("x_ms", ["converged", "failed"]),
        },
        coords={"x_ms": ("x_ms", [0.05, 0.1], {"units": "m"})},
        attrs={"task": "find_jump", "tol": 1e-4},
    )
    lines = mu_star_table(ds)
    assert lines[0] == "mu* per point (bracket width <= tol 0.0001):"
    assert lines[1].split() == [
        "x_ms",
        "[m]",
        "mu*",
        "bracket",
        "[mu_lo,",
        "mu_hi]",
        "runs",
        "status",
    ]
    assert lines[2].split() == ["0.05", "0.063300", "[0.063200,", "0.063400]", "14", "converged"]
    assert lines[3].split() == ["0.1", "-", "-", "3", "failed"]
    assert TASKS["scan"].run_lines(ds.assign_attrs(task="scan")) == []  # its own table
