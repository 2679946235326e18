"""The map task end to end (its smoke test; its contract with the engine is
tests/test_task_contract.py): a small pin map in decide mode, whose run cells must each be
the verdict of a single run of their scene, and whose inferred cells (inside a uniform block
of the refinement) must be too."""

from __future__ import annotations

import pytest
import xarray as xr

from frictiondisk.engine.runner import run_campaign
from frictiondisk.simulation.simulate import simulate
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.map.figure import plot_map
from frictiondisk.tasks.map.table import summary_lines
from frictiondisk.verdict.outcomes import outcome_class

PIN_MAP = """\
name: pin_map_smoke
scene: pin
map:
  over: {params.omega_m: [0.8, 1.1, 1.4], params.mu: {start: 0.14, stop: 0.26, num: 7}}
  mode: decide
  stride: 3
"""


def test_a_map_names_each_cell_as_a_single_run_does(tmp_path):
    campaign = campaign_from_text(PIN_MAP)
    summary = run_campaign(campaign, tmp_path, workers=1, progress=False)
    with xr.open_dataset(tmp_path / "results.nc") as ds:
        ds = ds.load()
    points = campaign.points()
    ran = ds["ran"].values.ravel()
    motions = ds["motion"].values.ravel()
    assert summary.runs_total == int((ran == 1).sum()) < len(points)  # refinement saved runs
    assert (ran == 0).any() and (ran >= 0).all()
    for point, motion in zip(points, motions, strict=True):
        assert simulate(point.config).outcome == motion, point.coords
    # the stick/not-stick boundary is there and resolved to the grid step on every line
    assert {outcome_class(m) for m in motions} == {"stick", "not_stick"}
    for k in range(ds.sizes["omega_m"]):
        line = ds["motion"].isel(omega_m=k).values
        changes = [j for j in range(len(line) - 1) if line[j] != line[j + 1]]
        assert all(ran.reshape(ds["ran"].shape)[k, j : j + 2].min() == 1 for j in changes)
    assert ds["mu"].attrs["units"] == "1" and ds["omega_m"].attrs["units"] == "rad/s"
    assert ds.attrs["start"].startswith("rest")
    lines = summary_lines(ds)
    assert len(lines) == 1 + len(points)
    fig = plot_map(ds)
    assert len([a for a in fig.get_axes() if a.get_legend() is not None]) == 1
    # a traced boundary over the same two keys is drawn on top (`plot --boundary`), one
    # line per curve through its points; a trace over another plane, or results without mu_star,
    # are not
    trace = _trace_results("omega_m", [0.8, 1.1, 1.4], [0.2, 0.19, 0.18])
    fig = plot_map(ds, (trace,))
    lines = [line for line in fig.get_axes()[0].get_lines() if line.get_linestyle() == "-"]
    assert [list(line.get_xdata()) for line in lines] == [[0.8, 1.1, 1.4]]
    assert [list(line.get_ydata()) for line in lines] == [[0.2, 0.19, 0.18]]
    legend = [t.get_text() for t in fig.get_axes()[0].get_legend().get_texts()]
    assert "traced slide_cycle | stick, tol 0.0001" in legend
    with pytest.raises(ValueError, match="the trace runs over \\(x_ms, mu\\)"):
        plot_map(ds, (_trace_results("x_ms", [0.1, 0.2], [0.2, 0.2]),))
    with pytest.raises(ValueError, match="without mu_star"):
        plot_map(ds, (trace.drop_vars("mu_star"),))


def _trace_results(key: str, along: list[float], mu_star: list[float]) -> xr.Dataset:
    """A trace results.nc of one curve through (along, mu_star) over (key, mu): the
    variables and attributes a map's boundary reads."""
    return xr.Dataset(
        {
            key: ("point", along),
            "mu_star": ("point", mu_star),
            "curve_first_point": ("curve", [0]),
            "curve_points": ("curve", [len(along)]),
        },
        attrs={
            "task": "trace",
            "trace_key_var": key,
            "tol": 1e-4,
            "between": "[slide_cycle, stick]: each curve separates slide_cycle from stick",
        },
    )
