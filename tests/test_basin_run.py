"""Basin campaigns end to end (the task's smoke test; its contract with the engine is
tests/test_task_contract.py): the pin's stick fraction against its boundary x0* located by
bisection, adaptive sampling on its target, a map against single runs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.engine.runner import run_campaign
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.jump_search.bisection import Bisection
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings

X0_RANGE = (-0.05, 0.05)  # [m]
PIN = {"scene": "pin", "params": {"x_ms": 0.1, "mu": 0.125}}

PIN_BASIN = """\
name: pin_basin
scene: pin
params: {x_ms: 0.1, mu: 0.125}
basin:
  sample: {params.x0: {uniform: [-0.05, 0.05]}}
  samples: 150
  seed: 7
"""

# Adaptive, two points: a few hundred runs of ~5 ms.
ADAPTIVE = """\
name: pin_basin_adaptive
scene: pin
params: {x_ms: 0.1}
basin:
  sample: {params.x0: {uniform: [-0.05, 0.05]}}
  target_se: 0.035
  max_samples: 400
  batch: 40
  seed: 3
  along: {params.mu: [0.12, 0.13]}
"""


def _outcome(x0: float, level: int = 0) -> str:
    config = scene_from_dict(PIN).with_overrides(
        {"params.x0": x0, "numerics.t_decide": 30.0 * 2.0**level}
    )
    return simulate(config).outcome


def _identical(dir_a: Path, dir_b: Path) -> None:
    with xr.open_dataset(dir_a / "results.nc") as a, xr.open_dataset(dir_b / "results.nc") as b:
        xr.testing.assert_identical(a.load(), b.load())
    with xr.open_dataset(dir_a / "runs.nc") as a, xr.open_dataset(dir_b / "runs.nc") as b:
        xr.testing.assert_identical(a.drop_vars("wall_s").load(), b.drop_vars("wall_s").load())


def test_pin_stick_fraction_agrees_with_the_boundary_located_by_bisection(tmp_path):
    # The stick set in x0 first: a scan must show one change, stick on the left of it.
    scan = np.linspace(*X0_RANGE, 21)
    sticks = [_outcome(float(x0)) == "stick" for x0 in scan]
    changes = np.flatnonzero(np.diff(sticks))
    assert sticks[0] and not sticks[-1] and changes.size == 1, list(zip(scan, sticks, strict=True))
    # ... so it is [-0.05, x0*): bisect x0* (a falling jump: stick below, not stick above)
    bisection = Bisection(X0_RANGE, BisectionSettings(1e-4, X0_RANGE, max_retries=2, rising=False))
    while not bisection.done:
        for request in bisection.pending():
            bisection.feed(request, {"outcome": _outcome(request.mu, request.level)})
    boundary = bisection.result()
    assert boundary.status == "converged" and boundary.monotone, boundary.reason
    implied = (boundary.mu_star - X0_RANGE[0]) / (X0_RANGE[1] - X0_RANGE[0])

    result = CliRunner().invoke(
        main, ["run", str(_write(tmp_path / "b.yaml", PIN_BASIN)), "-o", str(tmp_path / "o")]
    )
    assert result.exit_code == 0, result.output
    assert "basin: stick " in result.output and "(95 % Wilson), n = 150" in result.output
    with xr.open_dataset(tmp_path / "o" / "results.nc") as ds:
        stick = ds.sel(outcome="stick")
        lo, p, hi = float(stick.fraction_lo), float(stick.fraction), float(stick.fraction_hi)
        assert float(ds.n_samples) == 150 and ds.status.values == "converged"
    assert lo <= implied <= hi, (lo, p, hi, implied)
    # Sample by sample: stick exactly where x0 < x0* (outside the bisection's last bracket).
    with xr.open_dataset(tmp_path / "o" / "runs.nc") as runs:
        x0, outcome = runs.x0.values, runs.outcome.values
    clear = (x0 < boundary.mu_lo) | (x0 > boundary.mu_hi)
    np.testing.assert_array_equal((outcome == "stick")[clear], (x0 < boundary.mu_star)[clear])
    assert set(outcome) <= {"stick", "stick_slip", "slide"}


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


def test_adaptive_sampling_stops_on_its_target_in_batches(tmp_path):
    spec = _write(tmp_path / "b.yaml", ADAPTIVE)
    result = CliRunner().invoke(main, ["run", str(spec), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert "mu = 0.12: stick" in result.output  # the fractions, one line per point
    with xr.open_dataset(tmp_path / "out" / "results.nc") as ds:
        n = ds.n_samples.values
        assert (n % 40 == 0).all() and (n < 400).all()  # stopped on the target, in batches
        assert (ds.not_stick_se <= 0.036).all()
        # more friction, more sticking (x0* moves right with mu)
        stick = ds.fraction.sel(outcome="stick").values
        assert stick[0] < stick[1]


def test_a_map_gives_the_outcome_of_each_initial_state(tmp_path):
    text = """\
name: pin_map
scene: pin
params: {x_ms: 0.1, mu: 0.125}
basin:
  grid: {params.x0: [-0.03, 0.0, 0.03], params.y0: [-0.02, 0.02]}
"""
    run_campaign(campaign_from_text(text, "<test>"), tmp_path, workers=2, progress=False)
    with xr.open_dataset(tmp_path / "results.nc") as ds:
        for x0 in ds.x0.values:
            for y0 in ds.y0.values:
                config = scene_from_dict(PIN).with_overrides(
                    {"params.x0": float(x0), "params.y0": float(y0)}
                )
                assert ds.outcome_map.sel(x0=x0, y0=y0) == simulate(config).outcome
    result = CliRunner().invoke(main, ["plot", str(tmp_path), "-o", str(tmp_path / "m.png")])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "m.png").stat().st_size > 10_000
    # --boundary: a find_jump grid over the same keys draws; over other keys it is refused
    jump = tmp_path / "jump"
    jump.mkdir()
    (jump / "campaign.yaml").write_text("name: j\n")
    x0, y0 = ds.x0.values, ds.y0.values
    star = 0.125 + np.add.outer(x0, 0 * y0)
    xr.Dataset(
        {
            "mu_star": (("x0", "y0"), star),
            "status": (("x0", "y0"), np.full(star.shape, "converged")),
        },
        coords={"x0": x0, "y0": y0},
        attrs={"task": "find_jump"},
    ).to_netcdf(jump / "results.nc")
    args = ["plot", str(tmp_path), "--boundary", str(jump), "-o", str(tmp_path / "b.png")]
    assert CliRunner().invoke(main, args).exit_code == 0
    fraction_dir = tmp_path / "fractions"
    run_campaign(
        campaign_from_text(PIN_BASIN.replace("samples: 150", "samples: 4"), "<test>"),
        fraction_dir,
        workers=1,
        progress=False,
    )
    result = CliRunner().invoke(main, ["plot", str(fraction_dir), "--boundary", str(jump)])
    assert result.exit_code == 2 and "boundary: applies to a basin map" in result.output
