"""The well-posedness study (benchmarks/study_wellposed.py): its scenes, its rule for who
was right in a dispute, and one scene end to end against the dense reference."""

from __future__ import annotations

import dataclasses
import importlib.util
import math
import sys
from pathlib import Path

import pytest

STUDY = Path(__file__).resolve().parents[1] / "benchmarks" / "study_wellposed.py"


@pytest.fixture(scope="module")
def study():
    spec = importlib.util.spec_from_file_location("study_wellposed", STUDY)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


def test_scenes_are_seeded_cover_both_bodies_and_half_are_stribeck(study):
    scenes = [study.draw_scene(1, k) for k in range(8)]
    assert scenes == [study.draw_scene(1, k) for k in range(8)]
    assert {s["scene"] for s in scenes} == {"pin", "disk"}
    assert sum(bool(s["contact"].get("stribeck")) for s in scenes) == 4
    assert study.draw_scene(2, 0) != scenes[0]


def found(study, mu_star, claims, certification="certified"):
    return study.Found(
        status="converged",
        reason="",
        mu_star=mu_star,
        mu_lo=mu_star - 5e-5,
        mu_hi=mu_star + 5e-5,
        n_jumps=1,
        windows=(),
        certification=certification,
        grid_share=1.0,
        resolution=0.03,
        claims=tuple(claims),
        runs=0,
        wall_s=0.0,
    )


def test_a_dispute_is_settled_against_the_side_a_long_run_contradicts(study):
    # the default says 0.20 does not stick; the reference says it sticks (mu* 0.15)
    default = found(study, 0.25, [(0.20, False), (0.25, True)])
    reference = found(study, 0.15, [(0.15, True), (0.20, True)])
    row = {"default": default, "reference": reference}
    assert study.disagrees(default, reference)
    assert 0.20 in study.disputed(default, reference)
    row["settled"] = [{"mu": 0.20, "sticks": True}]
    assert study.verdict(row) == "reference"
    assert study.silent_errors([{**row, "seed": 0, "index": 0}]) == 1
    row["settled"] = [{"mu": 0.20, "sticks": False}]
    assert study.verdict(row) == "default"
    row["settled"] = [{"mu": 0.20, "sticks": None}]
    assert study.verdict(row) == "unsettled"


def test_a_lower_jump_that_persists_is_one_the_default_missed(study):
    """Well-posedness seed 3 scene 14: the default's grid stepped over a jump the
    reference found 0.12 lower. Every verdict either side claimed is right (or stays
    undetermined), yet the slave sticks at the reference's mu_hi and 2 ... 20 tol above
    it: the default's certified headline is not the lowest rising jump."""
    default = found(study, 0.205, [(0.08, False), (0.11, False), (0.205, True)])
    reference = found(
        study, 0.0868, [(0.08, False), (0.0868 - 5e-5, False), (0.0868 + 5e-5, True), (0.14, False)]
    )
    row = {"default": default, "reference": reference}
    row["settled"] = [
        {"mu": reference.mu_lo, "sticks": False},
        {"mu": reference.mu_hi, "sticks": True},
        {"mu": 0.14, "sticks": None},
    ]
    assert study.lower_reference(row) and study.disputed(default, reference)[0] == reference.mu_lo
    row["persisted"] = [{"mu": reference.mu_hi + k * study.TOL, "sticks": True} for k in (2, 5)]
    assert study.missed_jump(row) and study.verdict(row) == "reference"
    assert study.silent_errors([{**row, "seed": 3, "index": 14}]) == 1
    # a window narrower than the watched steps (it slides 10 tol above) is not a jump that
    # persists: the dispute stays as the claims settle it
    row["persisted"][1]["sticks"] = False
    assert not study.missed_jump(row) and study.verdict(row) == "unsettled"
    # nor is a reference jump whose sticking side does not stick when watched
    row["persisted"][1]["sticks"] = True
    row["settled"][1]["sticks"] = None
    assert not study.missed_jump(row)
    # a reference that sticks at its own mu_lo too is wrong there, and the default still
    # missed the sticking above it: neither is right
    row["settled"][1]["sticks"] = True
    row["settled"][0]["sticks"] = True
    assert study.missed_jump(row) and study.verdict(row) == "neither"


def test_a_wide_bracket_that_holds_the_lower_jump_did_not_miss_it(study):
    """Well-posedness seed 1 scene 43: the default's bracket straddles undetermined mu and
    is 4 tol wide, [0.174781, 0.175188]; the reference's, [0.174785, 0.174883], lies inside
    it, so their mid points are 1.5 tol apart. A stick at the reference's mu_hi is then no
    jump the default missed: its bracket reported it."""
    default = found(study, 0.1749845, [(0.174781, False), (0.175188, True)])
    default = dataclasses.replace(default, mu_lo=0.174781, mu_hi=0.175188)
    reference = found(study, 0.174834, [(0.174785, False), (0.174883, True)])
    reference = dataclasses.replace(reference, mu_lo=0.174785, mu_hi=0.174883)
    row = {"default": default, "reference": reference}
    row["settled"] = [
        {"mu": 0.174781, "sticks": None},
        {"mu": 0.174785, "sticks": None},
        {"mu": 0.174883, "sticks": True},
        {"mu": 0.175188, "sticks": True},
    ]
    row["persisted"] = [{"mu": 0.174883 + k * study.TOL, "sticks": True} for k in (2, 5)]
    assert study.disagrees(default, reference) and study.lower_reference(row)
    assert not study.missed_jump(row) and study.verdict(row) == "unsettled"
    # the same reference below the default's bracket is a jump the default missed
    low = dataclasses.replace(default, mu_lo=0.17490, mu_star=0.17504)
    assert study.missed_jump({**row, "default": low})


def test_a_longer_watch_replaces_only_the_undetermined_ones(study):
    """benchmarks/settle_longer.py: an unsettled dispute is run again only where a watch
    ended undetermined, and the longer watch then settles it."""
    spec = importlib.util.spec_from_file_location(
        "settle_longer", STUDY.with_name("settle_longer.py")
    )
    longer = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(longer)  # imports study_wellposed, registered by the fixture
    default = found(study, 0.25, [(0.20, False), (0.25, True)])
    reference = found(study, 0.15, [(0.15, True), (0.20, True)])
    row = {
        "default": default,
        "reference": reference,
        "settled": [{"mu": 0.15, "sticks": True}, {"mu": 0.20, "sticks": None}],
        "persisted": [],
    }
    assert longer.unsettled([row]) == [row]
    assert longer.undecided_watches(row) == [0.20]
    watched = {0.15: {"mu": 0.15, "sticks": False}, 0.20: {"mu": 0.20, "sticks": False}}
    after = longer.with_longer(row, watched)
    assert after["settled"][0]["sticks"] is True  # decided before: kept
    assert study.verdict(after) == "default"
    assert study.verdict(longer.with_longer(row, {})) == "unsettled"


def test_one_scene_agrees_with_the_dense_reference_or_is_settled_for_the_default(study):
    rows = study.run_study([0], 1, processes=1)
    (row,) = rows
    default, reference = row["default"], row["reference"]
    assert math.isfinite(reference.mu_star)
    if default.certified:
        if study.disagrees(default, reference):
            assert study.verdict(row) in ("default", "both"), row["settled"]
        else:
            assert abs(default.mu_star - reference.mu_star) <= study.TOL * (1 + 1e-9)
    else:  # not certified: said, with the reason, never a number passed off as certified
        assert default.status == "failed" or default.certification == "uncertain"
        assert "stricter numerics" in default.reason, default.reason
    assert study.silent_errors(rows) == 0
