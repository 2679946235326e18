"""Output side of the CLI: trajectory Dataset / netCDF, orbit plot, and bad-scene handling.

The results here are built by hand (a circular orbit with one sticking arc), so these tests
do not run the kernel. End-to-end runs of `frictiondisk simulate` are tested elsewhere.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from frictiondisk import __version__
from frictiondisk.cli import main
from frictiondisk.simulation.result import SimulationResult, Trajectory

OMEGA_M = 1.1
RADIUS = 0.05
N_SAMPLES = 400
STICK_SLICE = slice(100, 200)  # samples during which every contact sticks


def _config(scene: str):
    config_module = pytest.importorskip("frictiondisk.model.scene")
    return config_module.scene_from_dict({"scene": scene})


def _result(scene: str, n_contacts: int, *, record: bool = True) -> SimulationResult:
    """A run whose slave circles the point (0.1, 0) once, sticking on one arc."""
    t = np.linspace(0.0, 2.0 * math.pi / OMEGA_M, N_SAMPLES)
    angle = OMEGA_M * t
    mode = np.zeros((N_SAMPLES, n_contacts), dtype=np.int8)
    mode[STICK_SLICE, :] = 1
    mode[50, 0] = 1  # one contact sticking alone: not a sticking sample
    rotating = scene == "disk"
    trajectory = Trajectory(
        t=t,
        x=0.1 + RADIUS * np.cos(angle),
        y=RADIUS * np.sin(angle),
        vx=-RADIUS * OMEGA_M * np.sin(angle),
        vy=RADIUS * OMEGA_M * np.cos(angle),
        phi=angle.copy() if rotating else None,
        phidot=np.full(N_SAMPLES, OMEGA_M) if rotating else None,
        Zx=np.linspace(-0.1, 0.1, N_SAMPLES)[:, None] * np.ones((1, n_contacts)),
        Zy=np.zeros((N_SAMPLES, n_contacts)),
        mode=mode,
    )
    return SimulationResult(
        outcome="stick_slip",
        reason="limit cycle converged",
        R1=0.08,
        t_R1=1.5,
        size=0.08,
        a=float("nan"),
        n_transitions=7,
        stick_fraction=0.25,
        t_end=float(t[-1]),
        n_steps=1234,
        n_rejected=5,
        n_refused=0,
        cycle_converged=True,
        wall_s=0.42,
        method="test",
        trajectory=trajectory if record else None,
    )


# --- trajectory Dataset and netCDF -------------------------------------------------------------


def test_netcdf_round_trip_pin(tmp_path: Path) -> None:
    from frictiondisk.store.trajectory import write_trajectory

    config = _config("pin")
    result = _result("pin", 1)
    path = tmp_path / "deeper" / "dir" / "traj.nc"  # parents are created

    assert write_trajectory(path, result, config) == path
    assert path.is_file()
    assert [p.name for p in path.parent.iterdir()] == ["traj.nc"]  # no temporary left over

    with xr.open_dataset(path) as ds:
        ds.load()
    assert dict(ds.sizes) == {"time": N_SAMPLES, "contact": 1, "event": 0}
    for name in ("x", "y", "vx", "vy", "Zx", "Zy", "mode"):
        assert name in ds.data_vars, name
        assert ds[name].attrs["units"], name
        assert ds[name].attrs["long_name"], name
    assert "phi" not in ds and "phidot" not in ds  # the pin does not rotate
    assert ds["x"].attrs["units"] == "m"
    assert ds["vx"].attrs["units"] == "m s-1"
    assert ds["Zx"].attrs["units"] == "N"
    assert ds["time"].attrs["units"] == "s"
    assert ds["time"].dtype == np.float64  # not decoded as a timedelta
    assert ds["Zx"].dims == ("time", "contact")

    np.testing.assert_array_equal(ds["time"].values, result.trajectory.t)
    np.testing.assert_array_equal(ds["x"].values, result.trajectory.x)
    np.testing.assert_array_equal(ds["Zx"].values, result.trajectory.Zx)

    assert ds["mode"].dtype == np.int8
    np.testing.assert_array_equal(ds["mode"].values, result.trajectory.mode)
    assert list(ds["mode"].attrs["flag_values"]) == [0, 1]
    assert ds["mode"].attrs["flag_meanings"] == "slide stick"

    assert ds.attrs["scene_yaml"] == config.to_yaml()
    assert ds.attrs["config_hash"] == config.content_hash()
    assert ds.attrs["frictiondisk_version"] == __version__
    assert ds.attrs["outcome"] == "stick_slip"
    assert ds.attrs["reason"] == "limit cycle converged"
    assert ds.attrs["n_steps"] == 1234
    assert ds.attrs["R1"] == pytest.approx(0.08)
    assert math.isnan(ds.attrs["a"])  # NaN -> None in summary() -> NaN, never a string
    assert ds.attrs["cycle_converged"] == 1  # bool -> int


def test_switches_go_to_their_own_dimension_and_time_strictly_increases(tmp_path: Path) -> None:
    import dataclasses

    import netCDF4

    from frictiondisk.store.trajectory import write_trajectory

    result = _result("pin", 1)
    traj = result.trajectory
    # the recorder's form of a switch: the sample before it repeated at the same time, with
    # the mode before the switch; here at the two edges of the sticking arc
    edges = [STICK_SLICE.start, STICK_SLICE.stop]
    at = np.sort(np.concatenate([np.arange(N_SAMPLES), edges]))
    mode = traj.mode[at].copy()
    for k, i in enumerate(edges):
        mode[i + k] = traj.mode[i - 1]  # the copy placed first keeps the mode before
    switched = dataclasses.replace(
        traj,
        **{name: getattr(traj, name)[at] for name in ("t", "x", "y", "vx", "vy", "Zx", "Zy")},
        mode=mode,
    )
    path = write_trajectory(
        tmp_path / "t.nc", dataclasses.replace(result, trajectory=switched), _config("pin")
    )
    with xr.open_dataset(path) as ds:
        ds.load()
    assert np.all(np.diff(ds["time"].values) > 0)
    np.testing.assert_array_equal(ds["time"].values, traj.t)
    np.testing.assert_array_equal(ds["mode"].values, traj.mode)  # the mode after each switch
    np.testing.assert_array_equal(ds["event_time"].values, traj.t[edges])
    np.testing.assert_array_equal(ds["mode_before_event"].values[:, 0], [0, 1])
    assert float(ds.sel(time=traj.t[edges[0]] + 1e-9, method="nearest")["time"]) == pytest.approx(
        traj.t[edges[0]]
    )
    with netCDF4.Dataset(path) as nc:  # CF: no _FillValue on coordinate variables
        assert all("_FillValue" not in nc[name].ncattrs() for name in ("time", "event_time"))


def test_netcdf_disk_has_rotation(tmp_path: Path) -> None:
    from frictiondisk.store.trajectory import write_trajectory

    config = _config("disk")
    result = _result("disk", 12)
    path = write_trajectory(tmp_path / "disk.nc", result, config)

    with xr.open_dataset(path) as ds:
        ds.load()
    assert dict(ds.sizes) == {"time": N_SAMPLES, "contact": 12, "event": 0}
    assert ds["phi"].attrs["units"] == "rad"
    assert ds["phidot"].attrs["units"] == "rad s-1"
    np.testing.assert_array_equal(ds["phi"].values, result.trajectory.phi)
    np.testing.assert_array_equal(ds["contact"].values, np.arange(12))


def test_write_trajectory_replaces_existing_file(tmp_path: Path) -> None:
    from frictiondisk.store.trajectory import write_trajectory

    config = _config("pin")
    path = tmp_path / "traj.nc"
    path.write_text("not a netCDF file")
    write_trajectory(path, _result("pin", 1), config)
    with xr.open_dataset(path) as ds:
        assert ds.sizes["time"] == N_SAMPLES


def test_dataset_needs_a_trajectory() -> None:
    from frictiondisk.store.trajectory import trajectory_dataset

    with pytest.raises(ValueError, match="no trajectory"):
        trajectory_dataset(_result("pin", 1, record=False), _config("pin"))


# --- orbit plot --------------------------------------------------------------------------------


def test_plot_orbit_png(tmp_path: Path) -> None:
    import matplotlib.image

    from frictiondisk.figures.plotting import plot_orbit, save_figure

    config = _config("pin")
    fig = plot_orbit(_result("pin", 1), config)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "x [m]"
    assert ax.get_ylabel() == "y [m]"
    assert "stick_slip" in ax.get_title()
    assert "pin" in ax.get_title()
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert labels[:2] == ["sticking", "sliding"]
    assert labels[-2:] == ["start", "direction of motion"]
    assert len(ax.texts) >= 1  # the arrowheads (annotations) along the path

    # Sticking segments: every contact sticks at the segment's first sample; sample 50 (one
    # contact of one only for the pin, so it counts) is a sticking segment too.
    collections = ax.collections
    assert len(collections) == 2
    n_stick = len(collections[1].get_segments())
    assert n_stick == (STICK_SLICE.stop - STICK_SLICE.start) + 1
    assert len(collections[0].get_segments()) == N_SAMPLES - 1 - n_stick

    path = save_figure(fig, tmp_path / "plots" / "orbit.png")
    assert path.is_file() and path.stat().st_size > 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    image = matplotlib.image.imread(path)
    assert image.ndim == 3 and image.shape[0] > 100 and image.shape[1] > 100
    assert [p.name for p in path.parent.iterdir()] == ["orbit.png"]


def test_plot_orbit_disk_pdf_and_given_axes(tmp_path: Path) -> None:
    from matplotlib.figure import Figure

    from frictiondisk.figures.plotting import plot_orbit, save_figure

    fig = Figure()
    ax = fig.add_subplot()
    assert plot_orbit(_result("disk", 12), _config("disk"), ax=ax) is fig
    # For the disk, sample 50 (one contact of twelve sticking) is not a sticking segment.
    assert len(ax.collections[1].get_segments()) == STICK_SLICE.stop - STICK_SLICE.start
    path = save_figure(fig, tmp_path / "orbit.pdf")
    assert path.read_bytes()[:5] == b"%PDF-"


def test_save_figure_rejects_unknown_suffix(tmp_path: Path) -> None:
    from matplotlib.figure import Figure

    from frictiondisk.figures.plotting import save_figure

    with pytest.raises(ValueError, match="suffix"):
        save_figure(Figure(), tmp_path / "orbit.gif")


# --- CLI: bad scenes exit 2 with the field named, no traceback ---------------------------------


def _run_cli(args: list[str]):
    result = CliRunner().invoke(main, args)
    text = result.output + (result.stderr if result.stderr_bytes is not None else "")
    return result, text


@pytest.mark.parametrize(
    ("yaml_text", "needles"),
    [
        ("scene: pin\nparams: {x_ms: -inf}\n", ["params.x_ms"]),
        ("scene: pin\nparams: {x_ms: -.inf}\n", ["params.x_ms"]),
        ("scene: pin\nparams: {mu: 0.2, bogus_key: 1}\n", ["params", "bogus_key"]),
        ("scene: pin\nfoo: 3\n", ["foo"]),
    ],
    ids=["x_ms=-inf", "x_ms=-.inf", "unknown-param", "unknown-section"],
)
def test_bad_scene_exits_2_naming_the_field(
    tmp_path: Path, yaml_text: str, needles: list[str]
) -> None:
    pytest.importorskip("frictiondisk.model.scene")
    scene = tmp_path / "bad.yaml"
    scene.write_text(yaml_text)

    result, text = _run_cli(["simulate", str(scene), "--json"])

    assert result.exit_code == 2, text
    assert isinstance(result.exception, SystemExit), repr(result.exception)
    assert "Traceback" not in text
    assert f"error: {scene}" in result.stderr
    for needle in needles:
        assert needle in result.stderr, (needle, result.stderr)
    assert result.stdout == ""  # nothing for a JSON reader on a failure


def test_bad_override_exits_2(tmp_path: Path) -> None:
    pytest.importorskip("frictiondisk.model.scene")
    scene = tmp_path / "ok.yaml"
    scene.write_text("scene: pin\n")

    result, text = _run_cli(["simulate", str(scene), "--set", "params.x_ms=-inf"])

    assert result.exit_code == 2, text
    assert "Traceback" not in text
    assert "x_ms" in result.stderr


def test_missing_scene_file_exits_2(tmp_path: Path) -> None:
    pytest.importorskip("frictiondisk.model.scene")
    missing = tmp_path / "nope.yaml"
    result, text = _run_cli(["simulate", str(missing)])
    assert result.exit_code == 2, text
    assert "Traceback" not in text
    assert "not found" in result.stderr and str(missing) in result.stderr


@pytest.mark.parametrize(
    "args",
    [["--dt-out", "0"], ["--dt-out", "nan"], ["--plot", "orbit.gif"]],
    ids=["dt-out=0", "dt-out=nan", "plot-suffix"],
)
def test_bad_options_exit_2(tmp_path: Path, args: list[str]) -> None:
    scene = tmp_path / "ok.yaml"
    scene.write_text("scene: pin\n")
    result, text = _run_cli(["simulate", str(scene), *args])
    assert result.exit_code == 2, text
    assert "Traceback" not in text


def test_version_and_help() -> None:
    result, text = _run_cli(["--version"])
    assert result.exit_code == 0
    assert __version__ in result.output
    result, text = _run_cli(["simulate", "--help"])
    assert result.exit_code == 0
    for option in ("--set", "--json", "--output", "--plot", "--dt-out"):
        assert option in result.output


def test_console_entry_bad_scene_has_no_traceback(tmp_path: Path) -> None:
    """The real process: exit status 2, message on stderr, nothing on stdout."""
    pytest.importorskip("frictiondisk.model.scene")
    scene = tmp_path / "bad.yaml"
    scene.write_text("scene: pin\nparams: {x_ms: -inf}\n")
    proc = subprocess.run(
        [sys.executable, "-m", "frictiondisk.cli", "simulate", str(scene), "--json"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    assert "params.x_ms" in proc.stderr
    assert proc.stdout == ""
