"""The well-posedness study (benchmarks/study_wellposed.py): its scenes, its rule for who
was right in a dispute, and one scene end to end against the dense reference."""

from __future__ import annotations

import dataclasses
import importlib.util
import math
import sys
from pathlib import Path
from types import SimpleNamespace

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


def test_an_open_watch_where_both_sides_claim_the_same_leaves_no_dispute_there(study):
    # the default's bracket [0.20, 0.25] holds the reference's jump at 0.22
    default = found(study, 0.225, [(0.18, False), (0.20, False), (0.25, True)])
    default = dataclasses.replace(default, mu_lo=0.20, mu_hi=0.25)
    reference = found(study, 0.22, [(0.20, False), (0.22, True)])
    row = {"default": default, "reference": reference}
    row["settled"] = [{"mu": 0.18, "sticks": None}, {"mu": 0.22, "sticks": False}]
    # 0.18: the default says no stick, and so does the reference (below its headline)
    assert study.implied_claim(reference, 0.18) is False
    assert study.verdict(row) == "default"  # the reference's 0.22 does not stick
    row["settled"][1]["sticks"] = None  # open, and inside the default's bracket
    assert study.implied_claim(default, 0.22) is None
    assert study.verdict(row) == "default"
    # 0.25: the default says it sticks, the reference (5 tol above its mu_hi) says nothing
    row["settled"] = [{"mu": 0.20, "sticks": None}, {"mu": 0.25, "sticks": None}]
    assert study.verdict(row) == "unsettled"
    # the reference's jump 1 tol above the default's mu_hi: the default claims that its
    # headline persists there, the reference that it does not stick
    low = found(study, 0.21, [(0.20, False), (0.21, True)])
    high = found(study, 0.2101, [(0.20995, False), (0.21005, True)])
    row = {"default": low, "reference": high, "settled": [{"mu": 0.20995, "sticks": None}]}
    assert study.implied_claim(low, 0.20995) is None  # inside its bracket [0.20995, 0.21005]
    row["settled"] = [{"mu": 0.21015, "sticks": None}]
    row["reference"] = dataclasses.replace(high, claims=((0.21015, False), (0.21025, True)))
    assert study.implied_claim(low, 0.21015) is True
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
    # persists: the dispute stays as the claims settle it, both right (0.14, open, is
    # below the default's headline: both say it does not stick)
    row["persisted"][1]["sticks"] = False
    assert not study.missed_jump(row) and study.verdict(row) == "both"
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
    assert not study.missed_jump(row)
    # open: the default's 0.174781 (the reference, lower, says the same: no dispute there)
    # and the reference's 0.174785 (inside the default's bracket): the default's claims stand
    assert study.verdict(row) == "default"
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
    assert list(longer.undecided_watches(row)) == [0.20]
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


def test_a_coulomb_pin_is_watched_by_the_exact_integrator_too(study, monkeypatch):
    """settle: the verdict one watch shows counts; two that differ leave it open."""
    import frictiondisk.simulation.simulate as simulation

    shown = {}

    def fake(config):
        outcome = shown[config.numerics.method]
        return SimpleNamespace(outcome=outcome, t_end=1.0, reason=outcome)

    monkeypatch.setattr(simulation, "simulate", fake)
    pin = {"scene": "pin", "params": {"x_ms": 0.08}, "contact": {}}
    assert study.coulomb_pin(pin)
    assert not study.coulomb_pin({**pin, "contact": {"stribeck": {"r": 0.7, "v_s": 0.01}}})
    shown.update(rodas4="undetermined", coulomb="stick")
    run = study.settle(pin, 0.1)
    assert run["sticks"] is True and run["coulomb"]["outcome"] == "stick"
    shown.update(rodas4="stick_slip", coulomb="stick")
    assert study.settle(pin, 0.1)["sticks"] is None  # a conflict settles nothing
    shown.update(rodas4="stick_slip", coulomb="undetermined")
    assert study.settle(pin, 0.1)["sticks"] is False
    # the regularized watch of an earlier call is taken, not run again
    shown.update(rodas4="stick", coulomb="stick_slip")
    earlier = {"outcome": "stick_slip", "t_end": 9.0, "reason": "a cycle"}
    assert study.settle(pin, 0.1, regularized=earlier)["sticks"] is False


def test_a_reused_settling_run_of_a_coulomb_pin_gains_the_exact_watch(study, monkeypatch):
    """--settled-from rows written before the exact Coulomb watch: the regularized watch
    is reused, the exact one is added; a run that has both is taken as it is."""
    default = found(study, 0.25, [(0.20, False), (0.25, True)])
    reference = found(study, 0.15, [(0.15, True), (0.20, True)])
    monkeypatch.setattr(
        study,
        "locate",
        lambda scene, setting, observe: {"default": default}.get(setting, reference),
    )
    calls = []

    def fake_settle(scene, mu, longer=1, regularized=None):
        calls.append((mu, regularized))
        return {"mu": mu, "sticks": True, "coulomb": {}}

    monkeypatch.setattr(study, "settle", fake_settle)
    seed, index = 1, 48  # a pin with Coulomb friction
    assert study.coulomb_pin(study.draw_scene(seed, index))
    old = {"mu": 0.20, "outcome": "undetermined", "sticks": None, "t_end": 1.0, "reason": ""}
    both = {**old, "mu": 0.15, "coulomb": {}}
    study.study_scene((seed, index, True, False, None, {0.20: old, 0.15: both}))
    assert (0.20, old) in calls  # the exact watch added, the regularized one reused
    assert all(mu != 0.15 for mu, _ in calls)  # taken as it is
