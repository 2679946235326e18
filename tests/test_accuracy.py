"""`frictiondisk accuracy`: the work-precision study of the jump search (issue 5, item 1)."""

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.studies.accuracy.ladder import (
    NUMERICS_REFERENCE,
    STIFFNESSES,
    build_ladder,
    default_knobs,
)
from frictiondisk.studies.accuracy.study import plan_rows

CAMPAIGNS = Path(__file__).resolve().parents[1] / "campaigns"
PIN = CAMPAIGNS / "accuracy_pin.yaml"
TOL = 1.0e-8  # small enough that the rtol errors (1e-7 ... 1e-5 on this pin) are resolved


def _invoke(*args):
    return CliRunner().invoke(main, ["accuracy", *map(str, args)])


@pytest.fixture(scope="module")
def quick_study(tmp_path_factory):
    out = tmp_path_factory.mktemp("accuracy")
    result = _invoke(PIN, "-o", out, "--knobs", "rtol,method", "--quick", "--tol", TOL)
    assert result.exit_code == 0, result.output
    return out, result


def test_writes_dataset_and_figures(quick_study):
    out, result = quick_study
    for name in ("accuracy.nc", "work_precision.png", "work_precision.pdf"):
        assert (out / name).stat().st_size > 1000, name
    assert "accuracy" in result.stderr  # tqdm progress on stderr, the table on stdout
    assert "mu*" in result.stdout and "%|" not in result.stdout
    with xr.open_dataset(out / "accuracy.nc") as ds:
        assert list(ds.sizes) == ["setting"]
        for name in ("knob", "value", "mu_lo", "mu_hi", "mu_star", "error", "wall_s"):
            assert name in ds and ds[name].attrs["long_name"]
        for name in ("n_steps", "n_events", "n_runs", "status", "reason", "reference"):
            assert name in ds
        assert ds["error"].attrs["units"] == "1" and ds["wall_s"].attrs["units"] == "s"
        assert ds.attrs["tol"] == TOL and ds.attrs["campaign_name"] == "accuracy_pin"
        assert ds.attrs["point"] == "params.x_ms = 0.1"
        assert set(ds["knob"].values) == {"rtol", "method"}
        assert (ds["status"] == "converged").all()
        assert ((ds["mu_hi"] - ds["mu_lo"]) <= TOL * (1 + 1e-9)).all()
        assert (ds["n_runs"] > 0).all() and (ds["n_steps"] > 0).all()
        np.testing.assert_array_equal(ds["error"], abs(ds["mu_star"] - ds["mu_star_ref"]))


def test_error_falls_as_rtol_tightens_and_the_reference_is_exact(quick_study):
    out, _ = quick_study
    with xr.open_dataset(out / "accuracy.nc") as ds:
        rows = ds.where(ds["knob"] == "rtol", drop=True).sortby("value", ascending=False)
        rtol = rows["value"].values
        error = rows["error"].values
        assert list(rtol) == [1e-3, 1e-5, 1e-7, 1e-9]
        assert np.all(np.diff(error) < 0), dict(zip(rtol, error, strict=True))
        # the tightest rtol is the reference: exactly zero error, flagged
        assert error[-1] == 0.0 and rows["is_reference"].values[-1] == 1
        assert rows["is_reference"].values[:-1].sum() == 0
        # the loosest rtol is resolved by the bisection (its error is not bracket noise)
        assert error[0] > 10 * TOL
        # and tightening costs steps per simulated second (the runs' mu and length
        # depend on where the search probes)
        steps_per_s = rows["n_steps"].values / rows["t_simulated"].values
        assert np.all(np.diff(steps_per_s) > 0), steps_per_s
        # the method knob is measured against the same reference
        method = ds.where(ds["knob"] == "method", drop=True)
        assert (method["mu_star_ref"] == rows["mu_star"].values[-1]).all()
        assert set(method["series"].values) == {"rodas4-fixed (dt)", "reference"}


def test_ladder_references_and_physics_numerics():
    pin = scene_from_dict({"scene": "pin", "contact": {"damping": 500.0}})
    assert "points" not in default_knobs("pin") and "points" in default_knobs("disk")
    knobs = {k.name: k for k in build_ladder(pin, default_knobs("pin"))}
    # c -> infinity for the pin: the exact Coulomb model
    assert knobs["stiffness"].reference.overrides == {"numerics.method": "coulomb"}
    assert knobs["damping"].reference.overrides == {"numerics.method": "coulomb"}
    for setting in knobs["stiffness"].settings:
        config = setting.config(pin)
        c = config.contact.stiffness
        # critical damping follows c, although the base scene fixed the damping
        assert config.contact_damping == pytest.approx(2 * math.sqrt(c * config.params.m_s))
        # physics rows run at the reference numerics
        assert config.numerics.rtol == NUMERICS_REFERENCE["numerics.rtol"]
        assert config.numerics.atol == NUMERICS_REFERENCE["numerics.atol"]
    disk = scene_from_dict({"scene": "disk", "params": {"phidot0": 1.1}})
    knobs = {k.name: k for k in build_ladder(disk, default_knobs("disk"))}
    ref = knobs["stiffness"].reference.config(disk)
    assert ref.contact.stiffness == max(STIFFNESSES) and ref.numerics.method == "rodas4"
    assert knobs["points"].reference.config(disk).n_contacts == 768
    # the knob refines the campaign's own layout
    clutch = disk.with_overrides(
        {"contact.layout": "annulus", "contact.inner_radius": 0.063, "contact.outer_radius": 0.087}
    )
    knobs = {k.name: k for k in build_ladder(clutch, default_knobs("disk"))}
    ref = knobs["points"].reference.config(clutch)
    assert (ref.contact.layout, ref.n_contacts) == ("annulus", 768)
    assert "finest annulus" in knobs["points"].note


def test_plan_runs_each_scene_once():
    pin = scene_from_dict({"scene": "pin"})
    ladder = build_ladder(pin, ("rtol", "method", "preset"))
    rows, scenes = plan_rows(pin, ladder)
    # rtol 1e-9 is the reference of all three knobs, and so is numerics.preset: reference
    assert len(scenes) < len(rows)
    ref_hashes = {row.reference_hash for row in rows}
    assert len(ref_hashes) == 1
    rtol_rows = [row for row in rows if row.setting.knob == "rtol"]
    assert [row.is_reference for row in rtol_rows] == [False] * 6 + [True]
    preset = {row.setting.tag: row.is_reference for row in rows if row.setting.knob == "preset"}
    assert preset == {"fast": False, "default": False, "reference": True}


# --- bad input: exit code 2, the field named ---------------------------------------------


def _fails(result, *pieces):
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith("error: ")
    for piece in pieces:
        assert piece in result.stderr, result.stderr


def test_scan_campaign_is_refused(tmp_path):
    path = tmp_path / "scan.yaml"
    path.write_text("name: s\nscene: pin\nscan:\n  mu: [0.1, 0.2]\n")
    _fails(_invoke(path, "-o", tmp_path / "out"), "scan: the accuracy study needs a find_jump")
    assert not (tmp_path / "out").exists()


def test_bad_campaign_names_the_field(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text(PIN.read_text().replace("tol: 1.0e-4", "tol: -1.0"))
    _fails(_invoke(path, "-o", tmp_path / "out"), "find_jump.tol: -1.0 is out of range")
    path.write_text(PIN.read_text().replace("mode: decide", "mode: decide\n  preset: turbo"))
    _fails(
        _invoke(path, "-o", tmp_path / "out"),
        "numerics.preset: 'turbo' is not allowed: must be one of 'fast', 'default', 'reference'",
    )


def test_missing_file(tmp_path):
    _fails(_invoke(tmp_path / "nope.yaml", "-o", tmp_path / "out"), "campaign file not found")


@pytest.mark.parametrize(
    "args, piece",
    [
        (("--knobs", "rtol,bogus"), "--knobs: unknown knob 'bogus'; allowed: rtol, method"),
        (("--knobs", "points"), "--knobs: knob 'points' applies to scene 'disk' only"),
        (("--point", "1"), "--point: 1 is out of range: the campaign has 1 points (0 ... 0)"),
        (("--tol", "0.5"), "--tol: 0.5 is out of range: must be > 0 and < 0.25"),
        (("--tol", "0"), "--tol: 0.0 is out of range"),
    ],
)
def test_bad_options(tmp_path, args, piece):
    _fails(_invoke(PIN, "-o", tmp_path / "out", *args), piece)
    assert not (tmp_path / "out").exists()


def test_figure_lists_failed_rows_instead_of_drawing_them(quick_study):
    from frictiondisk.studies.accuracy.figure import work_precision_figure

    out, _ = quick_study
    with xr.open_dataset(out / "accuracy.nc") as ds:
        ds = ds.load()
    ds["status"].values[0] = "failed"
    ds["reason"].values[0] = "no stick up to the limit"
    ds["error"].values[0] = np.nan
    fig = work_precision_figure(ds)
    texts = [t.get_text() for t in fig.texts]
    assert any("not shown: rodas4 rtol = 0.001" in t and "no stick up" in t for t in texts)
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    # the bisection tol is drawn
    assert any(np.allclose(line.get_xdata(), TOL) for line in ax.get_lines())
