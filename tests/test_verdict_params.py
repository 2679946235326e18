"""VerdictParams (frictiondisk/verdict/params.py): every threshold of the verdict in one
documented record, passed in; docs/model.md shows the table generated from it."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from frictiondisk.cli.docs_blocks import block_text
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict.params import PARAMS, VerdictParams, allowed_range, markdown_table

FIELDS = {f.name: f for f in dataclasses.fields(VerdictParams)}

MODEL_DOC = Path(__file__).resolve().parents[1] / "docs" / "model.md"


def test_docs_model_shows_the_record_as_it_is():
    """docs/model.md holds the record's generated table (python -m
    frictiondisk.cli.docs_blocks rewrites it)."""
    assert block_text("verdict-params") in MODEL_DOC.read_text()
    assert markdown_table() in block_text("verdict-params")


def test_every_field_has_a_unit_and_a_one_line_reason():
    for field in dataclasses.fields(VerdictParams):
        assert field.metadata["unit"], field.name
        reason = field.metadata["reason"]
        assert reason and "\n" not in reason, field.name


def test_the_record_holds_the_dataclass_values_with_their_types():
    params = VerdictParams(q_max=0.95, verdict_revs=7)
    record = params.record()
    assert record.dtype == PARAMS
    for field in dataclasses.fields(VerdictParams):
        assert record[field.name] == getattr(params, field.name), field.name
    assert PARAMS["verdict_revs"].kind == "i" and PARAMS["q_max"].kind == "f"
    assert params.changed() == {"q_max": 0.95, "verdict_revs": 7}
    assert VerdictParams().changed() == {}


@pytest.mark.parametrize("method", ["rodas4", "scipy-radau", "coulomb"])
def test_the_defaults_passed_in_give_the_default_result(method):
    """simulate(config) and simulate(config, verdict=VerdictParams()) are the same run."""
    numerics = {"method": method, "stick_rule": "contacts", "t_decide": 10.0}
    config = scene_from_dict({"scene": "pin", "params": {"mu": 0.13}, "numerics": numerics})
    plain = simulate(config)
    given = simulate(config, verdict=VerdictParams())
    assert (plain.outcome, plain.reason, plain.t_end) == (given.outcome, given.reason, given.t_end)


def test_a_study_varies_a_threshold_without_editing_code():
    """A braked disk from rest co-rotates at 80 s by the default spacing of Aitken's limit;
    at a spacing of 2 revolutions the limit is read from a transient, 23 s earlier."""
    config = scene_from_dict({"scene": "disk", "params": {"beta_b": 0.005, "mu": 0.22}})
    default = simulate(config)
    close = simulate(config, verdict=VerdictParams(limit_min_spacing=2))
    assert default.outcome == close.outcome == "stick"
    assert close.t_end < default.t_end - 20.0


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("verdict_revs", 0),
        ("verdict_revs", 2.5),
        ("q_max", 1.5),
        ("q_max", 1.0),
        ("q_max", float("nan")),
        ("shakedown_zero", -0.01),
        ("stick_noise", -1e-9),
        ("rim_min_fall", 1.0),
        ("repeat_count", True),
    ],
)
def test_nonsense_is_refused_naming_the_field_and_its_range(field, value):
    allowed = str(allowed_range(FIELDS[field]))
    with pytest.raises(ValueError) as error:
        VerdictParams(**{field: value})
    assert f"VerdictParams.{field} = {value!r}" in str(error.value)
    assert allowed in str(error.value)


def test_every_default_lies_in_its_range_and_every_range_refuses_something():
    for field in dataclasses.fields(VerdictParams):
        allowed = allowed_range(field)
        assert allowed.holds(field.default), field.name
        assert not allowed.holds(-1.0), field.name  # no threshold may be negative


def test_the_ends_of_a_range_are_accepted_or_refused_as_written():
    assert VerdictParams(layout_alias=0.0).layout_alias == 0.0  # [0, ...): switches it off
    assert VerdictParams(shakedown_depth=1.0).shakedown_depth == 1.0  # (0, 1]
    with pytest.raises(ValueError, match=r"shakedown_depth = 0\.0: must be a number in \(0, 1\]"):
        VerdictParams(shakedown_depth=0.0)
