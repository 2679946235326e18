"""Figures and tables say what they show: a `between` find_jump names its two motions in
the title, the legend and the region labels, with each run in its outcome's style; a
find_jump bisecting another key names that key and its unit, not mu."""

from __future__ import annotations

import dataclasses
import sys

import numpy as np
import pytest
import xarray as xr
from matplotlib.colors import to_hex

from frictiondisk.engine.runner import run_campaign
from frictiondisk.figures.footer import footer_text
from frictiondisk.figures.shared import OUTCOME_STYLE
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.find_jump.table import table_lines
from frictiondisk.tasks.plot import figure_for_dir
from frictiondisk.verdict.outcomes import record

sys.path.insert(0, "tests")
from fake_simulate import install  # noqa: E402

# the fake's stick side becomes slide_cycle, its stick_slip side self_centring
RENAMED = {"stick": "slide_cycle", "stick_slip": "self_centring"}


def _two_motions(monkeypatch):
    """The fake simulate (stick where mu >= 1.2 x_ms) with its verdicts renamed: a
    boundary between self_centring (below) and slide_cycle (above)."""
    from frictiondisk.simulation import simulate as simulate_module

    fake = install(monkeypatch)

    def renamed(config, record=False, dt_out=0.0):
        result = fake(config, record, dt_out)
        return dataclasses.replace(result, outcome=RENAMED[result.outcome])

    monkeypatch.setattr(simulate_module, "simulate", renamed)


def _run(text, tmp_path, monkeypatch):
    _two_motions(monkeypatch)
    run_campaign(campaign_from_text(text), tmp_path, workers=1, progress=False)
    return xr.load_dataset(tmp_path / "results.nc")


BETWEEN = """\
name: two_motions
scene: pin
params: {c_s: 1.5, y0: 0.01}
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-3
  between: [self_centring, slide_cycle]
  along: {params.x_ms: [0.08, 0.1, 0.12]}
"""


def _legend_texts(fig) -> list[str]:
    ax = fig.get_axes()[0]
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_plot_of_a_between_campaign_titles_and_labels_both_motions(tmp_path, monkeypatch):
    _run(BETWEEN, tmp_path, monkeypatch)
    fig = figure_for_dir(tmp_path, show_runs=True)
    (title,) = [sub._suptitle.get_text() for sub in fig.subfigs if sub._suptitle is not None]
    assert record("self_centring").legend in title and record("slide_cycle").legend in title
    assert "pure sticking" not in title and "outer limit cycle" not in title
    legend = _legend_texts(fig)
    assert "run: self_centring" in legend and "run: slide_cycle" in legend
    assert not any("stick" in text for text in legend), legend
    # the footer names every scene key off its default (c_s, y0), not the varied x_ms
    footer = footer_text(fig)
    assert "c_s 1.5 N/m" in footer and "y0 0.01 m" in footer and "x_ms" not in footer
    ax = fig.get_axes()[0]
    regions = {t.get_text(): t for t in ax.texts if t.get_text() in RENAMED.values()}
    assert set(regions) == {"self_centring", "slide_cycle"}
    # each side's label in its outcome's edge colour, above and below the line
    for name, text in regions.items():
        assert to_hex(text.get_color()) == to_hex(OUTCOME_STYLE[name]["edge"])
    assert regions["slide_cycle"].get_position()[1] > regions["self_centring"].get_position()[1]
    # the run dots: one style per outcome, from the one style table
    dots = {
        to_hex(line.get_color()): line.get_marker()
        for line in ax.get_lines()
        if line.get_xdata().size
    }
    for name in RENAMED.values():
        style = OUTCOME_STYLE[name]
        assert dots.get(to_hex(style["color"])) == style["marker"]


BISECT_X_MS = """\
name: in_xms
scene: pin
find_jump:
  parameter: params.x_ms
  bracket: [0.05, 0.2]
  tol: 1.0e-4
  between: [slide_cycle, self_centring]
  along: {params.mu: [0.15, 0.18]}
"""


def test_a_find_jump_in_another_key_names_it_and_its_unit(tmp_path, monkeypatch):
    """Bisecting x_ms: the table's heads, the figure's y axis and legend name x_ms [m]."""
    results = _run(BISECT_X_MS, tmp_path, monkeypatch)
    assert np.allclose(results["mu_star"].values, [0.125, 0.15], atol=1e-4)
    text = "\n".join(table_lines(results))
    assert "x_ms* [m]" in text and "bracket [x_ms_lo, x_ms_hi]" in text
    assert "mu*" not in text and "mu_lo" not in text
    fig = figure_for_dir(tmp_path)
    ax = fig.get_axes()[0]
    assert ax.get_ylabel().endswith("x_ms [m]") and "\u03bc" not in ax.get_ylabel()
    assert any(t.startswith("x_ms* with its bracket") for t in _legend_texts(fig))
    # runs.nc: `mu` holds the bisected x_ms, `point_mu` each run's mu along the points
    runs = xr.load_dataset(tmp_path / "runs.nc")
    assert runs["mu"].attrs["units"] == "m" and "x_ms" in runs["mu"].attrs["long_name"]
    assert np.all((runs["mu"] >= 0.05 - 1e-12) & (runs["mu"] <= 0.2 + 1e-12))
    expected = np.asarray([0.15, 0.18])[runs["point"].values]
    assert np.array_equal(runs["point_mu"].values, expected)


@pytest.mark.parametrize("between", [None, "[self_centring, slide_cycle]"])
def test_the_stick_jump_keeps_its_paper_labels(between):
    from frictiondisk.tasks.find_jump.figure_line import line_title, region_labels

    ds = xr.Dataset(attrs={} if between is None else {"between": between})
    if between is None:
        assert line_title(ds) == "jump \u03bc* from the outer limit cycle to pure sticking"
        assert [r[0] for r in region_labels(ds)] == ["pure sticking", "outer limit cycle"]
    else:
        assert [r[0] for r in region_labels(ds)] == ["slide_cycle", "self_centring"]


MAP = """\
name: xms_map
scene: pin
map:
  over: {params.x_ms: [0.08, 0.1, 0.12], params.mu: {start: 0.05, stop: 0.2, num: 7}}
  mode: converge
  stride: 1
"""


def test_a_map_takes_a_between_find_jump_as_its_boundary_and_marks_cells_as_its_log(
    tmp_path, monkeypatch
):
    """`plot MAP --boundary DIR` draws any results with a mu_star: here a find_jump between
    two motions along the map's x_ms; the cells crossed as not settled are those the log
    calls "not settled" (the fake's slide_cycle side reports no converged cycle)."""
    from frictiondisk.tasks.map.table import summary_lines

    _run(BETWEEN, tmp_path / "jump", monkeypatch)
    run_campaign(campaign_from_text(MAP), tmp_path / "map", workers=1, progress=False)
    fig = figure_for_dir(tmp_path / "map", boundary=[tmp_path / "jump"])
    ax = fig.get_axes()[0]
    legend = _legend_texts(fig)
    assert any(t.startswith("find_jump self_centring | slide_cycle") for t in legend), legend
    jump = xr.load_dataset(tmp_path / "jump" / "results.nc")
    drawn = [line for line in ax.get_lines() if line.get_linestyle() == "-"]
    np.testing.assert_allclose(drawn[0].get_ydata(), jump["mu_star"].values)
    results = xr.load_dataset(tmp_path / "map" / "results.nc")
    lines = summary_lines(results)[1:]
    unsettled_log = sum(", not settled" in line for line in lines)
    crosses = [line for line in ax.get_lines() if line.get_gid() == "cells_unsettled"]
    drawn_crosses = crosses[0].get_xdata().size if crosses else 0
    assert unsettled_log == drawn_crosses > 0
