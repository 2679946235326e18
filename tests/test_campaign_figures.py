"""Campaign figures and `frictiondisk plot`: the four figure kinds drawn from synthetic
results (same variables and attributes as campaign/datasets.py writes, checked against real
tiny campaigns), and the command on real campaign directories, missing and damaged files."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib
import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner
from conftest import outside_the_figure
from matplotlib.container import ErrorbarContainer
from matplotlib.text import Text

matplotlib.use("Agg")


from frictiondisk import __version__
from frictiondisk.cli import main  # noqa: E402
from frictiondisk.engine.runner import run_campaign  # noqa: E402
from frictiondisk.figures.shared import MU_LABEL, axis_label, caption_text  # noqa: E402
from frictiondisk.model.auto_numerics import choose  # noqa: E402
from frictiondisk.model.scene import scene_from_dict  # noqa: E402
from frictiondisk.model.search_settings import CERTIFICATION_FLAGS  # noqa: E402
from frictiondisk.store import cf  # noqa: E402
from frictiondisk.store.measures import RUN_MEASURES  # noqa: E402
from frictiondisk.tasks.campaign import campaign_from_text  # noqa: E402
from frictiondisk.tasks.find_jump.figure_grid import plot_jump_grid  # noqa: E402
from frictiondisk.tasks.find_jump.figure_kind import figure_kind  # noqa: E402
from frictiondisk.tasks.find_jump.figure_line import plot_jump_line  # noqa: E402
from frictiondisk.tasks.find_jump.table import mu_star_table, uncertain_summary  # noqa: E402
from frictiondisk.tasks.plot import plot_campaign  # noqa: E402
from frictiondisk.tasks.scan.figure import figure_kind as scan_figure_kind  # noqa: E402
from frictiondisk.tasks.scan.figure import plot_scan_family, plot_scan_mu, scan_mode  # noqa: E402

NUMERICS_YAML = (
    "atol: 1.0e-09\ncycle_count: 3\ncycle_tol: 1.0e-06\ndt: 0.01\nh_max: 0.1\n"
    "horizon_budget: 8.0\nmax_events: 200000\nmax_steps: 2000000\nmethod: rodas4\nmode: decide\nrtol: 1.0e-06\n"
    "stick_rule: corotation\nstop_on_stick: true\nt_decide: 30.0\nt_max: 3000.0\nwindow_revs: 2.0\n"
)
MEASURES = {name: units for name, (units, _) in RUN_MEASURES.items()}  # name -> units
JUMP_ONLY_ATTRS = ("tol", "runs_saved_by_warm_start")  # results.nc of find_jump, not runs.nc
KEYS = {  # scene key -> (dimension, units, long_name) as datasets._key_attrs writes them
    "params.x_ms": ("x_ms", "m", "axes offset: the slave's rest position is (x_ms, 0) [m]"),
    "params.x0": ("x0", "m", "initial spring deflection: the slave starts at x_ms + x0 [m]"),
    "params.mu": ("mu", "1", "static friction coefficient [1]"),
}


# ---- synthetic Datasets ------------------------------------------------------------------
CF_GLOBALS = ("Conventions", "title", "institution", "source", "history", "references")


def _coord(key, values):
    dim, units, long_name = KEYS[key]
    attrs = {"long_name": long_name, "scene_key": key, "units": units}
    return dim, (dim, np.asarray(values, float), attrs)


def _attrs(name, task, unfixed=(), **extra):
    return {
        "campaign_name": name,
        "task": task,
        "campaign_yaml": f"name: {name}\nscene: pin\n{task}: {{}}\n",
        "numerics_yaml": NUMERICS_YAML,
        "frictiondisk_version": __version__,
        "kernel_version": "0123456789abcdef",
        **cf.scene_attrs(scene_from_dict({"scene": "pin"}), unfixed),
        **{key: f"synthetic {key}" for key in CF_GLOBALS},
        **extra,
    }


def jump_results(
    along, mu_lo, mu_hi, status=None, reason=None, monotone=None, name="synth", certification=None
):
    """A find_jump results.nc over `along` ({scene key: values}, 1 or 2 keys)."""
    coords = dict(_coord(k, v) for k, v in along.items())
    dims = tuple(coords)
    mu_lo, mu_hi = np.asarray(mu_lo, float), np.asarray(mu_hi, float)
    shape = mu_lo.shape
    status = np.asarray(status if status is not None else np.full(shape, "converged"), str)
    reason = np.asarray(reason if reason is not None else np.full(shape, "bracket ok"), str)
    monotone = np.asarray(monotone if monotone is not None else np.ones(shape), np.int8)
    certified = np.full(shape, CERTIFICATION_FLAGS.index("certified"), np.int8)
    certification = np.asarray(
        certified
        if certification is None
        else [CERTIFICATION_FLAGS.index(c) for c in certification],
        np.int8,
    ).reshape(shape)
    nan = np.full(shape, np.nan)
    var = {
        "mu_star": (0.5 * (mu_lo + mu_hi), "1"),
        "mu_lo": (mu_lo, "1"),
        "mu_hi": (mu_hi, "1"),
        "outcome_lo": (np.full(shape, "slide"), None),
        "outcome_hi": (np.full(shape, "stick"), None),
        "size_lo": (nan, "m"),
        "size_hi": (nan + 0.1, "m"),
        "R1_hi": (nan + 0.1, "m"),
        "n_runs": (np.full(shape, 9, np.int64), "1"),
        "runs_search": (np.full(shape, 7, np.int64), "1"),
        "runs_prescan": (np.zeros(shape, np.int64), "1"),
        "runs_certification": (np.full(shape, 2, np.int64), "1"),
        "status": (status, None),
        "reason": (reason, None),
        "monotone": (monotone, None),
        "warm_start": (np.zeros(shape, np.int8), None),
        "certification": (certification, None),
        "verdict_horizon": (np.full(shape, 30.0), "s"),
        "verdict_rtol": (np.full(shape, 1e-6), "1"),
    }
    data_vars = {
        k: (dims, v, {"long_name": k, **({"units": u} if u else {})}) for k, (v, u) in var.items()
    }
    data_vars["certification"][2]["flag_meanings"] = " ".join(CERTIFICATION_FLAGS)
    return xr.Dataset(
        data_vars,
        coords=coords,
        attrs=_attrs(
            name,
            "find_jump",
            {"params.mu", *along},
            tol=1e-3,
            runs_saved_by_warm_start=0,
            **choose(1e-3, ["pin"], {}).attrs(),
        ),
    )


def jump_runs(results, per_point):
    """A runs.nc: per point (C order) a list of (mu, outcome)."""
    dims = list(results["mu_star"].dims)
    grids = [g.reshape(-1) for g in np.meshgrid(*[results[d].values for d in dims], indexing="ij")]
    rows = [(i, mu, out) for i, runs in enumerate(per_point) for mu, out in runs]
    n = len(rows)
    data_vars = {
        "point": ("run", np.asarray([r[0] for r in rows], np.int64), {}),
        "mu": ("run", np.asarray([r[1] for r in rows], float), {"units": "1"}),
        "level": ("run", np.zeros(n, np.int64), {}),
        "strict": ("run", np.zeros(n, np.int64), {}),
        "mode": ("run", np.full(n, "decide"), {}),
        "role": ("run", np.full(n, "search"), {}),
        "outcome": ("run", np.asarray([r[2] for r in rows], str), {}),
        "reason": ("run", np.full(n, "why"), {}),
        "decided_by": ("run", np.full(n, "corotation"), {}),
        "key": ("run", np.full(n, "0" * 64), {}),
        "wall_s": ("run", np.full(n, 0.001), {"units": "s"}),
    }
    for d, g in zip(dims, grids, strict=True):
        attrs = results[d].attrs
        data_vars[d] = ("run", np.asarray([g[r[0]] for r in rows], float), dict(attrs))
    for name, units in MEASURES.items():
        data_vars[name] = ("run", np.full(n, np.nan), {"units": units})
    return xr.Dataset(
        data_vars, attrs={k: v for k, v in results.attrs.items() if k not in JUMP_ONLY_ATTRS}
    )


def scan_results(mu, outcome, size, a, along=None, name="synth_scan", mode="converge"):
    """A scan results.nc over mu (and `along`: {scene key: values}, the second dimension)."""
    items = [_coord("params.mu", mu)] + [_coord(k, v) for k, v in (along or {}).items()]
    coords = dict(items)
    dims = tuple(coords)
    outcome = np.asarray(outcome, str)
    shape = outcome.shape
    data_vars = {
        "outcome": (dims, outcome, {"long_name": "outcome"}),
        "reason": (dims, np.char.add("reason of ", outcome), {"long_name": "why"}),
        "cycle_converged": (dims, (outcome == "stick_slip").astype(np.int8), {}),
    }
    for k, units in MEASURES.items():
        values = {"size": size, "a": a}.get(k, np.full(shape, np.nan))
        data_vars[k] = (dims, np.asarray(values, float), {"units": units, "long_name": k})
    attrs = _attrs(name, "scan", {"params.mu", *(along or {})})
    attrs["campaign_yaml"] = f"name: {name}\nscene: pin\nscan:\n  mode: {mode}\n"
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


# ---- helpers to read a figure --------------------------------------------------------------
def all_text(fig) -> str:
    return "\n".join(t.get_text() for t in fig.findobj(Text))


def by_gid(ax, gid):
    return [a for a in ax.get_children() if a.get_gid() == gid]


def main_axes(fig):
    """Axes holding data (not the colour bar)."""
    return [ax for ax in fig.get_axes() if ax.get_label() != "<colorbar>"]


def errorbar_spans(container: ErrorbarContainer):
    """(x, low end, high end) of every error bar of the container."""
    segments = container.lines[2][0].get_segments()
    return np.array([[s[0][0], min(s[0][1], s[1][1]), max(s[0][1], s[1][1])] for s in segments])


def text_with(fig, needle) -> Text:
    (found,) = [t for t in fig.findobj(Text) if t.get_text() == needle]
    return found


# ---- find_jump along a line ----------------------------------------------------------------
X_MS = [0.05, 0.075, 0.1, 0.125, 0.15]
LO = [0.0630, 0.0948, 0.1265, np.nan, 0.1880]
HI = [0.0640, 0.0953, 0.1270, np.nan, 0.1920]
STATUS = ["converged", "converged", "converged", "failed", "failed"]
REASON = [
    "bracket of width 0.001 <= tol 0.001",
    "bracket of width 0.0005 <= tol 0.001",
    "bracket of width 0.0005 <= tol 0.001",
    "no stick up to the limit: mu_lo = 0.3 gave slide, mu_hi = 10 (= limit) gave slide",
    "undetermined after 2 retries with longer horizons: step size underflow",
]


@pytest.fixture
def line():
    return jump_results(
        {"params.x_ms": X_MS}, LO, HI, STATUS, REASON, monotone=[1, 0, 1, 1, 1], name="lineA"
    )


def test_points_without_a_jump_are_marked_at_the_top_not_listed_as_failed():
    status = ["converged", "converged", "converged", "no_jump", "failed"]
    reason = [*REASON[:3], "no jump: no value from mu = 0.03 to 0.6 sticks", REASON[4]]
    data = jump_results({"params.x_ms": X_MS}, LO, HI, status, reason)
    fig = plot_jump_line(data)
    (ax,) = main_axes(fig)[:1]
    (mark,) = by_gid(ax, "no_jump")
    np.testing.assert_allclose(mark.get_xdata(), [0.125])
    assert mark.get_ydata()[0] > 0.9  # axes fraction: the top edge, mu* above the view
    assert not by_gid(ax, "failed_points")  # 0.15 kept its bracket; 0.125 is no failure
    text = all_text(fig)
    assert "failed points (1)" in text and "x_ms = 0.125 m" not in text
    assert "no jump: no value of the grid sticks" in all_text(fig)
    assert outside_the_figure(fig) == []
    # on a grid: a grey cell that says so, not a hatched failure
    grid = jump_results(
        {"params.x_ms": X_MS[:2], "params.x0": [0.0, 0.01]},
        np.array([[0.06, np.nan], [0.09, 0.095]]),
        np.array([[0.061, np.nan], [0.091, 0.096]]),
        np.array([["converged", "no_jump"], ["converged", "converged"]]),
        np.array([["ok", "no jump: none sticks"], ["ok", "ok"]]),
    )
    ax = main_axes(plot_jump_grid(grid))[0]
    assert len(by_gid(ax, "no_jump_cell")) == 1 and not by_gid(ax, "failed_cell")


def test_uncertain_points_are_hollow_named_in_the_legend_and_summed_up():
    flags = ["certified", "uncertain", "recertified", "certified", "uncertain"]
    data = jump_results(
        {"params.x_ms": X_MS}, LO, HI, ["converged"] * 5, REASON, certification=flags
    )
    fig = plot_jump_line(data)
    (ax,) = main_axes(fig)[:1]
    (hollow,) = by_gid(ax, "uncertain")
    np.testing.assert_allclose(hollow.get_xdata(), [0.075, 0.15])  # 0.125 has no bracket
    assert hollow.get_markerfacecolor() == "white"
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(t.startswith("uncertain") for t in legend)
    assert uncertain_summary(data) == "2 of 5 points uncertain: x_ms = 0.075; x_ms = 0.15"
    assert mu_star_table(data)[0].startswith("mu* per point")
    assert [row.split()[-1] for row in mu_star_table(data)[2:]] == flags
    certified = jump_results({"params.x_ms": X_MS}, LO, HI, ["converged"] * 5, REASON)
    assert uncertain_summary(certified) is None
    assert not by_gid(main_axes(plot_jump_line(certified))[0], "uncertain")


def test_jump_line_bars_span_the_brackets_and_failures_are_listed(line):
    assert figure_kind(line) == "jump_line"
    fig = plot_jump_line(line)
    (ax,) = main_axes(fig)[:1]
    assert ax.get_xlabel() == "axes offset x_ms [m]"
    assert ax.get_ylabel() == MU_LABEL == "friction coefficient \u03bc [-]"

    (bars,) = [c for c in ax.containers if c.get_label().startswith("\u03bc*")]
    np.testing.assert_allclose(errorbar_spans(bars), np.column_stack([X_MS, LO, HI])[:3])
    data_x, data_y = bars.lines[0].get_data()
    np.testing.assert_allclose(data_y, 0.5 * (np.array(LO) + np.array(HI))[:3])
    # the failed point that kept a bracket is drawn with it, in its own container
    (partial,) = [c for c in ax.containers if c.get_label().startswith("failed")]
    np.testing.assert_allclose(errorbar_spans(partial), [[0.15, 0.1880, 0.1920]])
    # the failed point without a bracket: a mark at the bottom, at its x
    (rug,) = by_gid(ax, "failed_points")
    np.testing.assert_allclose(rug.get_xdata(), [0.125])
    assert rug.get_ydata()[0] < 0.1  # axes fraction: the bottom strip
    (separator,) = by_gid(ax, "rug_line")  # ... set off from the data
    assert separator.get_ydata()[0] < np.nanmin(LO)
    (ring,) = by_gid(ax, "non_monotone")
    np.testing.assert_allclose(ring.get_xdata(), [0.075])

    text = all_text(fig)
    assert "failed points (2)" in text
    assert "x_ms = 0.125 m: no stick up to the limit" in text
    assert "x_ms = 0.15 m: undetermined after 2 retries" in text
    assert "bracket of width 0.001 <= tol" not in text  # converged points are not listed
    assert "campaign lineA" in caption_text(line) and "campaign lineA" in text


def test_no_legend_entry_or_text_of_a_busy_jump_line_is_clipped(line):
    """The disk line with prescan jumps drew 'non-monotone: a run contradicts a single...'
    past the right edge: a line with every kind of legend entry (non-monotone, uncertain,
    failed with and without a bracket, further and falling jumps, runs above the view)."""
    flags = ["certified", "uncertain", "certified", "certified", "certified"]
    data = jump_results(
        {"params.x_ms": X_MS},
        LO,
        HI,
        STATUS,
        REASON,
        monotone=[1, 0, 1, 1, 1],
        name="busy_line",
        certification=flags,
    )
    jumps = np.full((5, 3), np.nan)
    rising = np.full((5, 3), -1, np.int8)
    jumps_lo, jumps_hi = jumps.copy(), jumps.copy()
    jumps_lo[:, 0], jumps_hi[:, 0], rising[:, 0] = LO, HI, 1
    jumps_lo[1, 1:], jumps_hi[1, 1:], rising[1, 1:] = [0.20, 0.25], [0.201, 0.251], [0, 1]
    data = data.assign(
        jump_mu_lo=(("x_ms", "jump"), jumps_lo),
        jump_mu_hi=(("x_ms", "jump"), jumps_hi),
        jump_rising=(("x_ms", "jump"), rising),
    )
    runs = jump_runs(data, [[(0.09, "slide"), (3.0, "stick")]] * 5)
    for fig in (plot_jump_line(data), plot_jump_line(data, runs, show_runs=True)):
        legend = [t.get_text() for t in main_axes(fig)[0].get_legend().get_texts()]
        assert any(t.startswith("non-monotone") for t in legend), legend
        assert any(t.startswith("falling jump") for t in legend), legend
        assert outside_the_figure(fig) == []


def test_jump_line_regions_sit_on_their_side_of_the_line(line):
    fig = plot_jump_line(line)
    ax = main_axes(fig)[0]
    ok = np.array(STATUS) == "converged"
    xs, mu = np.array(X_MS)[ok], (0.5 * (np.array(LO) + np.array(HI)))[ok]
    for label, sign in (("pure sticking", 1), ("outer limit cycle", -1)):
        t = text_with(fig, label)
        x, y = ax.transLimits.inverted().transform(t.get_position())  # axes -> data
        assert sign * (y - np.interp(x, xs, mu)) > 0, (label, x, y)


def test_jump_line_runs_overlay_puts_every_run_at_its_coordinate(line):
    runs = jump_runs(
        line,
        [
            [(0.05, "slide"), (0.3, "stick"), (0.0640, "stick")],
            [(0.05, "stick_slip"), (0.3, "stick")],
            [(0.3, "stick"), (0.1265, "slide")],
            [(0.3, "slide"), (10.0, "slide")],
            [(0.19, "undetermined")],
        ],
    )
    fig = plot_campaign(line, runs, show_runs=True)
    ax = main_axes(fig)[0]
    dots = {
        line2d.get_marker() + str(line2d.get_markerfacecolor()): line2d
        for line2d in ax.get_lines()
        if line2d.get_markersize() == 3.0
    }
    xy = {k: sorted(zip(v.get_xdata(), v.get_ydata(), strict=True)) for k, v in dots.items()}
    points = sorted(p for v in xy.values() for p in v)
    view = runs["mu"].values <= 2 * np.nanmax(HI)  # mu = 10 (widened to the limit) is not
    expected = sorted(zip(runs["x_ms"].values[view], runs["mu"].values[view], strict=True))
    np.testing.assert_allclose(points, expected)
    (above,) = by_gid(ax, "runs_above")  # ... it is marked at the top edge instead
    np.testing.assert_allclose(above.get_xdata(), [0.125])
    assert ax.get_ylim()[1] < 1.0
    # every outcome its own legend entry (the one style table), in the listing order
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    runs_legend = [t for t in legend if t.startswith("run: ")]
    assert runs_legend == ["run: stick", "run: stick_slip", "run: slide", "run: undetermined"]
    with pytest.raises(ValueError, match="runs Dataset"):
        plot_jump_line(line, None, show_runs=True)


def test_jump_line_where_nothing_converged_says_so():
    ds = jump_results(
        {"params.x_ms": [0.1, 0.2]},
        [np.nan, np.nan],
        [np.nan, np.nan],
        ["failed", "failed"],
        ["bracket inverted: a", "bracket inverted: b"],
    )
    text = all_text(plot_jump_line(ds))
    assert "no point converged" in text and "bracket inverted: b" in text


# ---- find_jump over a grid -----------------------------------------------------------------
def test_jump_grid_maps_mu_star_and_hatches_failed_cells():
    x_ms, x0 = [0.05, 0.1, 0.15], [-0.01, 0.01]
    lo = np.array([[0.060, 0.065], [0.120, 0.125], [np.nan, 0.190]])
    hi = lo + 0.001
    status = np.where(np.isnan(lo), "failed", "converged")
    reason = np.where(np.isnan(lo), "no stick up to the limit: grid cell", "ok")
    ds = jump_results({"params.x_ms": x_ms, "params.x0": x0}, lo, hi, status, reason, name="gridB")
    assert figure_kind(ds) == "jump_grid"
    fig = plot_jump_grid(ds, show_runs=True)
    ax = main_axes(fig)[0]
    assert ax.get_xlabel() == "axes offset x_ms [m]"
    assert ax.get_ylabel() == "initial spring deflection x0 [m]"
    (mesh,) = by_gid(ax, "mu_star")
    shown = np.ma.masked_invalid(mesh.get_array()).reshape(2, 3).T  # (x0, x_ms) -> (x_ms, x0)
    np.testing.assert_allclose(shown.filled(np.nan), np.where(np.isnan(lo), np.nan, lo + 0.0005))
    (cell,) = by_gid(ax, "failed_cell")
    assert cell.get_hatch() == "xx"
    assert cell.get_x() < 0.15 < cell.get_x() + cell.get_width()
    assert cell.get_y() < -0.01 < cell.get_y() + cell.get_height()
    (cbar_ax,) = [a for a in fig.get_axes() if a.get_label() == "<colorbar>"]
    assert "\u03bc*" in cbar_ax.get_ylabel()
    text = all_text(fig)
    assert "x_ms = 0.15 m, x0 = -0.01 m: no stick up to the limit: grid cell" in text
    assert "9 runs" in text  # --runs on a grid: run counts
    assert "campaign gridB" in text
    assert outside_the_figure(fig) == []
    # every legend entry at once (a failed cell, a non-monotone one): still inside
    monotone = [[1, 0], [1, 1], [1, 1]]
    busy = jump_results(
        {"params.x_ms": x_ms, "params.x0": x0}, lo, hi, status, reason, monotone=monotone
    )
    assert outside_the_figure(plot_jump_grid(busy, show_runs=True)) == []


# ---- scans ---------------------------------------------------------------------------------
def test_scan_mu_size_by_outcome_and_a_with_its_least_squares_line():
    mu = np.round(np.arange(0.10, 0.1351, 0.005), 4)  # 8 values
    outcome = [
        "slide",
        "stick_slip",
        "stick_slip",
        "stick_slip",
        "undetermined",
        "stick_slip",
        "stick",
        "stick",
    ]
    a = np.where(np.array(outcome) == "stick_slip", 2.0 * mu - 0.2, np.nan)  # a = 2 m * mu - ...
    size = np.where(np.array(outcome) == "stick_slip", 3 * mu, np.nan)
    size[-2:] = 0.11
    ds = scan_results(mu, outcome, size, a, name="scanC")
    assert scan_figure_kind(ds) == "scan_mu"
    fig = plot_scan_mu(ds)
    ax_size, ax_a = main_axes(fig)
    assert ax_size.get_shared_x_axes().joined(ax_size, ax_a)
    assert ax_size.get_ylabel().endswith("[m]") and ax_a.get_ylabel().endswith("[m]")
    assert ax_a.get_xlabel() == MU_LABEL

    (stick,) = by_gid(ax_size, "stick")
    np.testing.assert_allclose(stick.get_xdata(), mu[-2:])
    (cycles,) = by_gid(ax_size, "stick_slip")
    np.testing.assert_allclose(cycles.get_ydata(), size[[1, 2, 3, 5]])
    (slide,) = by_gid(ax_size, "slide_rug")  # no size: on the bottom edge
    np.testing.assert_allclose(slide.get_xdata(), [0.10])
    (undetermined,) = by_gid(ax_size, "undetermined_rug")
    assert undetermined.get_marker() == "x"
    assert matplotlib.colors.same_color(undetermined.get_color(), "tab:red")

    (fit,) = by_gid(ax_a, "a_fit")
    assert "slope 2 m" in fit.get_label()
    np.testing.assert_allclose(fit.get_ydata(), 2.0 * fit.get_xdata() - 0.2)
    assert "numerics rodas4, rtol 1e-06" in all_text(fig)
    assert "mode converge" in caption_text(ds, scan_mode(ds))
    assert outside_the_figure(fig) == []


def test_scan_mu_in_decide_mode_says_why_a_is_missing():
    mu = [0.12, 0.125, 0.13]
    ds = scan_results(
        mu,
        ["stick_slip", "stick_slip", "stick"],
        [np.nan, np.nan, 0.11],
        [np.nan] * 3,
        mode="decide",
    )
    fig = plot_scan_mu(ds)
    assert "no converged stick_slip cycle" in all_text(fig)
    assert "mode decide" in caption_text(ds, scan_mode(ds))


def test_scan_family_one_curve_per_value_with_its_unit():
    mu = [0.12, 0.125, 0.13]
    outcome = [["stick_slip", "stick", "stick"], ["stick_slip", "stick_slip", "stick"]]
    size = [[0.3, 0.1, 0.1], [0.3, 0.35, 0.1]]
    ds = scan_results(
        mu,
        np.array(outcome).T,
        np.array(size).T,
        np.full((3, 2), np.nan),
        along={"params.x0": [-0.01, 0.01]},
        name="famD",
    )
    assert scan_figure_kind(ds) == "scan_family"
    fig = plot_scan_family(ds)
    ax = main_axes(fig)[0]
    assert ax.get_xlabel() == MU_LABEL and ax.get_ylabel().endswith("[m]")
    for k in range(2):
        (curve,) = by_gid(ax, f"family{k}")
        np.testing.assert_allclose(curve.get_ydata(), size[k])
    legend_text = {t.get_text() for t in fig.findobj(Text)}
    assert {"x0 = -0.01 m", "x0 = 0.01 m", "stick", "stick_slip (limit cycle)"} <= legend_text
    assert "campaign famD" in all_text(fig)
    assert outside_the_figure(fig) == []


# ---- labels, caption, refusals -----------------------------------------------------------
def test_axis_label_and_caption_from_attributes(line):
    assert axis_label(line["x_ms"]) == "axes offset x_ms [m]"
    caption = caption_text(line)
    for part in (
        "campaign lineA",
        "task find_jump",
        "tol 0.001",
        "rodas4",
        "rtol 1e-06",
        "t_decide 30 s",
        f"frictiondisk {__version__}",
    ):
        assert part in caption


def test_a_dataset_that_is_not_a_campaign_result_is_refused(line):
    with pytest.raises(
        ValueError, match="expected one of find_jump, scan, trajectory, basin, trace, map"
    ):
        plot_campaign(xr.Dataset(attrs={"task": "orbit"}))
    with pytest.raises(ValueError, match="lacks the variable"):
        figure_kind(line.drop_vars("mu_hi"))
    with pytest.raises(ValueError, match="lacks the variable"):  # a scan is no line
        plot_jump_line(scan_results([0.1], ["stick"], [0.1], [np.nan]))


def test_figures_module_never_loads_the_kernel():
    code = (
        "import sys, frictiondisk.tasks.plot, frictiondisk.cli.plot;"
        "bad = [m for m in sys.modules if m.startswith(('frictiondisk.kernel', "
        "'frictiondisk.simulation.simulate', 'numba'))]; assert not bad, bad"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


# ---- real campaigns: the synthetic layout matches, and the command ----------------------
TINY_LINE = """\
name: tiny_line
scene: pin
numerics: {t_decide: 20.0}
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-2
  along:
    params.x_ms: [0.05, 0.1]
"""
TINY_SCAN = """\
name: tiny_scan
scene: pin
params: {x_ms: 0.1}
numerics: {t_max: 2000.0}
scan:
  mu: [0.12, 0.125, 0.13]
  mode: converge
"""


@pytest.fixture(scope="module")
def campaign_dirs(tmp_path_factory):
    root = tmp_path_factory.mktemp("campaigns")
    dirs = {}
    for name, text in (("line", TINY_LINE), ("scan", TINY_SCAN)):
        dirs[name] = root / name
        run_campaign(campaign_from_text(text, "<test>"), dirs[name], 1, None, False)
    return dirs


def _layout(ds):
    return (
        set(ds.data_vars),
        set(ds.attrs),
        {name: set(ds[name].attrs) for name in ds.coords},
        {name: ds[name].dtype.kind for name in ds.data_vars},
    )


def test_synthetic_datasets_have_the_layout_of_real_ones(campaign_dirs, line):
    with xr.open_dataset(campaign_dirs["line"] / "results.nc") as real:
        assert _layout(real.load()) == _layout(line)
    with xr.open_dataset(campaign_dirs["line"] / "runs.nc") as real:
        synth = jump_runs(line, [[(0.1, "stick")]] * 5)
        assert set(real.data_vars) == set(synth.data_vars)
        assert set(real.attrs) == set(synth.attrs)
    with xr.open_dataset(campaign_dirs["scan"] / "results.nc") as real:
        synth = scan_results([0.1, 0.2], ["stick", "slide"], [0.1, np.nan], [np.nan] * 2)
        assert _layout(real.load()) == _layout(synth)


def test_plot_writes_a_png_into_the_campaign_directory(campaign_dirs):
    for name in ("line", "scan"):
        out = campaign_dirs[name]
        result = CliRunner().invoke(main, ["plot", str(out)])
        assert result.exit_code == 0, result.output
        target = out / "figure.png"
        assert str(target.resolve()) in result.output
        image = matplotlib.image.imread(target)
        assert image.ndim == 3 and image.shape[0] > 500 and image.shape[1] > 500


def test_plot_runs_overlay_to_pdf(campaign_dirs, tmp_path):
    target = tmp_path / "sub" / "x.pdf"
    result = CliRunner().invoke(
        main, ["plot", str(campaign_dirs["line"]), "-o", str(target), "--runs"]
    )
    assert result.exit_code == 0, result.output
    assert target.read_bytes().startswith(b"%PDF")
    assert str(target.resolve()) in result.output


def test_plot_refuses_an_unknown_suffix(campaign_dirs, tmp_path):
    result = CliRunner().invoke(
        main, ["plot", str(campaign_dirs["line"]), "-o", str(tmp_path / "x.jpg")]
    )
    assert result.exit_code == 2
    assert "suffix" in result.stderr and not (tmp_path / "x.jpg").exists()


@pytest.mark.parametrize("damage", ["missing", "truncated", "garbage"])
def test_plot_without_a_readable_results_file_exits_2_and_names_it(campaign_dirs, tmp_path, damage):
    out = tmp_path / "copy"
    shutil.copytree(campaign_dirs["line"], out)
    (out / "figure.png").unlink(missing_ok=True)  # drawn by an earlier test
    results = out / "results.nc"
    if damage == "missing":
        results.unlink()
    elif damage == "truncated":
        results.write_bytes(results.read_bytes()[: results.stat().st_size // 3])
    else:
        results.write_bytes(b"not netcdf at all\n")
    result = CliRunner().invoke(main, ["plot", str(out)])
    assert result.exit_code == 2
    assert str(results) in result.stderr
    assert f"frictiondisk resume {out}" in result.stderr
    assert "Traceback" not in result.output + result.stderr
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert not (out / "figure.png").exists()


def test_plot_on_a_directory_that_is_no_campaign(tmp_path):
    result = CliRunner().invoke(main, ["plot", str(tmp_path)])
    assert result.exit_code == 2
    assert str(tmp_path / "results.nc") in result.stderr
    assert "not a campaign directory" in result.stderr
    assert "Traceback" not in result.output + result.stderr


def test_plot_runs_with_a_damaged_runs_file(campaign_dirs, tmp_path):
    out = tmp_path / "copy"
    shutil.copytree(campaign_dirs["line"], out)
    (out / "runs.nc").write_bytes(b"\x89HDF\r\n")
    assert CliRunner().invoke(main, ["plot", str(out)]).exit_code == 0  # runs.nc not needed
    result = CliRunner().invoke(main, ["plot", str(out), "--runs"])
    assert result.exit_code == 2
    assert str(out / "runs.nc") in result.stderr and "frictiondisk resume" in result.stderr


def test_plot_needs_no_results_beyond_its_files(campaign_dirs, tmp_path):
    """Only results.nc (and runs.nc) are read: no journal, no campaign.yaml needed to draw."""
    out = tmp_path / "bare"
    out.mkdir()
    for name in ("results.nc", "runs.nc", "campaign.yaml"):
        shutil.copy(campaign_dirs["line"] / name, out / name)
    result = CliRunner().invoke(main, ["plot", str(out), "--runs"])
    assert result.exit_code == 0, result.output
    assert Path(out / "figure.png").is_file()
