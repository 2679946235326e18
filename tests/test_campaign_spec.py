"""Campaign files: validation messages with YAML paths, grid points, canonical form, hash, diff.

Fast: no simulation.
"""

import hashlib
import json
import re
from pathlib import Path

import numpy as np
import pytest

from frictiondisk.model.scene import ConfigError, SceneConfig, scene_from_dict
from frictiondisk.tasks.campaign import (
    Campaign,
    Point,
    campaign_from_dict,
    campaign_from_text,
    load_campaign,
)
from frictiondisk.tasks.find_jump.spec import FindJump
from frictiondisk.tasks.scan.spec import Scan

CAMPAIGNS = Path(__file__).resolve().parent.parent / "campaigns"

LINE = """\
name: pin_xms_line
scene: pin
params: {x0: 0.0}
contact: {}
numerics: {t_decide: 30.0}
find_jump:
  parameter: mu
  bracket: [0.05, 0.3]
  tol: 1.0e-4
  limits: [1.0e-6, 10.0]
  max_retries: 2
  horizon_factor: 2.0
  lanes: 2
  along:
    params.x_ms: {start: 0.02, stop: 0.2, num: 10}
"""

SCAN = """\
name: pin_scan
scene: pin
scan:
  mu: {start: 0.12, stop: 0.13, num: 11}
  along: {params.x_ms: [0.05, 0.1, 0.15]}
  mode: converge
"""


def find_jump(**task):
    """A find_jump campaign dict: a pin, the given find_jump keys over a valid default."""
    spec = {"bracket": [0.05, 0.3], "along": {"params.x_ms": [0.05, 0.1]}, **task}
    return {"name": "t", "scene": "pin", "find_jump": spec}


def scan(**task):
    return {"name": "t", "scene": "pin", "scan": {"mu": [0.12, 0.13], **task}}


def problems(data):
    """The ConfigError problems of validating `data` (it must fail)."""
    with pytest.raises(ConfigError) as info:
        campaign_from_dict(data, source="c.yaml")
    assert info.value.source == "c.yaml"
    return info.value.problems


def assert_problem(found, *pieces):
    """Some problem line contains every piece, in order."""
    pattern = ".*".join(re.escape(piece) for piece in pieces)
    assert any(re.search(pattern, line) for line in found), (pieces, found)


# --- good files ---------------------------------------------------------------------------


def test_find_jump_file_loads_with_values():
    c = campaign_from_text(LINE, "line.yaml")
    assert isinstance(c, Campaign) and c.kind == "find_jump" and c.name == "pin_xms_line"
    assert c.text == LINE
    assert isinstance(c.task, FindJump)
    assert c.task.parameter == "mu"
    assert c.task.bracket == (0.05, 0.3) and c.task.limits == (1.0e-6, 10.0)
    assert (c.task.tol, c.task.max_retries, c.task.horizon_factor, c.task.lanes) == (
        1e-4,
        2,
        2.0,
        2,
    )
    assert c.dims == ("params.x_ms",) and c.shape == (10,)
    np.testing.assert_array_equal(c.coords["params.x_ms"], np.linspace(0.02, 0.2, 10))
    assert c.task.along["params.x_ms"] == tuple(np.linspace(0.02, 0.2, 10))
    # rtol and atol not given: chosen from the tol (model/auto_numerics.py); t_decide given
    choice = c.numerics_choice
    assert choice.chosen == ("rtol", "atol") and choice.t_decide == 30.0
    numerics = {"t_decide": 30.0, "rtol": choice.rtol, "atol": choice.atol}
    assert c.base == scene_from_dict({"scene": "pin", "numerics": numerics})


def test_find_jump_defaults():
    c = campaign_from_dict(find_jump())
    assert c.task.parameter == "mu" and c.task.tol == 1e-4
    assert c.task.limits == (1e-6, 10.0) and c.task.max_retries == 2
    assert c.task.horizon_factor == 2.0 and c.task.lanes == 2
    assert c.canonical()["find_jump"]["tol"] == 1e-4


def test_scan_file_loads():
    c = campaign_from_text(SCAN, "scan.yaml")
    assert c.kind == "scan" and isinstance(c.task, Scan)
    assert c.dims == ("params.mu", "params.x_ms") and c.shape == (11, 3)
    assert c.task.mode == "converge" and c.task.along == {"params.x_ms": (0.05, 0.1, 0.15)}
    np.testing.assert_allclose(c.coords["params.mu"], np.linspace(0.12, 0.13, 11))


def test_scan_defaults_to_converge_and_no_along():
    c = campaign_from_dict(scan())
    assert c.task.mode == "converge" and c.task.along == {}
    assert c.dims == ("params.mu",) and c.shape == (2,)


@pytest.mark.parametrize("name", ["demo_line.yaml", "demo_scan.yaml"])
def test_demo_campaigns_load(name):
    c = load_campaign(CAMPAIGNS / name)
    assert c.text == (CAMPAIGNS / name).read_text()
    assert all(isinstance(p.config, SceneConfig) for p in c.points())


def test_demo_line_values():
    c = load_campaign(CAMPAIGNS / "demo_line.yaml")
    assert c.kind == "find_jump" and c.base.scene == "pin"
    assert c.task.bracket == (0.04, 0.3) and c.task.tol == 1e-4
    np.testing.assert_allclose(c.coords["params.x_ms"], [0.05, 0.075, 0.1, 0.125, 0.15])


def test_demo_scan_values():
    c = load_campaign(CAMPAIGNS / "demo_scan.yaml")
    assert c.kind == "scan" and c.task.mode == "converge" and c.shape == (11,)
    assert c.base.params.x_ms == 0.1 and c.base.numerics.t_max == 2000.0
    np.testing.assert_allclose(c.coords["params.mu"], np.linspace(0.12, 0.13, 11))


def test_missing_file():
    with pytest.raises(ConfigError, match="nope.yaml: cannot read"):
        load_campaign("nope.yaml")


def test_yaml_errors_name_the_source():
    with pytest.raises(ConfigError, match=r"c\.yaml, line 2") as info:
        campaign_from_text("name: a\n  - b: [\n", "c.yaml")
    assert info.value.source == "c.yaml"


def test_duplicate_along_key_is_a_yaml_error():
    text = LINE + "    params.x_ms: [0.1]\n"
    with pytest.raises(ConfigError, match=r"find_jump\.along\.params\.x_ms: duplicate key"):
        campaign_from_text(text, "c.yaml")


# --- points -------------------------------------------------------------------------------


def test_points_of_a_line():
    c = campaign_from_dict(find_jump(along={"params.x_ms": [0.05, 0.1, 0.15]}))
    points = c.points()
    assert [p.index for p in points] == [(0,), (1,), (2,)]
    assert [p.coords for p in points] == [{"params.x_ms": x} for x in (0.05, 0.1, 0.15)]
    assert all(isinstance(p, Point) for p in points)
    assert points[2].config == c.base.with_overrides({"params.x_ms": 0.15})
    assert points[2].config.params.mu == c.base.params.mu  # mu is the bisection's


def test_points_of_a_grid_of_two_keys_in_c_order():
    along = {"params.x0": [0.0, 0.01, 0.02], "params.x_ms": {"start": 0.1, "stop": 0.2, "num": 2}}
    c = campaign_from_dict(find_jump(along=along))
    assert c.dims == ("params.x0", "params.x_ms") and c.shape == (3, 2)
    points = c.points()
    assert [p.index for p in points] == [(i, j) for i in range(3) for j in range(2)]
    p = points[3]  # (1, 1)
    assert p.coords == {"params.x0": 0.01, "params.x_ms": 0.2}
    assert (p.config.params.x0, p.config.params.x_ms) == (0.01, 0.2)


def test_grid_order_follows_the_file():
    along = {"params.x_ms": [0.1, 0.2], "params.x0": [0.0, 0.01, 0.02]}
    c = campaign_from_dict(find_jump(along=along))
    assert c.dims == ("params.x_ms", "params.x0") and c.shape == (2, 3)
    assert c.points()[1].coords == {"params.x_ms": 0.1, "params.x0": 0.01}


def test_scan_points_set_mu_and_mode():
    c = campaign_from_dict(scan(along={"params.x_ms": [0.05, 0.1, 0.15]}, mode="converge"))
    points = c.points()
    assert len(points) == 6 and points[4].index == (1, 1)
    assert points[4].coords == {"params.mu": 0.13, "params.x_ms": 0.1}
    config = points[4].config
    assert (config.params.mu, config.params.x_ms, config.numerics.mode) == (0.13, 0.1, "converge")
    assert c.base.numerics.mode == "decide"  # the base keeps its own mode


def test_scan_mode_decide():
    c = campaign_from_dict(scan(mode="decide"))
    assert c.points()[0].config.numerics.mode == "decide"


def test_numerics_and_contact_keys_can_be_varied():
    c = campaign_from_dict(
        find_jump(along={"numerics.rtol": [1e-6, 1e-8], "contact.stiffness": [1e5, 2.53e5]})
    )
    config = c.points()[1].config
    assert (config.numerics.rtol, config.contact.stiffness) == (1e-6, 2.53e5)


def test_whole_floats_vary_an_integer_key():
    data = {"name": "d", "scene": "disk", "scan": {"mu": [0.2]}}
    data["scan"]["along"] = {"contact.points": {"start": 4, "stop": 12, "num": 3}}
    points = campaign_from_dict(data).points()
    assert [p.config.contact.points for p in points] == [4, 8, 12]
    assert isinstance(points[0].coords["contact.points"], float)


def test_list_and_linspace_give_the_same_values():
    listed = campaign_from_dict(find_jump(along={"params.x_ms": [0.1, 0.15, 0.2]}))
    spaced = campaign_from_dict(
        find_jump(along={"params.x_ms": {"start": 0.1, "stop": 0.2, "num": 3}})
    )
    np.testing.assert_allclose(listed.coords["params.x_ms"], spaced.coords["params.x_ms"])
    assert spaced.task.along["params.x_ms"] == tuple(np.linspace(0.1, 0.2, 3))


def test_linspace_of_one_value_is_start():
    c = campaign_from_dict(find_jump(along={"params.x_ms": {"start": 0.1, "stop": 0.2, "num": 1}}))
    assert c.task.along == {"params.x_ms": (0.1,)} and c.shape == (1,)


def test_coords_are_fresh_arrays():
    c = campaign_from_dict(find_jump())
    c.coords["params.x_ms"][0] = 99.0
    assert c.coords["params.x_ms"][0] == 0.05


# --- canonical form, hash, diff ------------------------------------------------------------


def test_canonical_is_json_with_defaults_and_base_scene():
    c = campaign_from_dict(find_jump(along={"params.x_ms": {"start": 0.1, "stop": 0.2, "num": 2}}))
    canon = c.canonical()
    json.dumps(canon)
    assert list(canon) == ["contact", "find_jump", "name", "numerics", "params", "scene"]
    for key in ("contact", "numerics", "params", "scene"):
        assert canon[key] == c.base.canonical()[key]
    assert canon["find_jump"] == {
        "along": {"params.x_ms": [0.1, 0.2]},
        "bracket": [0.05, 0.3],
        "horizon_factor": 2.0,
        "lanes": 2,
        "limits": [1e-6, 10.0],
        "max_retries": 2,
        "parameter": "mu",
        "tol": 1e-4,
    }
    text = json.dumps(canon, separators=(",", ":"))
    assert c.content_hash() == hashlib.sha256(text.encode()).hexdigest()


def test_scan_canonical():
    canon = campaign_from_dict(scan(mode="decide")).canonical()
    assert canon["scan"] == {"along": {}, "mode": "decide", "mu": [0.12, 0.13]}


def test_content_hash_is_stable_across_key_order():
    a = campaign_from_text(LINE, "a.yaml")
    reordered = """\
find_jump:
  along:
    params.x_ms: {num: 10, stop: 0.2, start: 0.02}
  lanes: 2
  horizon_factor: 2.0
  max_retries: 2
  limits: [1.0e-6, 10.0]
  tol: 1.0e-4
  bracket: [0.05, 0.3]
  parameter: mu
numerics: {t_decide: 30.0}
contact: {}
params: {x0: 0.0}
scene: pin
name: pin_xms_line
"""
    b = campaign_from_text(reordered, "b.yaml")
    assert a.text != b.text
    assert a.content_hash() == b.content_hash() and a.diff(b) == []


def test_content_hash_ignores_written_defaults():
    plain = campaign_from_dict(find_jump())
    explicit = campaign_from_dict(
        {**find_jump(tol=1e-4, lanes=2), "params": {"mu": 0.13}, "contact": {"points": 1}}
    )
    assert plain.content_hash() == explicit.content_hash()


def test_content_hash_changes_with_any_value():
    base = campaign_from_dict(find_jump())
    assert base.content_hash() != campaign_from_dict(find_jump(tol=2e-4)).content_hash()
    assert base.content_hash() != campaign_from_dict(find_jump(lanes=3)).content_hash()


def test_along_order_is_part_of_the_content():
    a = campaign_from_dict(find_jump(along={"params.x0": [0.0, 0.01], "params.x_ms": [0.1]}))
    b = campaign_from_dict(find_jump(along={"params.x_ms": [0.1], "params.x0": [0.0, 0.01]}))
    assert a.shape == (2, 1) and b.shape == (1, 2)
    assert a.content_hash() != b.content_hash()
    assert a.diff(b) == ["dims: params.x0, params.x_ms -> params.x_ms, params.x0"]


def test_from_dict_text_is_a_canonical_dump_that_loads_back():
    along = {"params.x_ms": [0.2, 0.1], "params.x0": {"start": 0.0, "stop": 0.03, "num": 4}}
    c = campaign_from_dict(find_jump(along=along))
    again = campaign_from_text(c.text, "again.yaml")
    assert again.canonical() == c.canonical() and again.dims == c.dims
    assert again.content_hash() == c.content_hash()
    assert campaign_from_dict(c.canonical()).content_hash() == c.content_hash()


def test_diff_names_each_changed_path():
    a = campaign_from_dict(find_jump())
    b = campaign_from_dict({**find_jump(tol=1e-3), "params": {"x0": 0.01}})
    assert a.diff(b) == ["find_jump.tol: 0.0001 -> 0.001", "params.x0: 0.0 -> 0.01"]
    assert b.diff(a) == ["find_jump.tol: 0.001 -> 0.0001", "params.x0: 0.01 -> 0.0"]
    assert a.diff(a) == []


def test_diff_of_changed_values_and_tasks():
    a = campaign_from_dict(find_jump())
    b = campaign_from_dict(find_jump(along={"params.x_ms": [0.05, 0.2]}))
    assert a.diff(b) == ["find_jump.along.params.x_ms: [0.05, 0.1] -> [0.05, 0.2]"]
    lines = a.diff(campaign_from_dict(scan()))
    assert "find_jump.tol: 0.0001 -> (absent)" in lines
    assert "scan.mode: (absent) -> 'converge'" in lines


# --- bad files: each message names the YAML path --------------------------------------------


def test_unknown_top_level_key():
    found = problems({**find_jump(), "bracket": [0.1, 0.2]})
    assert_problem(found, "bracket: unknown key; allowed keys at top level: name, scene")


def test_unknown_top_level_key_suggests_close_match():
    found = problems({**find_jump(), "nmae": "x"})
    assert_problem(found, "nmae: unknown key", "(did you mean 'name'?)")


@pytest.mark.parametrize(
    ("data", "path", "allowed"),
    [
        (find_jump(tolerance=1e-3), "find_jump.tolerance", "under find_jump: parameter, bracket"),
        (scan(steps=3), "scan.steps", "under scan: mu, along, mode"),
        (
            find_jump(along={"params.x_ms": {"start": 0.1, "stop": 0.2, "num": 2, "step": 1}}),
            "find_jump.along.params.x_ms.step",
            "under find_jump.along.params.x_ms: start, stop, num",
        ),
        (
            scan(mu={"start": 0.1, "end": 0.2, "num": 2}),
            "scan.mu.end",
            "under scan.mu: start, stop, num",
        ),
    ],
)
def test_unknown_key_in_a_task(data, path, allowed):
    assert_problem(problems(data), f"{path}: unknown key; allowed keys {allowed}")


def test_both_tasks():
    data = {**find_jump(), "scan": {"mu": [0.1]}}
    assert problems(data) == [
        "(top level): find_jump and scan given: give exactly one task "
        "(find_jump, scan, trajectory, basin, trace, map)"
    ]


def test_no_task():
    assert problems({"name": "t", "scene": "pin"}) == [
        "(top level): no task: give exactly one of find_jump, scan, trajectory, basin, trace, map"
    ]


def test_trajectory_task():
    campaign = campaign_from_dict(
        {
            "name": "orbit",
            "scene": "pin",
            "params": {"mu": 0.12},
            "numerics": {"mode": "converge"},
            "trajectory": {"dt_out": 0.02, "show": "cycle"},
        }
    )
    assert campaign.kind == "trajectory"
    assert campaign.task.dt_out == 0.02 and campaign.task.show == "cycle"
    assert campaign.shape == () and len(campaign.points()) == 1
    defaults = campaign_from_dict({"name": "o", "scene": "pin", "trajectory": None})
    assert (defaults.task.dt_out, defaults.task.show) == (0.01, "whole")


@pytest.mark.parametrize(
    "task, numerics, message",
    [
        (
            {"show": "last"},
            {},
            "trajectory.show: 'last' is not allowed: must be 'whole' or 'cycle'",
        ),
        (
            {"show": "cycle"},
            {},
            "trajectory.show: 'cycle' needs the converged limit cycle: set numerics.mode: "
            "converge (got 'decide')",
        ),
        ({"dt_out": 0}, {}, "trajectory.dt_out: 0 is out of range: must be > 0"),
        ({"every": 1}, {}, "trajectory.every: unknown key; allowed keys under trajectory"),
    ],
)
def test_bad_trajectory_task(task, numerics, message):
    data = {"name": "o", "scene": "pin", "numerics": numerics, "trajectory": task}
    assert_problem(problems(data), message)


def test_not_a_mapping():
    assert_problem(problems([1, 2]), "(top level): expected a mapping with keys name, scene")
    assert_problem(problems({**find_jump(), "find_jump": [1]}), "find_jump: expected a mapping")


@pytest.mark.parametrize(
    ("name", "shown"), [("bad name", "'bad name' is not allowed"), (12, "12 is an integer")]
)
def test_bad_name(name, shown):
    assert_problem(problems({**find_jump(), "name": name}), f"name: {shown}", "letters, digits")


def test_missing_name():
    data = find_jump()
    del data["name"]
    assert_problem(problems(data), "name: missing")


@pytest.mark.parametrize("bracket", [[0.3, 0.05], [0.1, 0.1]])
def test_bracket_lo_not_below_hi(bracket):
    found = problems(find_jump(bracket=bracket))
    assert found == [
        f"find_jump.bracket: {bracket!r} is not allowed: must be a list [lo, hi] of two "
        "finite numbers with 0 < lo < hi"
    ]


@pytest.mark.parametrize(
    ("value", "index", "shown"), [(float("inf"), 1, "inf"), (float("nan"), 0, "nan")]
)
def test_bracket_non_finite(value, index, shown):
    bracket = [0.05, 0.3]
    bracket[index] = value
    found = problems(find_jump(bracket=bracket))
    assert found == [
        f"find_jump.bracket[{index}]: {shown} is not allowed: must be a finite number > 0"
    ]


def test_bracket_non_finite_from_yaml():
    with pytest.raises(ConfigError) as info:
        campaign_from_text(LINE.replace("[0.05, 0.3]", "[0.05, .inf]"), "c.yaml")
    assert_problem(info.value.problems, "find_jump.bracket[1]: inf is not allowed")


@pytest.mark.parametrize(
    ("bracket", "message"),
    [
        ([0.0, 0.3], "find_jump.bracket[0]: 0.0 is out of range: must be > 0"),
        ([0.05], "find_jump.bracket: expected a list [lo, hi]; got a list [0.05]"),
        (["0.05", 0.3], "find_jump.bracket[0]: '0.05' is a string, not a number"),
        (None, "find_jump.bracket: expected a list [lo, hi]; got null"),
    ],
)
def test_bracket_shapes_and_types(bracket, message):
    assert_problem(problems(find_jump(bracket=bracket)), message)


def test_bracket_is_required():
    data = find_jump()
    del data["find_jump"]["bracket"]
    assert_problem(problems(data), "find_jump.bracket: missing; must be a list [lo, hi]")


@pytest.mark.parametrize(("tol", "shown"), [(0, "0"), (-1e-4, "-0.0001")])
def test_tol_not_positive(tol, shown):
    assert problems(find_jump(tol=tol)) == [f"find_jump.tol: {shown} is out of range: must be > 0"]


@pytest.mark.parametrize("tol", [0.25, 0.5])
def test_tol_not_below_bracket_width(tol):
    found = problems(find_jump(tol=tol))
    assert_problem(found, f"find_jump.tol: {tol} is out of range: must be > 0 and < hi - lo = 0.25")


def test_tol_non_finite():
    assert_problem(problems(find_jump(tol=float("inf"))), "find_jump.tol: inf is not allowed")


@pytest.mark.parametrize("limits", [[0.1, 10.0], [1e-6, 0.2]])
def test_limits_must_contain_the_bracket(limits):
    found = problems(find_jump(limits=limits))
    assert found == [
        f"find_jump.limits: {limits!r} does not contain the bracket [0.05, 0.3]: "
        "must have limits[0] <= lo and hi <= limits[1]"
    ]


def test_limits_may_equal_the_bracket():
    assert campaign_from_dict(find_jump(limits=[0.05, 0.3])).task.limits == (0.05, 0.3)


@pytest.mark.parametrize(
    ("key", "value", "message"),
    [
        ("lanes", 0, "find_jump.lanes: 0 is out of range: must be >= 1 and <= 64"),
        ("lanes", 65, "find_jump.lanes: 65 is out of range: must be >= 1 and <= 64"),
        ("lanes", 2.0, "find_jump.lanes: 2.0 is a float, not an integer"),
        ("lanes", True, "find_jump.lanes: true is a boolean, not an integer"),
        ("max_retries", -1, "find_jump.max_retries: -1 is out of range: must be >= 0 and <= 10"),
        ("max_retries", 11, "find_jump.max_retries: 11 is out of range"),
        ("horizon_factor", 1.0, "find_jump.horizon_factor: 1.0 is out of range: must be > 1"),
        (
            "parameter",
            "x_ms",
            "find_jump.parameter: 'x_ms' is not allowed: must be mu or a dotted numeric scene key",
        ),
    ],
)
def test_find_jump_settings(key, value, message):
    assert_problem(problems(find_jump(**{key: value})), message)


def test_bad_scan_mode():
    found = problems(scan(mode="fast"))
    assert found == ["scan.mode: 'fast' is not allowed: must be 'decide' or 'converge'"]


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        (
            {"start": 0.1, "stop": 0.2, "num": 0},
            "find_jump.along.params.x_ms.num: 0 is out of range: must be >= 1",
        ),
        (
            {"start": 0.1, "stop": 0.2, "num": 2.5},
            "find_jump.along.params.x_ms.num: 2.5 is a float, not an integer: "
            "must be an integer >= 1",
        ),
        (
            {"start": 0.1, "stop": 0.2, "num": 3.0},
            "find_jump.along.params.x_ms.num: 3.0 is a float, not an integer",
        ),
        (
            {"start": float("-inf"), "stop": 0.2, "num": 2},
            "find_jump.along.params.x_ms.start: -inf is not allowed: must be a finite number",
        ),
        (
            {"start": 0.1, "stop": float("nan"), "num": 2},
            "find_jump.along.params.x_ms.stop: nan is not allowed: must be a finite number",
        ),
        ({"start": 0.1, "num": 2}, "find_jump.along.params.x_ms.stop: missing"),
        (
            {"start": 0.1, "stop": 0.1, "num": 3},
            "find_jump.along.params.x_ms: start = stop = 0.1 with num 3 repeats one value",
        ),
        ([], "find_jump.along.params.x_ms: empty list: give at least one number"),
        (
            [0.1, 0.2, 0.1],
            "find_jump.along.params.x_ms[2]: 0.1 repeats find_jump.along.params.x_ms[0]: "
            "values must differ",
        ),
        (
            [0.1, float("inf")],
            "find_jump.along.params.x_ms[1]: inf is not allowed: must be a finite number",
        ),
        ([0.1, "0.2"], "find_jump.along.params.x_ms[1]: '0.2' is a string, not a number"),
        (0.1, "find_jump.along.params.x_ms: expected a list or a mapping; got a float 0.1"),
    ],
)
def test_bad_values(spec, message):
    assert_problem(problems(find_jump(along={"params.x_ms": spec})), message)


def test_bad_scan_mu_values():
    assert_problem(problems(scan(mu=[])), "scan.mu: empty list")
    assert_problem(
        problems(scan(mu={"start": 0.1, "stop": 0.2, "num": 0})),
        "scan.mu.num: 0 is out of range",
    )
    assert_problem(problems(scan(mu=[0.1, 0.1])), "scan.mu[1]: 0.1 repeats scan.mu[0]")
    data = scan()
    del data["scan"]["mu"]
    assert_problem(problems(data), "scan.mu: missing; must be a list of numbers or a mapping")


def test_scan_mu_must_make_valid_scenes():
    found = problems(scan(mu=[0.1, -0.1, 0.0]))
    assert found == [
        "scan.mu[1]: -0.1 is out of range: must be > 0",
        "scan.mu[2]: 0.0 is out of range: must be > 0",
    ]


@pytest.mark.parametrize(
    ("key", "allowed"),
    [
        ("params.nope", "allowed keys under params: mu, omega_m"),
        ("numerics.nope", "allowed keys under numerics: method, rtol"),
        ("nope", "allowed keys at top level: scene, params, contact, numerics"),
        ("contact.stribeck.nope", "allowed keys under contact.stribeck: r, v_s, delta"),
    ],
)
def test_varied_key_that_does_not_exist(key, allowed):
    found = problems(find_jump(along={key: [0.1, 0.2]}))
    assert len(found) == 1
    assert_problem(found, f"find_jump.along.{key}: unknown scene key; {allowed}")


def test_varied_key_that_does_not_exist_in_a_scan():
    found = problems(scan(along={"params.nope": [1.0]}))
    assert_problem(found, "scan.along.params.nope: unknown scene key; allowed keys under params")


def test_varied_key_suggests_close_match():
    found = problems(find_jump(along={"params.xms": [0.1]}))
    assert_problem(found, "find_jump.along.params.xms: unknown scene key", "'x_ms'?")


@pytest.mark.parametrize(
    ("key", "message"),
    [
        ("params.x_ms.a", "unknown scene key; params.x_ms is a value, not a section"),
        ("contact.stribeck", "a section, not a number: vary one of its keys: r, v_s, delta"),
        ("scene", "not a numeric scene key (it must be 'pin' or 'disk')"),
        ("numerics.stop_on_stick", "not a numeric scene key (it must be true or false)"),
        ("params..x", "not a dotted scene key"),
    ],
)
def test_varied_key_that_is_not_a_number(key, message):
    assert_problem(problems(find_jump(along={key: [1.0]})), f"find_jump.along.{key}: {message}")


def test_find_jump_cannot_vary_mu():
    found = problems(find_jump(along={"params.mu": [0.1, 0.2]}))
    assert found == [
        "find_jump.along.params.mu: params.mu is the bisected parameter; it cannot also be varied"
    ]


def test_scan_cannot_vary_mu_along():
    found = problems(scan(along={"params.mu": [0.1]}))
    assert_problem(found, "scan.along.params.mu: params.mu is the scan's own axis")


def test_three_along_keys():
    along = {"params.x_ms": [0.1], "params.x0": [0.0], "params.y0": [0.0]}
    found = problems(find_jump(along=along))
    assert found == [
        "find_jump.along: 3 keys (params.x_ms, params.x0, params.y0) given: vary 1 or 2 scene keys"
    ]


def test_no_along_keys():
    assert problems(find_jump(along={})) == [
        "find_jump.along: no keys given: vary 1 or 2 scene keys"
    ]
    data = find_jump()
    del data["find_jump"]["along"]
    assert_problem(problems(data), "find_jump.along: missing")


def test_scan_along_at_most_one_key():
    found = problems(scan(along={"params.x_ms": [0.1], "params.x0": [0.0]}))
    assert_problem(found, "scan.along: 2 keys (params.x_ms, params.x0) given: vary at most 1")


def test_along_value_that_makes_an_invalid_scene():
    found = problems(find_jump(along={"params.m_s": [1.0, 2.0, 0.5, -0.5]}))
    assert found == ["find_jump.along.params.m_s[3]: -0.5 is out of range: must be > 0 kg"]


def test_along_linspace_value_that_makes_an_invalid_scene():
    found = problems(find_jump(along={"numerics.rtol": {"start": 0.5, "stop": 1.5, "num": 3}}))
    assert found == [
        "find_jump.along.numerics.rtol[1]: 1.0 is out of range: must be > 0 and < 1",
        "find_jump.along.numerics.rtol[2]: 1.5 is out of range: must be > 0 and < 1",
    ]


def test_along_value_checked_against_the_scene_rules():
    found = problems(scan(along={"contact.points": [1, 2]}))
    assert found == [
        "scan.along.contact.points[1]: 2 is not allowed for scene 'pin': "
        "a pin has exactly one contact; use 1 or null"
    ]
    found = problems({**scan(along={"contact.points": [4, 6.5]}), "scene": "disk"})
    assert_problem(found, "scan.along.contact.points[1]: 6.5 is a float, not an integer")


def test_base_scene_error_keeps_its_scene_path():
    with pytest.raises(ConfigError) as info:
        campaign_from_text(LINE.replace("{x0: 0.0}", "{x0: 0.0, x_ms: -.inf}"), "c.yaml")
    assert info.value.problems == [
        "params.x_ms: -inf is not allowed: must be a finite number >= -1000.0 and <= 1000.0 m"
    ]


def test_values_are_checked_once_the_base_scene_is_valid():
    data = {**find_jump(along={"params.m_s": [-1.0]}), "params": {"x_ms": float("inf")}}
    assert problems(data) == [
        "params.x_ms: inf is not allowed: must be a finite number >= -1000.0 and <= 1000.0 m"
    ]


def test_base_scene_problems_are_the_scene_file_problems():
    base = {"scene": "pin", "params": {"m_s": -1.0, "foo": 1}, "numerics": {"rtol": 2.0}}
    with pytest.raises(ConfigError) as info:
        scene_from_dict(base)
    assert problems({**find_jump(), **base}) == info.value.problems


def test_missing_scene():
    data = find_jump()
    del data["scene"]
    assert_problem(problems(data), "scene: missing; must be 'pin' or 'disk'")


def test_all_problems_are_reported_together():
    data = {
        "name": "bad name",
        "scene": "pin",
        "extra": 1,
        "find_jump": {
            "bracket": [0.3, 0.05],
            "tol": 0,
            "lanes": 0,
            "along": {"params.nope": [1.0], "params.m_s": [-1.0]},
        },
    }
    found = problems(data)
    assert [line.split(":")[0] for line in found] == [
        "extra",
        "name",
        "find_jump.bracket",
        "find_jump.tol",
        "find_jump.lanes",
        "find_jump.along.params.nope",
        "find_jump.along.params.m_s[0]",
    ]
    with pytest.raises(ConfigError) as info:
        campaign_from_dict(data)
    assert str(info.value) == "\n".join(found)


def test_certify_defaults_on_and_is_switched_off_or_tuned():
    from frictiondisk.model.search_settings import Certify

    base = find_jump()
    assert campaign_from_dict(base).task.certify == Certify(horizon=4.0, rtol=0.1, levels=2)
    off = {**base, "find_jump": {**base["find_jump"], "certify": False}}
    assert not campaign_from_dict(off).task.certify.enabled
    tuned = {**base, "find_jump": {**base["find_jump"], "certify": {"horizon": 8, "levels": 1}}}
    assert campaign_from_dict(tuned).task.certify == Certify(horizon=8.0, rtol=0.1, levels=1)
    # the default keeps the campaign's hash: only a changed ladder enters the canonical form
    assert "certify" not in campaign_from_dict(base).task.canonical()
    assert campaign_from_dict(tuned).task.canonical()["certify"]["horizon"] == 8


@pytest.mark.parametrize(
    "certify, field",
    [
        ({"horizon": 1.0}, "find_jump.certify.horizon"),
        ({"rtol": 0.0}, "find_jump.certify.rtol"),
        ({"levels": 9}, "find_jump.certify.levels"),
        ({"horizn": 4}, "find_jump.certify.horizn"),
        ("yes", "find_jump.certify"),
    ],
)
def test_a_bad_certify_names_its_field(certify, field):
    data = {
        "name": "c",
        "scene": "pin",
        "find_jump": {"along": {"params.x_ms": [0.1]}, "certify": certify},
    }
    assert any(p.startswith(field) for p in problems(data)), problems(data)


# --- rules the hand validation had (regressions of the pydantic schema) --------------------


@pytest.mark.parametrize("task", [{}, None])
def test_the_default_dt_out_must_fit_a_recording(task):
    data = {"name": "o", "scene": "pin", "numerics": {"t_decide": 1e5}, "trajectory": task}
    found = problems(data)
    assert len(found) == 1, found
    assert_problem(
        found,
        "trajectory.dt_out: 0.01 s is out of range:",
        "would need 1e+07 rows",
        "must be >= 0.0513 s (or shorten numerics.t_decide)",
    )


@pytest.mark.parametrize("bracket", [[0.05, 0.3], None])
def test_a_null_prescan_is_refused(bracket):
    data = find_jump(prescan=None, limits=[0.01, 1.0])
    if bracket is None:  # no stand-in bracket may be checked against the limits
        del data["find_jump"]["bracket"]
    assert problems(data) == [
        "find_jump.prescan: expected a mapping with keys mu, mode, stride, persist; got null"
    ]


def test_a_bad_prescan_without_a_bracket_reports_only_the_prescan():
    data = find_jump(prescan={"mu": [0.1]}, limits=[0.01, 1.0], tol=0.5)
    del data["find_jump"]["bracket"]
    assert problems(data) == ["find_jump.prescan.mu: one value given: give at least 2"]


@pytest.mark.parametrize(
    ("task", "message"),
    [
        ({"tol": 5}, "find_jump.tol: 5 is out of range: must be > 0 and < hi - lo = 0.25"),
        (
            {"limits": [0.1, 10.0]},
            "find_jump.limits: [0.1, 10.0] does not contain the bracket [0.05, 0.3]: "
            "must have limits[0] <= lo and hi <= limits[1]",
        ),
        (
            {"horizon_factor": 1e5},
            "find_jump.horizon_factor: 100000.0 is out of range: with max_retries 2 the last "
            "retry would run",
        ),
    ],
)
def test_rules_across_find_jump_keys_are_reported_with_other_problems(task, message):
    found = problems(find_jump(lanes=0, along={"params.nope": [1.0]}, **task))
    assert [line.split(":")[0] for line in found] == [
        message.split(":")[0],
        "find_jump.lanes",
        "find_jump.along.params.nope",
    ]
    assert_problem(found, message)
    assert_problem(found, "find_jump.lanes: 0 is out of range: must be >= 1 and <= 64")
    assert_problem(found, "find_jump.along.params.nope: unknown scene key")


def test_rules_across_find_jump_keys_wait_for_the_keys_they_read():
    # a bad bracket: neither tol nor limits is compared with it
    found = problems(find_jump(bracket=[0.3, "x"], tol=5, limits=[0.1, 0.2]))
    assert [line.split(":")[0] for line in found] == ["find_jump.bracket[1]"]


@pytest.mark.parametrize(
    ("stride", "message"),
    [
        ("2", "'2' is a string, not an integer: must be an integer >= 1 and <= 2"),
        (None, "missing value (null); must be an integer >= 1 and <= 2"),
        (1.0, "1.0 is a float, not an integer: must be an integer >= 1 and <= 2"),
        (0, "0 is out of range: must be >= 1 and <= 2"),
        (3, "3 is out of range: must be >= 1 and <= 2"),
    ],
)
def test_prescan_stride_is_bounded_by_the_prescan_values(stride, message):
    found = problems(find_jump(prescan={"mu": [0.1, 0.2, 0.3], "stride": stride}))
    assert len(found) == 1, found
    assert found[0].startswith(f"find_jump.prescan.stride: {message}"), found
    prescan = {"mu": [0.1, 0.2, 0.3], "stride": 2}
    assert campaign_from_dict(find_jump(prescan=prescan)).task.prescan.stride == 2
