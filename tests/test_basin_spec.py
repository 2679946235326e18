"""Basin campaigns without simulation: validation messages, deterministic samples, the
binomial statistics, the adaptive stop rule, results layout and figures (fed fake runs)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure

from frictiondisk.figures.outcome_colors import outcome_colors
from frictiondisk.model.scene import ConfigError
from frictiondisk.tasks.basin import stats as basin_stats
from frictiondisk.tasks.basin.figure import plot_basin
from frictiondisk.tasks.basin.planner import BasinPlanner
from frictiondisk.tasks.basin.spec import Basin
from frictiondisk.tasks.basin.table import summary_lines
from frictiondisk.tasks.campaign import campaign_from_dict, campaign_from_text
from frictiondisk.tasks.sampling.draws import BLOCK
from frictiondisk.tasks.sampling.runs import SampleRequest
from frictiondisk.verdict.outcomes import OUTCOMES

BASIN = """\
name: pin_basin
scene: pin
params: {x_ms: 0.1, mu: 0.125}
basin:
  sample: {params.x0: {uniform: [-0.05, 0.05]}}
  samples: 400
  seed: 7
  along: {params.mu: [0.12, 0.125, 0.13]}
"""


def basin(**task):
    spec = {"sample": {"params.x0": {"uniform": [-0.05, 0.05]}}, "samples": 10, **task}
    return {"name": "t", "scene": "pin", "basin": spec}


def problems(data):
    with pytest.raises(ConfigError) as info:
        campaign_from_dict(data, source="c.yaml")
    return info.value.problems


def assert_problem(found, *pieces):
    pattern = ".*".join(re.escape(piece) for piece in pieces)
    assert any(re.search(pattern, line) for line in found), (pieces, found)


# --- the campaign file ----------------------------------------------------------------------


def test_the_issue_example_loads():
    campaign = campaign_from_text(BASIN)
    assert isinstance(campaign.task, Basin) and campaign.kind == "basin"
    assert campaign.dims == ("params.mu",) and campaign.shape == (3,)
    assert campaign.task.sample["params.x0"].kind == "uniform"
    assert campaign.task.samples == 400 and campaign.task.seed == 7
    assert campaign.canonical()["basin"] == {
        "along": {"params.mu": [0.12, 0.125, 0.13]},
        "sample": {"params.x0": {"uniform": [-0.05, 0.05]}},
        "samples": 400,
        "seed": 7,
    }


def test_target_se_and_a_map_load():
    spec = basin(target_se=0.01, max_samples=5000)
    del spec["basin"]["samples"]
    adaptive = campaign_from_dict(spec)
    assert adaptive.task.target_se == 0.01 and adaptive.task.batch == 100
    assert adaptive.task.samples is None and adaptive.task.sample_limit == 5000
    assert adaptive.dims == () and adaptive.shape == ()
    grid = {"params.x0": {"start": -0.05, "stop": 0.05, "num": 3}, "params.y0": [0.0, 0.01]}
    cmap = campaign_from_dict({"name": "m", "scene": "pin", "basin": {"grid": grid}})
    assert cmap.task.is_map and cmap.dims == ("params.x0", "params.y0") and cmap.shape == (3, 2)
    assert cmap.points()[1].config.params.y0 == 0.01


@pytest.mark.parametrize(
    "task, pieces",
    [
        ({"sample": {"params.mu": {"uniform": [0, 1]}}}, ("basin.sample.params.mu", "params.x0")),
        (
            {"sample": {"params.phidot0": {"uniform": [0, 1]}}},
            ("basin.sample.params.phidot0", "not allowed for scene 'pin'"),
        ),
        (
            {"sample": {"params.x0": {"uniform": [0.05, -0.05]}}},
            ("basin.sample.params.x0.uniform", "low < high"),
        ),
        (
            {"sample": {"params.x0": {"normal": [0.0, 0.0]}}},
            ("basin.sample.params.x0.normal[1]", "sd must be > 0"),
        ),
        (
            {"sample": {"params.x0": {"beta": [1, 2]}}},
            ("basin.sample.params.x0.beta", "uniform, normal"),
        ),
        ({"sample": {"params.x0": {"normal": 3}}}, ("basin.sample.params.x0.normal", "[mean, sd]")),
        ({"sample": {}}, ("basin.sample", "no keys")),
        ({"samples": 0}, ("basin.samples", ">= 1")),
        ({"samples": 1.5}, ("basin.samples", "integer")),
        ({"target_se": 0.01}, ("basin", "samples and target_se")),
        ({"seed": -1}, ("basin.seed", ">= 0")),
        ({"max_samples": 10}, ("basin.max_samples", "only used with basin.target_se")),
        ({"along": {"params.x0": [0.0]}}, ("basin.along.params.x0", "is sampled")),
        ({"along": {"params.mu": [-1.0]}}, ("basin.along.params.mu[0]",)),
        ({"frobnicate": 1}, ("basin.frobnicate", "unknown key")),
        ({"grid": {"params.x0": [0.0]}}, ("basin.sample", "not used with basin.grid")),
    ],
)
def test_bad_basin_fields_are_named(task, pieces):
    assert_problem(problems(basin(**task)), *pieces)


def test_target_se_needs_max_samples_and_a_range():
    spec = basin(target_se=0.7)
    del spec["basin"]["samples"]
    found = problems(spec)
    assert_problem(found, "basin.target_se", "<= 0.5")
    assert_problem(found, "basin.max_samples", "missing")


def test_a_map_takes_initial_state_keys_only():
    found = problems({"name": "m", "scene": "pin", "basin": {"grid": {"params.mu": [0.1]}}})
    assert_problem(found, "basin.grid.params.mu", "not an initial-state key")
    found = problems({"name": "m", "scene": "pin", "basin": {}})
    assert_problem(found, "basin", "give `sample`")


# --- samples ---------------------------------------------------------------------------------


def _draws(text, point, n):
    planner = BasinPlanner(campaign_from_text(text))
    return np.array([planner.sample_values(point, j)["params.x0"] for j in range(n)])


def test_samples_are_fixed_by_seed_and_point_not_by_count_or_other_points():
    first = _draws(BASIN, 1, BLOCK + 5)  # crosses a block
    assert np.all((first >= -0.05) & (first < 0.05)) and len(np.unique(first)) == first.size
    # more samples, a different list of points around mu = 0.125: the same draws
    other = BASIN.replace("samples: 400", "samples: 5000").replace(
        "[0.12, 0.125, 0.13]", "[0.125, 0.14]"
    )
    np.testing.assert_array_equal(_draws(other, 0, BLOCK + 5), first)
    # another seed or another point: other draws
    assert not np.array_equal(_draws(BASIN.replace("seed: 7", "seed: 8"), 1, 10), first[:10])
    assert not np.array_equal(_draws(BASIN, 0, 10), first[:10])


def test_normal_samples_have_the_asked_moments():
    text = BASIN.replace("{uniform: [-0.05, 0.05]}", "{normal: [0.01, 0.02]}")
    draws = _draws(text, 0, 4 * BLOCK)
    # 4096 draws: the sample mean is within 5 standard errors of 0.01
    assert abs(draws.mean() - 0.01) < 5 * 0.02 / math.sqrt(draws.size)
    assert 0.018 < draws.std() < 0.022


def test_sample_configs_set_the_sampled_key_only():
    planner = BasinPlanner(campaign_from_text(BASIN))
    config = planner.config_for(2, SampleRequest(3))
    assert config.params.x0 == planner.sample_values(2, 3)["params.x0"]
    assert config.params.mu == 0.13 and config.params.y0 == 0.0


# --- statistics ------------------------------------------------------------------------------


def test_wilson_interval_and_standard_error():
    z2 = 1.959963984540054**2
    lo, hi = basin_stats.wilson_interval(0, 10)
    assert lo == 0.0 and hi == pytest.approx(z2 / (10 + z2))  # closed form at k = 0
    lo, hi = basin_stats.wilson_interval(5, 10)
    assert lo + hi == pytest.approx(1.0)  # symmetric at p = 1/2
    assert basin_stats.standard_error(50, 100) == pytest.approx(0.05)
    assert basin_stats.standard_error(0, 100) == 0.0
    assert basin_stats.stopping_error(0, 100) > 0  # never stops on agreement alone
    assert basin_stats.stopping_error(500, 1000) == pytest.approx(
        basin_stats.standard_error(500, 1000), rel=2e-3
    )
    assert basin_stats.samples_for_error(0.5, 0.01) == 2500


# --- the planner, fed fake runs -------------------------------------------------------------


def _feed_all(planner, outcome_of):
    """Answer every request at once, as a journal replay would; returns the feeds made."""
    fed = 0
    while not planner.done:
        requests = planner.requests()
        assert requests, "planner stalled"
        for i, request in requests:
            x0 = planner.config_for(i, request).params.x0
            planner.feed(i, request, {"outcome": outcome_of(x0), "reason": "fake"})
            fed += 1
    return fed


def _stick_below(threshold):
    return lambda x0: "stick" if x0 < threshold else "stick_slip"


def _adaptive(target_se, max_samples, batch):
    text = BASIN.replace("samples: 400", f"target_se: {target_se}\n  batch: {batch}")
    return campaign_from_text(text.replace("seed: 7", f"seed: 7\n  max_samples: {max_samples}"))


def test_adaptive_sampling_stops_at_the_first_batch_meeting_the_target():
    campaign = _adaptive(0.02, 5000, 50)
    planner = BasinPlanner(campaign)
    _feed_all(planner, _stick_below(-0.01))
    for i in range(3):
        res = planner.results[i]
        assert res.n % 50 == 0 and res.status == "converged"
        assert basin_stats.stopping_error(res.not_stick, res.n) <= 0.02
        # one batch less would not have met the target
        samples = res.results[: res.n - 50]
        k = sum(r["outcome"] != "stick" for r in samples)
        assert basin_stats.stopping_error(k, res.n - 50) > 0.02
        assert "target_se reached" in res.reason


def test_adaptive_sampling_ends_at_max_samples_and_says_so():
    planner = BasinPlanner(_adaptive(0.001, 120, 50))
    _feed_all(planner, _stick_below(0.0))
    assert all(planner.results[i].n == 120 for i in range(3))
    assert "max_samples 120 reached" in planner.results[0].reason


def test_results_follow_the_outcome_list_and_count_new_outcomes_as_not_stick():
    planner = BasinPlanner(campaign_from_text(BASIN.replace("samples: 400", "samples: 40")))
    # a fourth kind of outcome (e.g. `creep`, added to frictiondisk.verdict.outcomes later)
    _feed_all(
        planner,
        lambda x0: "stick" if x0 < -0.02 else ("creep" if x0 < 0.0 else "undetermined"),
    )
    ds = planner.snapshot().to_dataset()
    assert list(ds.outcome.values) == [*OUTCOMES, "creep"] or "creep" in OUTCOMES
    np.testing.assert_allclose(ds.fraction.sum("outcome"), 1.0)
    creep = ds.fraction.sel(outcome="creep")
    np.testing.assert_allclose(ds.not_stick_fraction, creep)  # undetermined counts in neither
    assert ((ds.fraction_lo <= ds.fraction) & (ds.fraction <= ds.fraction_hi)).all()
    assert ds.n_samples.values.tolist() == [40, 40, 40]
    assert ds.mu.attrs["units"] == "1" and "creep" in ds.attrs["large_cycle"]
    runs = planner.snapshot().runs_dataset(lambda i, r: "k")
    assert runs.sizes["run"] == 120 and runs.x0.attrs["units"] == "m"
    assert np.all((runs.x0 < -0.02) == (runs.outcome == "stick"))
    lines = summary_lines(ds)
    assert len(lines) == 3 and lines[1].startswith("mu = 0.125: stick ")
    assert "95 % Wilson" in lines[0]
    fig = plot_basin(ds)
    assert isinstance(fig, Figure)
    assert {"fraction_stick", "fraction_creep"} <= {
        line.get_gid() for ax in fig.axes for line in ax.get_lines()
    }
    assert outcome_colors(["stick", "creep"])["creep"] not in (outcome_colors(["stick"]).values())


def test_a_map_has_the_outcome_of_every_cell_and_draws_with_a_boundary():
    grid = {"params.x0": [-0.04, -0.02, 0.0, 0.02], "params.y0": [-0.01, 0.0, 0.01]}
    campaign = campaign_from_dict({"name": "m", "scene": "pin", "basin": {"grid": grid}})
    planner = BasinPlanner(campaign)
    assert _feed_all(planner, _stick_below(-0.01)) == 12
    ds = planner.snapshot().to_dataset()
    assert ds.outcome_map.dims == ("x0", "y0") and ds.x0.attrs["units"] == "m"
    assert (ds.outcome_map.values[:2] == "stick").all() and (ds.outcome_map[2:] != "stick").all()
    assert float(ds.fraction.sel(outcome="stick")) == 0.5 and int(ds.n_samples) == 12
    assert summary_lines(ds) == ["basin map, 12 cells: stick 0.500, stick_slip 0.500"]
    # a find_jump boundary over the same keys: mu* = 0.13 + x0 crosses mu = 0.13 at x0 = 0
    x0, y0 = ds.x0.values, ds.y0.values
    star = 0.13 + np.add.outer(x0, 0 * y0)
    boundary = xr.Dataset(
        {
            "mu_star": (("x0", "y0"), star),
            "status": (("x0", "y0"), np.full(star.shape, "converged")),
        },
        coords={"x0": x0, "y0": y0},
        attrs={"task": "find_jump"},
    )
    fig = plot_basin(ds, boundary)
    gids = {child.get_gid() for ax in fig.axes for child in ax.get_children()}
    assert {"basin_map", "boundary"} <= gids
    with pytest.raises(ValueError, match="boundary: mu_star varies"):
        plot_basin(ds, boundary.rename({"y0": "vx0"}))


@pytest.mark.parametrize(
    "name", ["basin_pin_x0", "basin_pin_map", "basin_pin_boundary", "basin_disk_map"]
)
def test_basin_campaign_files_load(name):
    from pathlib import Path

    from frictiondisk.tasks.campaign import load_campaign

    path = Path(__file__).resolve().parent.parent / "campaigns" / f"{name}.yaml"
    campaign = load_campaign(path)
    assert campaign.name == name and campaign.text == path.read_text()


def test_canonical_text_loads_back_to_the_same_campaign():
    spec = basin(target_se=0.02, max_samples=300, batch=50, along={"params.mu": [0.12, 0.13]})
    del spec["basin"]["samples"]
    campaign = campaign_from_dict(spec)
    again = campaign_from_text(campaign.text)
    assert again.canonical() == campaign.canonical() and again.task == campaign.task
    assert again.content_hash() == campaign.content_hash()
    other = campaign_from_dict(spec | {"basin": spec["basin"] | {"seed": 1}})
    assert campaign.diff(other) == ["basin.seed: 0 -> 1"]


@pytest.mark.parametrize(
    "along, gid",
    [
        (None, "fractions"),  # a single point: bars with their intervals
        ({"params.mu": [0.12, 0.13], "params.x_ms": [0.09, 0.1, 0.11]}, "stick_fraction"),
    ],
)
def test_fraction_figures_of_a_point_and_of_a_grid(along, gid):
    spec = basin(samples=30)
    if along:
        spec["basin"]["along"] = along
    planner = BasinPlanner(campaign_from_dict(spec))
    _feed_all(planner, _stick_below(0.0))
    ds = planner.snapshot().to_dataset()
    assert ds.fraction.dims == (*([] if along is None else ["mu", "x_ms"]), "outcome")
    fig = plot_basin(ds)
    gids = {child.get_gid() for ax in fig.axes for child in ax.get_children()}
    assert gid in gids


# --- rules the hand validation had (regressions of the pydantic schema) --------------------


@pytest.mark.parametrize(
    "dist, message",
    [
        (
            {"uniform": None, "normal": [0.0, 1.0]},
            "basin.sample.params.x0: 2 distributions given: must be {uniform: [low, high]} "
            "with low < high, or {normal: [mean, sd]} with sd > 0",
        ),
        (
            {"uniform": None},
            "basin.sample.params.x0.uniform: expected a list [low, high]; got null: must be "
            "{uniform: [low, high]}",
        ),
        (
            {"normal": None},
            "basin.sample.params.x0.normal: expected a list [mean, sd]; got null: must be "
            "{uniform: [low, high]}",
        ),
        ({}, "basin.sample.params.x0: 0 distributions given: must be {uniform: [low, high]}"),
    ],
)
def test_one_distribution_per_sampled_key(dist, message):
    found = problems(basin(sample={"params.x0": dist}))
    assert_problem(found, message)
    if len(dist) == 2:  # the count first, then each key's own problem
        assert found[0].startswith("basin.sample.params.x0: 2 distributions given"), found
        assert found[1].startswith("basin.sample.params.x0.uniform: expected a list"), found


@pytest.mark.parametrize(
    "key, value", [("seed", -1), ("seed", "x"), ("batch", 0), ("sample", {"params.mu": 1})]
)
def test_a_key_not_used_with_a_map_is_reported_once(key, value):
    found = problems(
        {"name": "m", "scene": "pin", "basin": {"grid": {"params.x0": [0.0]}, key: value}}
    )
    assert found == [
        f"basin.{key}: not used with basin.grid (a basin map runs each cell of the grid once, "
        "at the base scene's parameters); remove it or drop grid"
    ]
