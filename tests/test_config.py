"""Scene configuration: strict YAML, validation messages, canonical form, hash, geometry."""

import hashlib
import json
import math
import re
import subprocess
import sys

import numpy as np
import pydantic
import pytest

from frictiondisk.model.scene import ConfigError, SceneConfig, load_scene, scene_from_dict
from frictiondisk.model.yamlio import ConfigError as YamlConfigError
from frictiondisk.model.yamlio import dump_yaml, load_yaml_file, load_yaml_text

DEFAULTS = {
    "params": {
        "mu": 0.13,
        "omega_m": 1.1,
        "c_s": 1.0,
        "beta_s": 0.1,
        "m_s": 1.0,
        "F_n": 1.0,
        "J_s": 0.02,
        "beta_b": 0.0,
        "x_ms": 0.1,
        "x0": 0.0,
        "y0": 0.0,
        "vx0": 0.0,
        "vy0": 0.0,
        "phidot0": 0.0,
    },
    "contact": {
        "stiffness": 2.53e5,
        "damping": None,
        "damping_ratio": 1.0,
        "eps": 1.0e-9,
        "layout": "ring",
        "points": None,
        "ring_radius": 0.05,
        "inner_radius": None,
        "outer_radius": None,
        "positions": None,
        "weights": None,
        "stribeck": {"r": 1.0, "v_s": 1.0e-3, "delta": 1.0},
    },
    "numerics": {
        "method": "rodas4",
        "rtol": 1.0e-6,
        "atol": 1.0e-9,
        "dt": 1.0e-2,
        "h_max": 0.1,
        "mode": "decide",
        "t_decide": 30.0,
        "t_max": 3000.0,
        "stop_on_stick": True,
        "window_revs": 2.0,
        "cycle_tol": 1.0e-6,
        "cycle_count": 3,
        "stick_rule": "corotation",
        "evidence": "extrapolate",
        "observe_until": 0.0,
        "follow_departures_until": 0.0,
        "horizon_budget": 8.0,
        "max_steps": 2_000_000,
        "max_events": 200_000,
        "preset": "default",  # resolved into the values above; not in the canonical form
    },
}


def write(tmp_path, text, name="scene.yaml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def load(tmp_path, text, *overrides):
    return load_scene(write(tmp_path, text), overrides)


def problems(tmp_path, text, *overrides):
    """The ConfigError problems of loading `text` (the load must fail)."""
    with pytest.raises(ConfigError) as info:
        load(tmp_path, text, *overrides)
    return info.value.problems


def assert_problem(found, *pieces):
    """Some problem line contains every piece, in order."""
    pattern = ".*".join(re.escape(piece) for piece in pieces)
    assert any(re.search(pattern, line) for line in found), (pieces, found)


# --- strict YAML -------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "value"),
    [("1e-4", 1e-4), ("2.53e5", 2.53e5), ("1E6", 1e6), ("-3e+2", -300.0), ("1.0e-09", 1e-9)],
)
def test_exponent_floats_load_as_float(text, value):
    loaded = load_yaml_text(f"x: {text}")["x"]
    assert type(loaded) is float and loaded == value


@pytest.mark.parametrize(
    "text", ["inf", "+inf", "-inf", "INF", "Inf", ".inf", "-.inf", ".Inf", "nan", "NaN", ".nan"]
)
def test_inf_and_nan_words_load_as_float(text):
    loaded = load_yaml_text(f"x: {text}")["x"]
    assert type(loaded) is float and not math.isfinite(loaded)


def test_yaml_12_scalars():
    loaded = load_yaml_text("a: yes\nb: no\nc: on\nd: 010\ne: true\nf: FALSE\ng: ~\nh: 2024-01-01")
    assert loaded == {
        "a": "yes",
        "b": "no",
        "c": "on",
        "d": 10,
        "e": True,
        "f": False,
        "g": None,
        "h": "2024-01-01",
    }


def test_dump_yaml_quotes_strings_that_look_like_numbers():
    data = {"s": ["1e-4", "inf", "true", "null", "3", "pin"], "x": [1e-9, 2.53e5, True, None]}
    assert load_yaml_text(dump_yaml(data)) == data


def test_duplicate_key_names_path_and_lines():
    text = "scene: pin\nparams:\n  mu: 0.1\n  m_s: 1.0\n  mu: 0.2\n"
    with pytest.raises(ConfigError) as info:
        load_yaml_text(text, source="s.yaml")
    assert info.value.problems == ["params.mu: duplicate key (lines 3 and 5)"]
    assert info.value.source == "s.yaml"


def test_duplicate_keys_all_reported_at_every_level():
    text = "scene: pin\ncontact:\n  stribeck: {r: 0.5, r: 0.6}\n  eps: 1\n  eps: 2\nscene: disk\n"
    with pytest.raises(YamlConfigError) as info:
        load_yaml_text(text)
    assert sorted(info.value.problems) == [
        "contact.eps: duplicate key (lines 4 and 5)",
        "contact.stribeck.r: duplicate key (lines 3 and 3)",
        "scene: duplicate key (lines 1 and 6)",
    ]


def test_duplicate_key_in_a_list_item():
    with pytest.raises(ConfigError, match=re.escape("1.a: duplicate key (lines 2 and 2)")):
        load_yaml_text("- 1\n- {a: 1, a: 2}\n")


def test_duplicate_key_in_scene_file(tmp_path):
    found = problems(tmp_path, "scene: pin\nnumerics:\n  rtol: 1e-6\n  rtol: 1e-7\n")
    assert found == ["numerics.rtol: duplicate key (lines 3 and 4)"]


def test_yaml_syntax_error_names_source_and_line(tmp_path):
    path = write(tmp_path, "scene: pin\nparams:\n  mu: [0.1\n")
    with pytest.raises(ConfigError) as info:
        load_scene(path)
    (message,) = info.value.problems
    assert message.startswith(f"{path}, line 4,")
    assert "invalid YAML" in message


def test_yaml_bad_indentation(tmp_path):
    found = problems(tmp_path, "scene: pin\nparams:\n  mu: 0.1\n   m_s: 1\n")
    assert_problem(found, "scene.yaml, line 4", "invalid YAML")


def test_unsafe_tag_is_rejected():
    with pytest.raises(ConfigError, match="could not determine a constructor"):
        load_yaml_text("x: !!python/name:os.system ''")


def test_missing_file(tmp_path):
    with pytest.raises(ConfigError, match="nope.yaml: cannot read"):
        load_yaml_file(tmp_path / "nope.yaml")


def test_config_error_is_value_error_joining_problems():
    err = ConfigError(["a: one", "b: two"], source="f.yaml")
    assert isinstance(err, ValueError)
    assert str(err) == "a: one\nb: two"
    assert err.source == "f.yaml"
    assert ConfigError("just one").problems == ["just one"]
    assert ConfigError is YamlConfigError


# --- defaults ------------------------------------------------------------------------


def test_only_scene_gives_all_defaults(tmp_path):
    config = load(tmp_path, "scene: pin\n")
    assert config.scene == "pin"
    assert config.model_dump() == {"scene": "pin", **DEFAULTS}
    assert config.n_contacts == 1


def test_disk_defaults(tmp_path):
    config = load(tmp_path, "scene: disk\n")
    assert config.n_contacts == 12
    assert config.canonical()["contact"]["points"] == 12


def test_scene_config_fields_are_documented_with_units():
    params = SceneConfig.model_fields["params"].annotation.model_fields
    assert params["m_s"].description.endswith("[kg]")
    assert params["m_s"].json_schema_extra == {"unit": "kg"}
    assert params["omega_m"].description.endswith("[rad/s]")
    models = [SceneConfig.model_fields[name].annotation for name in ("params", "numerics")]
    contact = SceneConfig.model_fields["contact"].annotation
    models += [contact, contact.model_fields["stribeck"].annotation]
    for model in models:
        for name, field in model.model_fields.items():
            assert field.description, f"{model.__name__}.{name} has no description"


def test_exponent_values_in_scene_file_are_floats(tmp_path):
    config = load(tmp_path, "scene: pin\ncontact:\n  eps: 1e-4\n  stiffness: 2.53e5\n")
    assert config.contact.eps == 1e-4
    assert config.contact.stiffness == 253000.0


def test_integer_accepted_for_float_and_stored_as_float(tmp_path):
    config = load(tmp_path, "scene: pin\nparams:\n  mu: 1\n")
    assert type(config.params.mu) is float


def test_config_is_frozen(tmp_path):
    config = load(tmp_path, "scene: pin\n")
    with pytest.raises(pydantic.ValidationError):
        config.params.mu = 0.5


# --- bad input ----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "path", "allowed"),
    [
        ("scene: pin\nfoo: 1\n", "foo", "allowed keys at top level: scene, params"),
        ("scene: pin\nparams:\n  foo: 1\n", "params.foo", "under params: mu, omega_m"),
        ("scene: pin\ncontact:\n  foo: 1\n", "contact.foo", "under contact: stiffness"),
        (
            "scene: pin\ncontact:\n  stribeck:\n    foo: 1\n",
            "contact.stribeck.foo",
            "under contact.stribeck: r, v_s, delta",
        ),
        ("scene: pin\nnumerics:\n  foo: 1\n", "numerics.foo", "under numerics: method, rtol"),
    ],
)
def test_unknown_key_at_each_level(tmp_path, text, path, allowed):
    assert_problem(problems(tmp_path, text), f"{path}: unknown key", allowed)


def test_unknown_key_suggests_close_match(tmp_path):
    found = problems(tmp_path, "scene: pin\nparams:\n  omega: 1.0\n")
    assert_problem(found, "params.omega: unknown key", "did you mean 'omega_m'?")


def test_non_string_key(tmp_path):
    found = problems(tmp_path, "scene: pin\nparams:\n  1: 2\n")
    assert_problem(found, "params: key 1 is not text", "allowed keys under params")


@pytest.mark.parametrize(
    ("word", "shown"),
    [("inf", "inf"), ("-inf", "-inf"), (".nan", "nan"), ("-.inf", "-inf"), ("NaN", "nan")],
)
def test_non_finite_values_are_rejected(tmp_path, word, shown):
    found = problems(tmp_path, f"scene: pin\nparams:\n  x_ms: {word}\n")
    assert len(found) == 1
    assert found[0].startswith(f"params.x_ms: {shown} is not allowed: must be a finite number")


@pytest.mark.parametrize(
    ("section", "key", "allowed"),
    [
        ("params", "m_s", "a finite number > 0 kg"),
        ("contact", "stiffness", "a finite number > 0 N/m"),
        ("contact", "damping", "null or a finite number > 0 N s/m"),
        ("numerics", "t_max", "a finite number > 0 and <= 1000000000.0 s"),
    ],
)
def test_infinite_value_message_names_the_range(tmp_path, section, key, allowed):
    found = problems(tmp_path, f"scene: pin\n{section}:\n  {key}: .inf\n")
    assert found == [f"{section}.{key}: inf is not allowed: must be {allowed}"]


def test_negative_mass(tmp_path):
    found = problems(tmp_path, "scene: pin\nparams:\n  m_s: -1.0\n")
    assert found == ["params.m_s: -1.0 is out of range: must be > 0 kg"]


@pytest.mark.parametrize("value", ["0", "-2.53e5"])
def test_non_positive_stiffness(tmp_path, value):
    found = problems(tmp_path, f"scene: pin\ncontact:\n  stiffness: {value}\n")
    assert_problem(
        found, f"contact.stiffness: {load_yaml_text(value)!r} is out of range", "> 0 N/m"
    )


@pytest.mark.parametrize(
    ("key", "bound"),
    [
        ("rtol", "> 0 and < 1"),
        ("atol", "> 0"),
        ("cycle_tol", "> 0 m"),
        ("dt", "> 0 s"),
        ("h_max", "> 0 s"),
        ("t_decide", "> 0 and <= 1000000000.0 s"),
        ("window_revs", "> 0"),
    ],
)
def test_zero_tolerances_and_times(tmp_path, key, bound):
    found = problems(tmp_path, f"scene: pin\nnumerics:\n  {key}: 0.0\n")
    assert found == [f"numerics.{key}: 0.0 is out of range: must be {bound}"]


@pytest.mark.parametrize("value", ["1.0", "2.0"])
def test_rtol_must_be_below_one(tmp_path, value):
    found = problems(tmp_path, f"scene: pin\nnumerics:\n  rtol: {value}\n")
    assert found == [f"numerics.rtol: {value} is out of range: must be > 0 and < 1"]


@pytest.mark.parametrize(
    ("key", "value", "bound"),
    [
        ("mu", "0.0", "> 0"),
        ("omega_m", "-1.1", ">= 0 and <= 10000.0 rad/s"),
        ("c_s", "-1", ">= 0 N/m"),
        ("beta_s", "-0.1", ">= 0 N s/m"),
        ("F_n", "0", "> 0 N"),
        ("J_s", "0", "> 0 kg m^2"),
        ("beta_b", "-1e-3", ">= 0 N m s/rad"),
    ],
)
def test_param_ranges(tmp_path, key, value, bound):
    # a disk: J_s and beta_b are its keys (a pin refuses them, tests/test_scene_keys.py)
    found = problems(tmp_path, f"scene: disk\nparams:\n  {key}: {value}\n")
    shown = repr(load_yaml_text(value))
    assert found == [f"params.{key}: {shown} is out of range: must be {bound}"]


def test_quoted_number_is_not_coerced(tmp_path):
    found = problems(tmp_path, 'scene: pin\nparams:\n  mu: "0.1"\n')
    assert_problem(found, "params.mu: '0.1' is a string, not a number", "> 0", "without quotes")


def test_quoted_integer_is_not_coerced(tmp_path):
    found = problems(tmp_path, "scene: pin\nnumerics:\n  max_steps: '3'\n")
    assert_problem(found, "numerics.max_steps: '3' is a string, not an integer", ">= 1")


@pytest.mark.parametrize("value", ["2.5", "3.0", "3e0"])
def test_float_for_an_int(tmp_path, value):
    found = problems(tmp_path, f"scene: pin\nnumerics:\n  cycle_count: {value}\n")
    shown = repr(float(value))
    assert found == [
        f"numerics.cycle_count: {shown} is a float, not an integer: must be an integer >= 2"
    ]


def test_int_below_minimum(tmp_path):
    found = problems(tmp_path, "scene: pin\nnumerics:\n  cycle_count: 1\n")
    assert found == ["numerics.cycle_count: 1 is out of range: must be >= 2"]


def test_bool_for_a_float(tmp_path):
    found = problems(tmp_path, "scene: pin\nparams:\n  mu: true\n")
    assert found == ["params.mu: true is a boolean, not a number: must be a finite number > 0"]


def test_bool_for_an_int(tmp_path):
    found = problems(tmp_path, "scene: pin\nnumerics:\n  max_events: false\n")
    assert_problem(found, "numerics.max_events: false is a boolean, not an integer")


@pytest.mark.parametrize(
    ("value", "shown"), [("1", "1 is an integer"), ("yes", "'yes' is a string")]
)
def test_bool_only_true_or_false(tmp_path, value, shown):
    found = problems(tmp_path, f"scene: pin\nnumerics:\n  stop_on_stick: {value}\n")
    assert found == [f"numerics.stop_on_stick: {shown}, not a boolean: must be true or false"]


def test_null_for_a_float(tmp_path):
    found = problems(tmp_path, "scene: pin\nparams:\n  mu:\n")
    assert found == ["params.mu: missing value (null); must be a finite number > 0"]


def test_bad_method(tmp_path):
    found = problems(tmp_path, "scene: pin\nnumerics:\n  method: euler\n")
    assert found == [
        "numerics.method: 'euler' is not allowed: "
        "must be one of 'rodas4', 'rodas4-fixed', 'rodas5', 'scipy-radau', 'coulomb'"
    ]


def test_bad_mode(tmp_path):
    found = problems(tmp_path, "scene: pin\nnumerics:\n  mode: fast\n")
    assert found == ["numerics.mode: 'fast' is not allowed: must be 'decide' or 'converge'"]


def test_bad_scene(tmp_path):
    found = problems(tmp_path, "scene: ring\n")
    assert found == ["scene: 'ring' is not allowed: must be 'pin' or 'disk'"]


def test_missing_scene(tmp_path):
    found = problems(tmp_path, "params:\n  mu: 0.1\n")
    assert found == ["scene: missing; must be 'pin' or 'disk'"]


@pytest.mark.parametrize("points", [2, 12])
def test_pin_has_exactly_one_contact(tmp_path, points):
    found = problems(tmp_path, f"scene: pin\ncontact:\n  points: {points}\n")
    assert_problem(
        found, f"contact.points: {points} is not allowed for scene 'pin'", "exactly one contact"
    )


def test_pin_accepts_one_point(tmp_path):
    assert load(tmp_path, "scene: pin\ncontact:\n  points: 1\n").n_contacts == 1


@pytest.mark.parametrize("points", [0, -1, 1001])
def test_points_out_of_range(tmp_path, points):
    found = problems(tmp_path, f"scene: disk\ncontact:\n  points: {points}\n")
    assert found == [f"contact.points: {points} is out of range: must be >= 1 and <= 1000"]


@pytest.mark.parametrize("value", ["1.5", "0", "-0.5"])
def test_stribeck_ratio_out_of_range(tmp_path, value):
    found = problems(tmp_path, f"scene: pin\ncontact:\n  stribeck:\n    r: {value}\n")
    shown = repr(load_yaml_text(value))
    assert found == [f"contact.stribeck.r: {shown} is out of range: must be > 0 and <= 1"]


def test_stribeck_ratio_one_is_allowed(tmp_path):
    text = "scene: pin\ncontact:\n  stribeck:\n    r: 1\n    v_s: 1e-2\n    delta: 2\n"
    assert load(tmp_path, text).contact.stribeck.r == 1.0


def test_zero_damping(tmp_path):
    found = problems(tmp_path, "scene: pin\ncontact:\n  damping: 0\n")
    assert found == ["contact.damping: 0 is out of range: must be > 0 N s/m"]


@pytest.mark.parametrize(
    ("text", "shown"),
    [("- scene: pin\n", "a list [{'scene': 'pin'}]"), ("pin\n", "a string 'pin'"), ("", "null")],
)
def test_top_level_not_a_mapping(tmp_path, text, shown):
    found = problems(tmp_path, text)
    assert found == [
        f"(top level): expected a mapping with keys scene, params, contact, numerics; got {shown}"
    ]


@pytest.mark.parametrize(("value", "shown"), [("[0.1]", "a list [0.1]"), ("", "null")])
def test_section_not_a_mapping(tmp_path, value, shown):
    found = problems(tmp_path, f"scene: pin\nparams: {value}\n")
    assert_problem(found, "params: expected a mapping with keys mu, omega_m", f"; got {shown}")


def test_stribeck_not_a_mapping(tmp_path):
    found = problems(tmp_path, "scene: pin\ncontact:\n  stribeck: 1.0\n")
    assert found == [
        "contact.stribeck: expected a mapping with keys r, v_s, delta; got a float 1.0"
    ]


def test_all_problems_are_collected(tmp_path):
    text = "scene: pin\nparams:\n  m_s: -1\n  foo: 2\nnumerics:\n  rtol: 0\n  method: x\n"
    path = write(tmp_path, text)
    with pytest.raises(ConfigError) as info:
        load_scene(path)
    err = info.value
    paths = sorted(line.split(":")[0] for line in err.problems)
    assert paths == ["numerics.method", "numerics.rtol", "params.foo", "params.m_s"]
    assert str(err) == "\n".join(err.problems)
    assert err.source == str(path)


# --- overrides ----------------------------------------------------------------------


def test_overrides_are_parsed_as_strict_yaml(tmp_path):
    config = load(
        tmp_path,
        "scene: disk\nparams:\n  mu: 0.2\n",
        "params.mu=1e-4",
        "numerics.stop_on_stick=false",
        "contact.points=6",
        "contact.damping=500",
        "contact.stribeck.r = 0.5",
    )
    assert config.params.mu == 1e-4
    assert config.numerics.stop_on_stick is False
    assert config.n_contacts == 6
    assert config.contact_damping == 500.0
    assert config.contact.stribeck.r == 0.5


def test_later_override_wins(tmp_path):
    config = load(tmp_path, "scene: pin\n", "params.mu=0.2", "params.mu=0.3")
    assert config.params.mu == 0.3


def test_override_can_set_scene_on_empty_sections(tmp_path):
    config = load(tmp_path, "scene: pin\nparams:\n", "scene=disk", "params.mu=0.2")
    assert (config.scene, config.params.mu) == ("disk", 0.2)


@pytest.mark.parametrize("text", ["params.mu", "=0.1", " =0.1", "params..mu=1", ".mu=1", "1x=2"])
def test_malformed_override(tmp_path, text):
    found = problems(tmp_path, "scene: pin\n", text)
    assert found == [
        f"--set {text!r}: malformed override: expected KEY=VALUE with a dotted KEY, "
        "e.g. params.mu=0.13"
    ]


def test_all_malformed_overrides_are_reported(tmp_path):
    found = problems(tmp_path, "scene: pin\n", "a", "params.mu=0.2", "=1")
    assert [line.split(":")[0] for line in found] == ["--set 'a'", "--set '=1'"]


def test_override_of_unknown_key(tmp_path):
    found = problems(tmp_path, "scene: pin\n", "params.foo=1")
    assert_problem(found, "params.foo: unknown key", "under params", "(from --set params.foo=1)")


def test_override_goes_through_validation(tmp_path):
    found = problems(tmp_path, "scene: pin\n", "params.m_s=-1", "params.mu='0.1'")
    assert found == [
        "params.mu: '0.1' is a string, not a number: must be a finite number > 0 "
        "(write numbers without quotes) (from --set params.mu='0.1')",
        "params.m_s: -1 is out of range: must be > 0 kg (from --set params.m_s=-1)",
    ]


def test_override_points_for_pin(tmp_path):
    found = problems(tmp_path, "scene: pin\n", "contact.points=3")
    assert_problem(found, "contact.points: 3 is not allowed for scene 'pin'", "--set")


def test_override_value_with_bad_yaml(tmp_path):
    found = problems(tmp_path, "scene: pin\n", "params.mu=[0.1")
    assert_problem(found, "--set params.mu=[0.1, line 1", "invalid YAML")


def test_override_below_a_number(tmp_path):
    found = problems(tmp_path, "scene: pin\nparams:\n  mu: 0.2\n", "params.mu.x=1")
    assert found == ["params.mu: cannot set params.mu.x: expected a mapping, got a float 0.2"]


def test_scene_from_dict_does_not_mutate_input():
    data = {"scene": "pin", "params": {"mu": 0.2}}
    config = scene_from_dict(data, ["params.mu=0.3", "contact.eps=1e-8"])
    assert config.params.mu == 0.3
    assert data == {"scene": "pin", "params": {"mu": 0.2}}


def test_scene_from_dict_source_in_error():
    with pytest.raises(ConfigError) as info:
        scene_from_dict({"scene": "x"}, source="campaign item 3")
    assert info.value.source == "campaign item 3"


def test_overrides_must_be_a_sequence_of_strings():
    with pytest.raises(TypeError, match="sequence of 'KEY=VALUE' strings"):
        scene_from_dict({"scene": "pin"}, "params.mu=0.1")


def test_with_overrides(tmp_path):
    config = load(tmp_path, "scene: disk\n")
    changed = config.with_overrides({"params.mu": 0.12, "contact.points": 4})
    assert changed.params.mu == 0.12 and changed.n_contacts == 4
    assert config.params.mu == 0.13 and config.n_contacts == 12
    assert changed.numerics == config.numerics
    assert type(config.with_overrides({"params.mu": np.float64(0.2)}).params.mu) is float


WHOLE_SCENES = (
    {"scene": "pin", "params": {"mu": 0.2}},
    {"scene": "disk", "contact": {"points": 4}},
    {"scene": "disk", "contact": {"layout": "annulus", "inner_radius": 0.01, "outer_radius": 0.05}},
    {"scene": "disk", "contact": {"layout": "points", "positions": [[0.0, 0.01], [0.02, 0.0]]}},
)
SECTION_OVERRIDES = (
    {"params.mu": 0.3},
    {"params.mu": 1},
    {"params.mu": np.float64(0.13)},
    {"params.x0": -0.0},
    {"numerics.mode": "decide"},
    {"numerics.mode": "converge", "params.mu": 0.5},
    {"numerics.rtol": "auto", "numerics.atol": 1e-10},
    {"numerics.cycle_count": 4},
    {"contact.stiffness": 1.0e4},
    {"contact.points": 2},
    {"contact.stribeck": {"r": 0.5}},
    {"params.J_s": 0.05},
)


def whole_overrides(config, overrides):
    """with_overrides as every key was set before section-wise validation: the whole scene
    dumped, the keys set, validated again."""
    from frictiondisk.model.overrides import apply_overrides
    from frictiondisk.model.scene_keys import drop_unused

    data = drop_unused(config.model_dump(), config.scene, config.contact.layout)
    return SceneConfig.model_validate(apply_overrides(data, overrides.items(), "<overrides>"))


@pytest.mark.parametrize("scene", WHOLE_SCENES)
@pytest.mark.parametrize("overrides", SECTION_OVERRIDES)
def test_with_overrides_section_by_section_is_the_whole_validation(scene, overrides):
    """Keys validated section by section give the scene (and canonical form) of the whole
    validation, and refuse what it refuses, with the override named."""
    config = scene_from_dict(scene)
    try:
        expected = whole_overrides(config, overrides)
    except pydantic.ValidationError:
        with pytest.raises(ConfigError, match="from override"):
            config.with_overrides(overrides)
        return
    changed = config.with_overrides(overrides)
    assert changed == expected
    assert json.dumps(changed.canonical()) == json.dumps(expected.canonical())


def test_with_overrides_can_change_scene(tmp_path):
    pin = load(tmp_path, "scene: disk\n").with_overrides({"scene": "pin"})
    assert pin.n_contacts == 1


@pytest.mark.parametrize(
    ("overrides", "pieces"),
    [
        ({"params.mu": -0.1}, ("params.mu: -0.1 is out of range", "(from override params.mu)")),
        ({"params.mu": "0.1"}, ("params.mu: '0.1' is a string, not a number",)),
        ({"params.foo": 1.0}, ("params.foo: unknown key",)),
        ({"numerics.cycle_count": 2.5}, ("numerics.cycle_count: 2.5 is a float",)),
        ({"params..mu": 1.0}, ("'params..mu': malformed override key",)),
    ],
)
def test_with_overrides_validates(tmp_path, overrides, pieces):
    config = load(tmp_path, "scene: pin\n")
    with pytest.raises(ConfigError) as info:
        config.with_overrides(overrides)
    assert_problem(info.value.problems, *pieces)


# --- canonical form and hash ----------------------------------------------------------


def test_canonical_is_sorted_json_with_points_resolved(tmp_path):
    canonical = load(tmp_path, "scene: disk\n").canonical()
    assert list(canonical) == sorted(canonical)
    assert list(canonical["params"]) == sorted(canonical["params"])
    assert list(canonical["contact"]["stribeck"]) == sorted(canonical["contact"]["stribeck"])
    assert canonical["contact"]["points"] == 12
    assert canonical["contact"]["damping"] is None
    assert json.loads(json.dumps(canonical)) == canonical


def test_hash_matches_documented_recipe(tmp_path):
    config = load(tmp_path, "scene: pin\n")
    text = json.dumps(config.canonical(), sort_keys=True, separators=(",", ":"))
    assert config.content_hash() == hashlib.sha256(text.encode()).hexdigest()
    assert re.fullmatch("[0-9a-f]{64}", config.content_hash())


def test_hash_stable_across_key_order_and_spelling(tmp_path):
    a = load(tmp_path, "scene: disk\nparams:\n  mu: 0.2\n  x_ms: 0.05\nnumerics:\n  rtol: 1e-7\n")
    b = load(
        tmp_path, "numerics: {rtol: 0.0000001}\nparams: {x_ms: 5.0e-2, mu: 0.2}\nscene: disk\n"
    )
    c = load(tmp_path, "scene: disk\nparams: {mu: 0.2, x_ms: 0.05, m_s: 1}\n", "numerics.rtol=1e-7")
    d = load(
        tmp_path,
        "scene: disk\ncontact: {points: 12}\nparams: {mu: 0.2, x_ms: 0.05}\n",
        "numerics.rtol=1e-7",
    )
    assert a.content_hash() == b.content_hash() == c.content_hash() == d.content_hash()
    assert a.canonical() == d.canonical()


def test_hash_changes_when_a_value_changes(tmp_path):
    config = load(tmp_path, "scene: pin\n")
    hashes = {
        config.content_hash(),
        config.with_overrides({"params.mu": 0.13 + 1e-12}).content_hash(),
        config.with_overrides({"numerics.method": "scipy-radau"}).content_hash(),
        config.with_overrides({"scene": "disk"}).content_hash(),
        config.with_overrides({"contact.stribeck.r": 0.9}).content_hash(),
    }
    assert len(hashes) == 5


@pytest.mark.parametrize(
    "overrides",
    [
        (),
        ("scene=disk", "contact.points=5", "contact.damping=300.5", "params.beta_b=0.004"),
        ("contact.stribeck.r=0.3", "numerics.method=rodas4-fixed", "params.mu=0.1234567890123"),
        ("numerics.stop_on_stick=false", "contact.eps=1e-12", "params.x0=-2.5e-3"),
    ],
)
def test_to_yaml_round_trip(tmp_path, overrides):
    config = load(tmp_path, "scene: pin\n", *overrides)
    text = config.to_yaml()
    again = load_scene(write(tmp_path, text, "again.yaml"))
    assert again.canonical() == config.canonical()
    assert again.content_hash() == config.content_hash()
    assert again.to_yaml() == text
    explicit = config.with_overrides({"contact.points": config.n_contacts})
    assert again == explicit


# --- derived quantities ---------------------------------------------------------------


def test_contact_damping_default_is_critical_for_the_pin(tmp_path):
    config = load(tmp_path, "scene: pin\n")
    assert config.contact_damping == pytest.approx(2 * math.sqrt(2.53e5))
    assert config.contact_damping == pytest.approx(1006, abs=0.1)


def test_contact_damping_ratio_and_explicit_value(tmp_path):
    text = "scene: pin\nparams: {m_s: 4}\ncontact: {damping_ratio: 0.5, stiffness: 1e4}\n"
    assert load(tmp_path, text).contact_damping == pytest.approx(0.5 * 2 * math.sqrt(4e4))
    text = "scene: pin\ncontact: {damping: 123.0, damping_ratio: 0.5}\n"
    assert load(tmp_path, text).contact_damping == 123.0


def test_contact_positions_pin(tmp_path):
    positions = load(tmp_path, "scene: pin\n").contact_positions()
    assert positions.shape == (1, 2)
    assert np.all(positions == 0.0)


def test_contact_positions_disk_default(tmp_path):
    positions = load(tmp_path, "scene: disk\n").contact_positions()
    assert positions.shape == (12, 2)
    np.testing.assert_allclose(np.hypot(*positions.T), 0.05, rtol=1e-15)
    np.testing.assert_allclose(positions[0], [0.05, 0.0])
    np.testing.assert_allclose(positions[3], [0.0, 0.05], atol=1e-17)
    np.testing.assert_allclose(positions.sum(axis=0), 0.0, atol=1e-16)


def test_contact_positions_disk_custom(tmp_path):
    config = load(tmp_path, "scene: disk\ncontact: {points: 5, ring_radius: 0.1}\n")
    positions = config.contact_positions()
    assert positions.shape == (5, 2)
    angles = np.arctan2(positions[:, 1], positions[:, 0]) % (2 * np.pi)
    np.testing.assert_allclose(angles, 2 * np.pi * np.arange(5) / 5, atol=1e-15)
    np.testing.assert_allclose(np.hypot(*positions.T), 0.1, rtol=1e-15)


def test_single_point_disk(tmp_path):
    config = load(tmp_path, "scene: disk\ncontact: {points: 1}\n")
    np.testing.assert_allclose(config.contact_positions(), [[0.05, 0.0]])


def test_config_modules_do_not_import_numba():
    code = "import sys, frictiondisk.model.scene, frictiondisk.model.yamlio; sys.exit('numba' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0
