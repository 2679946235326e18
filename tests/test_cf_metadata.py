"""CF-1.10 metadata of every netCDF file we write: results.nc (a trace's too), runs.nc, trajectory.nc and
accuracy.nc (frictiondisk/store/cf.py)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner
from conftest import outside_the_figure

from frictiondisk.cli import main
from frictiondisk.engine.runner import run_campaign
from frictiondisk.tasks.campaign import campaign_from_text

ACCURACY_PIN = Path(__file__).resolve().parents[1] / "campaigns" / "accuracy_pin.yaml"

LINE = """\
name: cf_line
scene: pin
numerics: {t_decide: 20.0}
find_jump:
  tol: 1.0e-2
  prescan: {mu: [0.05, 0.2], mode: decide}
  along: {params.x_ms: [0.1]}
"""
SCAN = """\
name: cf_scan
scene: pin
numerics: {t_decide: 20.0}
scan: {mu: [0.05, 0.2], mode: decide}
"""
BASIN = """\
name: cf_basin
scene: pin
params: {x_ms: 0.1, mu: 0.125}
numerics: {t_decide: 10.0}
basin:
  sample: {params.x0: {uniform: [-0.05, 0.05]}}
  samples: 6
  seed: 7
"""
TRACE = """\
name: cf_trace
scene: pin
numerics: {t_decide: 20.0}
trace:
  key: params.x_ms
  range: [0.08, 0.12]
  mu: [0.05, 0.2]
  tol: 1.0e-3
  resolution: 0.5
  first_look: {keys: 2, mu: 6}
"""
ORBIT = """\
name: cf_orbit
scene: pin
params: {mu: 0.2}
numerics: {t_decide: 10.0}
trajectory: {dt_out: 0.5, show: whole}
"""


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    root = tmp_path_factory.mktemp("cf")
    out = {}
    campaigns = (("line", LINE), ("scan", SCAN), ("orbit", ORBIT), ("basin", BASIN))
    for name, text in (*campaigns, ("trace", TRACE)):
        run_campaign(campaign_from_text(text, "<test>"), root / name, 1, None, False)
        for nc in (root / name).glob("*.nc"):
            out[f"{name}/{nc.name}"] = nc
    acc = root / "accuracy"
    result = CliRunner().invoke(
        main,
        ["accuracy", str(ACCURACY_PIN), "-o", str(acc), "--knobs", "preset"]
        + ["--quick", "--tol", "1e-3"],
    )
    assert result.exit_code == 0, result.output
    out["accuracy/accuracy.nc"] = acc / "accuracy.nc"
    return out


FILES = [  # every netCDF file the workflow writes, sorted
    "accuracy/accuracy.nc",
    "basin/results.nc",
    "basin/runs.nc",
    "line/results.nc",
    "line/runs.nc",
    "orbit/results.nc",
    "orbit/trajectory.nc",
    "scan/results.nc",
    "scan/runs.nc",
    "trace/results.nc",
    "trace/runs.nc",
]


def test_every_file_is_there(files):
    assert sorted(files) == FILES


@pytest.mark.parametrize("name", FILES)
def test_cf_attributes(files, name):
    with xr.open_dataset(files[name]) as ds:
        assert ds.attrs["Conventions"] == "CF-1.10"
        for key in ("title", "history", "source", "references"):
            assert isinstance(ds.attrs[key], str) and ds.attrs[key].strip(), key
        assert "frictiondisk" in ds.attrs["source"] and "numba" in ds.attrs["source"]
        # the resolved physical parameters
        scene = yaml.safe_load(ds.attrs["scene_yaml"])
        assert scene["params"]["omega_m"] == ds.attrs["param_omega_m"] == 1.1
        assert ds.attrs["param_F_n"] == 1.0 and ds.attrs["param_contact_points"] == 1
        for var_name, var in ds.variables.items():
            attrs = var.attrs
            assert attrs.get("long_name"), f"{name}: {var_name} has no long_name"
            if var.dtype.kind in "USO":
                assert "units" not in attrs, f"{name}: text variable {var_name} has units"
            elif "flag_values" in attrs:
                values = np.atleast_1d(attrs["flag_values"])
                meanings = attrs["flag_meanings"].split()
                assert len(values) == len(meanings) >= 2, var_name
                assert np.isin(var.values, values).all(), f"{var_name} outside its flags"
                assert attrs["units"] == "1"
            elif var_name == "value":  # accuracy.nc: units per row
                assert "value_units" in ds
            else:
                assert isinstance(attrs.get("units"), str), f"{name}: {var_name} has no units"
            units = attrs.get("units")
            if units and units != "1":  # a plot label "long_name [units]" must not say it twice
                assert f"[{units}]" not in attrs["long_name"], f"{name}: {var_name} doubles units"


@pytest.mark.parametrize("name", FILES)
def test_coordinates_have_no_fill_value_and_time_increases(files, name):
    import netCDF4

    with netCDF4.Dataset(files[name]) as nc:
        for dim in nc.dimensions:
            if dim in nc.variables:
                assert "_FillValue" not in nc[dim].ncattrs(), f"{name}: coordinate {dim}"
        for var in nc.variables.values():
            if getattr(var, "axis", None) == "T" or var.name == "time":
                assert np.all(np.diff(var[:]) > 0), f"{name}: {var.name} not increasing"


def test_flags_and_text_variables_are_described(files):
    with xr.open_dataset(files["line/results.nc"]) as ds:
        assert ds["monotone"].attrs["flag_meanings"] == "contradicts_a_single_jump single_jump"
        assert list(ds["jump_rising"].attrs["flag_values"]) == [-1, 0, 1]
        assert "stick_slip" in ds["outcome_hi"].attrs["comment"]
    with xr.open_dataset(files["line/runs.nc"]) as ds:
        assert ds["outcome"].attrs["long_name"] == "outcome of the run"
        assert "creep" in ds["outcome"].attrs["comment"]
        assert ds["reason"].attrs["long_name"] == "why this outcome"
    with xr.open_dataset(files["orbit/trajectory.nc"]) as ds:
        assert ds["mode"].attrs["flag_meanings"] == "slide stick"


def test_trajectory_measures_are_numbers_never_the_string_none(files):
    with xr.open_dataset(files["orbit/trajectory.nc"]) as ds:
        assert ds.attrs["outcome"] == "stick"
        for key in ("size", "a", "R1", "t_R1"):
            assert isinstance(ds.attrs[key], float | np.floating), key
        assert math.isnan(ds.attrs["a"])  # a stick has no cycle deviation
        assert ds.attrs["size"] > 0.0


def test_a_basin_caption_does_not_give_a_sampled_key_its_base_value(files):
    from frictiondisk import plot_results
    from frictiondisk.figures.shared import caption_text

    with xr.open_dataset(files["basin/results.nc"]) as ds:
        caption = caption_text(ds.load())
    assert "x_ms 0.1 m" in caption  # fixed: named with its value
    assert "x0" not in caption  # sampled (x0 ~ U[-0.05, 0.05]): it has no single value
    fig = plot_results(files["basin/results.nc"].parent)
    (title,) = [t for sub in fig.subfigs for t in [sub._suptitle] if t is not None]
    assert "x0 ~ U[-0.05, 0.05] m" in title.get_text() and title.get_wrap()


@pytest.mark.parametrize("kind", ["line", "scan", "orbit", "basin"])
def test_every_figure_has_the_one_house_style_whatever_the_callers_rc(files, kind):
    import matplotlib

    from frictiondisk import plot_results
    from frictiondisk.figures.style import LABEL_FONT_PT

    with matplotlib.rc_context({"font.size": 20.0, "axes.labelsize": 20.0, "axes.grid": False}):
        fig = plot_results(files[f"{kind}/results.nc"].parent)
    labelled = [ax for ax in fig.get_axes() if ax.get_xlabel()]
    assert labelled, kind
    for ax in labelled:
        assert ax.xaxis.label.get_fontsize() == LABEL_FONT_PT, (kind, ax.get_xlabel())
    assert outside_the_figure(fig) == [], kind  # no legend or text cut off at an edge


@pytest.mark.parametrize(
    ("name", "absent", "kept"),
    [
        ("line/results.nc", ("param_x_ms", "param_mu"), ("param_x0", "param_omega_m")),
        ("line/runs.nc", ("param_x_ms", "param_mu"), ("param_x0",)),
        ("scan/results.nc", ("param_mu",), ("param_x_ms", "param_x0")),
        ("basin/results.nc", ("param_x0",), ("param_x_ms", "param_mu")),
        ("orbit/results.nc", (), ("param_mu", "param_x0")),
    ],
)
def test_a_varied_sampled_or_searched_key_has_no_single_value_attribute(files, name, absent, kept):
    """param_x_ms = 0.1 in a file along x_ms, or param_mu = 0.13 in a file that searches
    mu, read as the value every point used; the coordinates (and scene_key) say it."""
    with xr.open_dataset(files[name]) as ds:
        for attr in absent:
            assert attr not in ds.attrs, (name, attr)
        for attr in kept:
            assert attr in ds.attrs, (name, attr)


def test_the_measures_table_of_the_model_gives_the_units_of_the_files():
    """docs/model.md's per-revolution measures carry the units runs.nc writes (slip_decay
    said 1/rev there and 1 in the file)."""
    import re

    from frictiondisk.store.measures import RUN_MEASURES

    text = (Path(__file__).resolve().parents[1] / "docs" / "model.md").read_text()
    rows = re.findall(r"^\| `(\w+)` \|.*\| ([^|]+) \|$", text, flags=re.MULTILINE)
    units = {name: unit.strip() for name, unit in rows if name in RUN_MEASURES}
    assert {"slip_per_rev", "slip_decay", "slip_limit"} <= units.keys(), units
    for name, unit in units.items():
        assert unit == RUN_MEASURES[name][0], (name, unit, RUN_MEASURES[name][0])
