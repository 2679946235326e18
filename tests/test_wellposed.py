"""The well-posedness study (frictiondisk.studies.wellposed): its scenes, its campaigns, its
rule for who was right in a dispute, its report, and one scene end to end on the engine
against the dense reference."""

from __future__ import annotations

import dataclasses
import json
import math

import pytest

from frictiondisk.studies import campaigns
from frictiondisk.studies.wellposed import found as found_module
from frictiondisk.studies.wellposed import judge, longer, report, rows, scenes, settings, study
from frictiondisk.studies.wellposed.found import Found

TOL = settings.TOL


def test_scenes_are_seeded_cover_both_bodies_and_half_are_stribeck():
    drawn = [scenes.draw_scene(1, k) for k in range(8)]
    assert drawn == [scenes.draw_scene(1, k) for k in range(8)]
    assert {s["scene"] for s in drawn} == {"pin", "disk"}
    assert sum(bool(s["contact"].get("stribeck")) for s in drawn) == 4
    assert scenes.draw_scene(2, 0) != drawn[0]
    assert scenes.parse_seeds("1-3") == [1, 2, 3] and scenes.parse_seeds("1,5") == [1, 5]
    assert scenes.parse_scene("3/14") == (3, 14)
    with pytest.raises(ValueError, match="SEED/INDEX"):
        scenes.parse_scene("3")


def test_the_settings_are_campaigns_of_the_study_numerics():
    """The default runs the campaign defaults at tol 1e-4; the reference a dense prescan at
    horizon x 8 and rtol, atol / 100 of the default's numerics; a watch t_decide 1 500 s,
    rtol, atol and eps / 100, observing; the exact watch the Coulomb integrator."""
    scene = scenes.draw_scene(1, 48)  # a pin with Coulomb friction
    default = campaigns.campaign(settings.locate_campaign("d", scene, "default"))
    assert default.task.certify.enabled and default.task.prescan.stride is None
    assert default.task.prescan.mu == settings.default_grid(0.01)
    assert default.task.tol == TOL and default.numerics_choice.chosen  # numerics auto
    num = default.base.numerics
    given = {"t_decide": num.t_decide, "rtol": num.rtol, "atol": num.atol}
    reference = campaigns.campaign(settings.locate_campaign("r", scene, "reference", given))
    assert reference.task.prescan.stride == 1 and not reference.task.certify.enabled
    assert reference.base.numerics.t_decide == num.t_decide * 8
    assert reference.base.numerics.rtol == num.rtol / 100
    point = default.points()[0].config
    assert point.params.x_ms == scene["params"]["x_ms"]
    watch = settings.watch_scene(point)
    assert watch["numerics"]["evidence"] == "observe" and watch["numerics"]["t_decide"] == 1500
    assert watch["contact"]["eps"] == point.contact.eps * settings.SETTLE_EPS
    exact = settings.watch_scene(point, exact=True)
    assert exact["numerics"]["method"] == "coulomb"
    prefix = settings.watch_prefix(1, 48, "coulomb", exact)
    assert prefix != settings.watch_prefix(1, 48, "coulomb", settings.watch_scene(point, 8, True))
    scan = campaigns.campaign(settings.watch_campaign(prefix, exact, [0.2, 0.1, 0.2]))
    assert scan.task.mu == (0.1, 0.2) and scan.task.mode == "decide"
    with pytest.raises(ValueError, match="default's numerics"):
        settings.locate_campaign("r", scene, "reference")


def found(mu_star, claims, certification="certified", **changes):
    base = Found(
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
    return dataclasses.replace(base, **changes)


def test_a_dispute_is_settled_against_the_side_a_long_run_contradicts():
    # the default says 0.20 does not stick; the reference says it sticks (mu* 0.15)
    default = found(0.25, [(0.20, False), (0.25, True)])
    reference = found(0.15, [(0.15, True), (0.20, True)])
    row = {"default": default, "reference": reference}
    assert judge.disagrees(default, reference)
    assert 0.20 in judge.disputed(default, reference)
    row["settled"] = [{"mu": 0.20, "sticks": True}]
    assert judge.verdict(row) == "reference"
    assert judge.silent_errors([{**row, "seed": 0, "index": 0}]) == 1
    row["settled"] = [{"mu": 0.20, "sticks": False}]
    assert judge.verdict(row) == "default"
    row["settled"] = [{"mu": 0.20, "sticks": None}]
    assert judge.verdict(row) == "unsettled"


def test_an_open_watch_where_both_sides_claim_the_same_leaves_no_dispute_there():
    # the default's bracket [0.20, 0.25] holds the reference's jump at 0.22
    default = found(0.225, [(0.18, False), (0.20, False), (0.25, True)], mu_lo=0.20, mu_hi=0.25)
    reference = found(0.22, [(0.20, False), (0.22, True)])
    row = {"default": default, "reference": reference}
    row["settled"] = [{"mu": 0.18, "sticks": None}, {"mu": 0.22, "sticks": False}]
    # 0.18: the default says no stick, and so does the reference (below its headline)
    assert judge.implied_claim(reference, 0.18) is False
    assert judge.verdict(row) == "default"  # the reference's 0.22 does not stick
    row["settled"][1]["sticks"] = None  # open, and inside the default's bracket
    assert judge.implied_claim(default, 0.22) is None
    assert judge.verdict(row) == "default"
    # 0.25: the default says it sticks, the reference (5 tol above its mu_hi) says nothing
    row["settled"] = [{"mu": 0.20, "sticks": None}, {"mu": 0.25, "sticks": None}]
    assert judge.verdict(row) == "unsettled"
    # the reference's jump 1 tol above the default's mu_hi: the default claims that its
    # headline persists there, the reference that it does not stick
    low = found(0.21, [(0.20, False), (0.21, True)])
    high = found(0.2101, [(0.20995, False), (0.21005, True)])
    row = {"default": low, "reference": high, "settled": [{"mu": 0.20995, "sticks": None}]}
    assert judge.implied_claim(low, 0.20995) is None  # inside its bracket [0.20995, 0.21005]
    row["settled"] = [{"mu": 0.21015, "sticks": None}]
    row["reference"] = dataclasses.replace(high, claims=((0.21015, False), (0.21025, True)))
    assert judge.implied_claim(low, 0.21015) is True
    assert judge.verdict(row) == "unsettled"


def test_a_lower_jump_that_persists_is_one_the_default_missed():
    """Well-posedness seed 3 scene 14: the default's grid stepped over a jump the
    reference found 0.12 lower. Every verdict either side claimed is right (or stays
    undetermined), yet the slave sticks at the reference's mu_hi and 2 ... 20 tol above
    it: the default's certified headline is not the lowest rising jump."""
    default = found(0.205, [(0.08, False), (0.11, False), (0.205, True)])
    reference = found(
        0.0868, [(0.08, False), (0.0868 - 5e-5, False), (0.0868 + 5e-5, True), (0.14, False)]
    )
    row = {"default": default, "reference": reference}
    row["settled"] = [
        {"mu": reference.mu_lo, "sticks": False},
        {"mu": reference.mu_hi, "sticks": True},
        {"mu": 0.14, "sticks": None},
    ]
    assert judge.lower_reference(row) and judge.disputed(default, reference)[0] == reference.mu_lo
    row["persisted"] = [{"mu": reference.mu_hi + k * TOL, "sticks": True} for k in (2, 5)]
    assert judge.missed_jump(row) and judge.verdict(row) == "reference"
    assert judge.silent_errors([{**row, "seed": 3, "index": 14}]) == 1
    # a window narrower than the watched steps (it slides 10 tol above) is not a jump that
    # persists: the dispute stays as the claims settle it, both right (0.14, open, is
    # below the default's headline: both say it does not stick)
    row["persisted"][1]["sticks"] = False
    assert not judge.missed_jump(row) and judge.verdict(row) == "both"
    # nor is a reference jump whose sticking side does not stick when watched
    row["persisted"][1]["sticks"] = True
    row["settled"][1]["sticks"] = None
    assert not judge.missed_jump(row)
    # a reference that sticks at its own mu_lo too is wrong there, and the default still
    # missed the sticking above it: neither is right
    row["settled"][1]["sticks"] = True
    row["settled"][0]["sticks"] = True
    assert judge.missed_jump(row) and judge.verdict(row) == "neither"


def test_a_wide_bracket_that_holds_the_lower_jump_did_not_miss_it():
    """Well-posedness seed 1 scene 43: the default's bracket straddles undetermined mu and
    is 4 tol wide, [0.174781, 0.175188]; the reference's, [0.174785, 0.174883], lies inside
    it, so their mid points are 1.5 tol apart. A stick at the reference's mu_hi is then no
    jump the default missed: its bracket reported it."""
    default = found(
        0.1749845, [(0.174781, False), (0.175188, True)], mu_lo=0.174781, mu_hi=0.175188
    )
    reference = found(
        0.174834, [(0.174785, False), (0.174883, True)], mu_lo=0.174785, mu_hi=0.174883
    )
    row = {"default": default, "reference": reference}
    row["settled"] = [
        {"mu": 0.174781, "sticks": None},
        {"mu": 0.174785, "sticks": None},
        {"mu": 0.174883, "sticks": True},
        {"mu": 0.175188, "sticks": True},
    ]
    row["persisted"] = [{"mu": 0.174883 + k * TOL, "sticks": True} for k in (2, 5)]
    assert judge.disagrees(default, reference) and judge.lower_reference(row)
    assert not judge.missed_jump(row)
    # open: the default's 0.174781 (the reference, lower, says the same: no dispute there)
    # and the reference's 0.174785 (inside the default's bracket): the default's claims stand
    assert judge.verdict(row) == "default"
    # the same reference below the default's bracket is a jump the default missed
    low = dataclasses.replace(default, mu_lo=0.17490, mu_star=0.17504)
    assert judge.missed_jump({**row, "default": low})


def test_a_coulomb_pin_is_watched_by_the_exact_integrator_too():
    """combine_watches: the verdict one watch shows counts; two that differ leave it open."""
    pin = {"scene": "pin", "params": {"x_ms": 0.08}, "contact": {}}
    assert scenes.coulomb_pin(pin)
    assert not scenes.coulomb_pin({**pin, "contact": {"stribeck": {"r": 0.7, "v_s": 0.01}}})

    def shows(outcome):
        return {"outcome": outcome, "t_end": 1.0, "reason": outcome}

    run = judge.combine_watches(0.1, shows("undetermined"), shows("stick"))
    assert run["sticks"] is True and run["coulomb"]["outcome"] == "stick"
    run = judge.combine_watches(0.1, shows("stick_slip"), shows("stick"))
    assert run["sticks"] is None and run["outcome"] == "conflict"  # settles nothing
    assert judge.combine_watches(0.1, shows("stick_slip"), shows("undetermined"))["sticks"] is False
    alone = judge.combine_watches(0.1, shows("stick"))
    assert alone["sticks"] is True and "coulomb" not in alone


def test_a_reused_settling_run_of_a_coulomb_pin_gains_the_exact_watch():
    """--settled-from rows written before the exact Coulomb watch: the regularized watch
    is reused, the exact one comes from this study's scan; a run that has both is taken."""
    pin = scenes.draw_scene(1, 48)  # a pin with Coulomb friction
    row = {"seed": 1, "index": 48, "scene": pin}
    old = {"mu": 0.20, "outcome": "undetermined", "sticks": None, "t_end": 1.0, "reason": "r"}
    exact = {"outcome": "stick", "t_end": 317.0, "reason": "creeps onto its rim"}
    assert study.earlier_watch(old, "regularized")["outcome"] == "undetermined"
    assert study.earlier_watch(old, "coulomb") is None  # so the study runs it
    shown = {(1, 48, "coulomb"): {0.20: exact}}
    run = study.settling_run(row, 0.20, shown, {(1, 48): {0.20: old}})
    assert run["sticks"] is True and run["reused"] and run["coulomb"] == exact
    both = judge.combine_watches(0.15, exact, exact)
    run = study.settling_run(row, 0.15, {}, {(1, 48): {0.15: both}})  # nothing run
    assert run["sticks"] is True and run["reused"]


def test_a_longer_watch_replaces_only_the_undetermined_ones():
    """wellposed.longer: an unsettled dispute is run again only where a watch ended
    undetermined, and the longer watch then settles it."""
    default = found(0.25, [(0.20, False), (0.25, True)])
    reference = found(0.15, [(0.15, True), (0.20, True)])
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
    assert judge.verdict(after) == "default"
    assert judge.verdict(longer.with_longer(row, {})) == "unsettled"


def test_the_report_counts_disagreements_silent_errors_and_failures(tmp_path):
    """The report on synthetic rows, and the rows file that carries them to a later study
    (in the line format of the former study's cache, which it also reads)."""
    pin = scenes.draw_scene(1, 0)
    agree = found(0.15, [(0.14, False), (0.15, True)], runs=10, wall_s=2.0)
    wrong = found(0.25, [(0.20, False), (0.25, True)], runs=12, wall_s=3.0)
    failed = dataclasses.replace(agree, status="failed", reason="undetermined at 0.3")
    cheap = dataclasses.replace(agree, wall_s=1.5)
    rows_ = [
        {"seed": 1, "index": 0, "scene": pin, "default": agree, "uncertified": cheap},
        {"seed": 1, "index": 2, "scene": pin, "default": wrong, "uncertified": cheap},
        {"seed": 1, "index": 4, "scene": pin, "default": failed, "uncertified": cheap},
    ]
    for row, ref in zip(rows_, (agree, found(0.15, [(0.20, True)]), agree), strict=True):
        row.update(reference=ref, settled=[], persisted=[])
    rows_[1]["settled"] = [{"mu": 0.20, "outcome": "stick", "sticks": True, "t_end": 99.0}]
    lines = report.report(rows_, 10.0)
    assert "1 disagree; settled run by run: reference right 1" in lines[1]
    assert lines[2].endswith(": 1")  # silent: settled against a certified default
    assert "failed points (honest, with a reason): 1 of 3 (33.3 %)" in lines[6]
    assert any("certification costs +56 %" in line for line in lines)  # 7.0 s over 4.5 s
    assert any(line.startswith("    1/2: 0.25000 [certified] vs 0.15000") for line in lines)
    assert any("failed 1/4: undetermined at 0.3" in line for line in lines)
    rows.write_rows(tmp_path, rows_)
    back = rows.read_rows(tmp_path)
    assert back[(1, 2)]["default"] == wrong and back[(1, 2)]["settled"] == rows_[1]["settled"]
    former = tmp_path / "former.jsonl"  # benchmarks/study_wellposed.py --cache
    entry = {"code": "abc", "seed": 1, "index": 2, "row": rows.to_json(rows_[1])}
    former.write_text(json.dumps(entry) + "\n")
    assert rows.read_rows(former)[(1, 2)]["reference"] == rows_[1]["reference"]
    assert rows.known_watches([former])[(1, 2)][0.20]["sticks"] is True


def test_generator_2_draws_its_own_wider_scenes():
    """Issue 50: an independent stream, a pin every fourth scene, disks from rest with small
    J_s, annulus layouts, braked disks, Stribeck v_s down to 0.002 m/s; 200 scenes valid."""
    drawn = [scenes.draw(2, 1, k) for k in range(200)]
    assert drawn[:8] == [scenes.draw_scene2(1, k) for k in range(8)]
    assert all(s != scenes.draw_scene(1, k) for k, s in enumerate(drawn[:8]))
    assert [s["scene"] for s in drawn[:4]] == ["pin", "disk", "disk", "disk"]
    disks = [s for s in drawn if s["scene"] == "disk"]
    assert any(s["contact"].get("layout") == "annulus" for s in disks)
    assert any(s["params"]["phidot0"] == 0.0 and s["params"]["J_s"] < 0.02 for s in disks)
    assert any(s["params"]["beta_b"] > 0.0 for s in disks)
    stribeck = [s["contact"]["stribeck"] for s in drawn if "stribeck" in s["contact"]]
    assert min(st["v_s"] for st in stribeck) < 0.003 and max(st["v_s"] for st in stribeck) <= 0.02
    for scene in drawn:
        campaigns.campaign(settings.locate_campaign("g2", scene, "default"))  # validates
    assert settings.scene_name(1, 4, generator=2) == "g2-s1-4" != settings.scene_name(1, 4)
    with pytest.raises(ValueError, match="generator must be one of"):
        scenes.draw(3, 1, 0)


def test_a_certified_end_that_its_watch_contradicts_is_a_silent_error_within_tol():
    """Issue 50: mu* within tol of the reference, but the watch at the certified mu_lo
    sticks (d1: 0.1516406 sticks at 171 s). A watch that stays undetermined contradicts
    nothing; an uncertified bracket makes no claim to count."""
    default = found(0.15168, [(0.1516406, False), (0.1517188, True)])
    default = dataclasses.replace(default, mu_lo=0.1516406, mu_hi=0.1517188)
    reference = found(0.15163, [(0.15162, False), (0.15164, True)])
    assert not judge.disagrees(default, reference)
    row = {"seed": 0, "index": 0, "default": default, "reference": reference, "settled": []}
    assert study.watched_mu(row) == ([], [], [0.1516406, 0.1517188])
    row["ends"] = [{"mu": 0.1516406, "sticks": True}, {"mu": 0.1517188, "sticks": True}]
    assert judge.end_contradicted(row) and judge.silent_errors([row]) == 1
    row["ends"][0]["sticks"] = None
    assert not judge.end_contradicted(row) and judge.silent_errors([row]) == 0
    row["ends"][1]["sticks"] = False  # the stick end that does not stick
    assert judge.end_contradicted(row)
    uncertain = {**row, "default": dataclasses.replace(default, certification="uncertain")}
    assert study.watched_mu(uncertain)[2] == [] and judge.silent_errors([uncertain]) == 0


def test_the_exact_watch_may_have_a_shorter_horizon():
    """--exact-horizon: the exact Coulomb watch runs to the given horizon, a watch scene,
    so a campaign, of its own; without it the whole watch budget."""
    scene = scenes.draw_scene(1, 48)  # a pin with Coulomb friction
    point = campaigns.campaign(settings.locate_campaign("d", scene, "default")).points()[0]
    whole = settings.watch_scene(point.config, exact=True)
    short = settings.watch_scene(point.config, exact=True, exact_horizon=1500.0)
    assert whole["numerics"]["t_decide"] == settings.SETTLE_HORIZON * settings.SETTLE_BUDGET
    assert short["numerics"]["t_decide"] == 1500.0
    assert short["numerics"]["method"] == "coulomb"
    assert settings.watch_prefix(1, 48, "coulomb", short) != settings.watch_prefix(
        1, 48, "coulomb", whole
    )
    assert settings.watch_scene(point.config, exact_horizon=1500.0) == settings.watch_scene(
        point.config
    )  # the regularized watch keeps its own


def test_the_report_says_what_the_end_watches_showed():
    default = found(0.15, [(0.14995, False), (0.15005, True)])
    exact = {"outcome": "undetermined", "t_end": 1500.0, "reason": "horizon reached"}
    row = {
        "default": default,
        "ends": [
            {"mu": default.mu_lo, "sticks": None, "coulomb": exact},
            {"mu": default.mu_hi, "sticks": True, "coulomb": {**exact, "outcome": "stick"}},
        ],
    }
    line = report.end_watch_line([row])
    assert "watched: 2: confirmed 1, contradicted 0, open 1" in line
    assert "exact Coulomb watches 2 (stick 1, the longest to 1500 s)" in line
    row["ends"][0]["sticks"] = True
    assert "confirmed 1, contradicted 1, open 0" in report.end_watch_line([row])


@pytest.mark.slow
def test_one_scene_agrees_with_the_dense_reference_or_is_settled_for_the_default(tmp_path):
    """Seed 0, scene 0 end to end: three find_jump campaigns on the engine, each read back
    by rebuilding its search from runs.nc (which a runs.nc short of a run cannot do); run
    again, it resumes from the journals and computes nothing. The bracket ends' watches
    (1 500 s or more each at rtol / 100) are left out here: the judge's reading of them is
    tested on rows above."""
    options = study.Options(watch_ends=False)
    (row,) = study.run_study([(0, 0)], tmp_path, options)
    assert row["ends"] == []
    default, reference = row["default"], row["reference"]
    assert math.isfinite(reference.mu_star)
    if default.certified:
        if judge.disagrees(default, reference):
            assert judge.verdict(row) in ("default", "both"), row["settled"]
        else:
            assert abs(default.mu_star - reference.mu_star) <= TOL * (1 + 1e-9)
    else:  # not certified: said, with the reason, never a number passed off as certified
        assert default.status == "failed" or default.certification == "uncertain"
        assert "stricter numerics" in default.reason, default.reason
    assert judge.silent_errors([row]) == 0
    assert default.runs > row["uncertified"].runs  # certification runs
    assert (0.02, False) in default.claims  # the lowest grid value does not stick
    campaign = campaigns.campaign(settings.locate_campaign("s0-0-default", row["scene"], "default"))
    runs = campaigns.results(tmp_path / "s0-0-default", "runs")
    assert found_module.replay(campaign, runs).headline().mu_star == default.mu_star
    with pytest.raises(found_module.ReplayMismatch, match="not in runs.nc"):
        found_module.replay(campaign, runs.isel(run=slice(1, None)))
    journal = sorted((tmp_path / "s0-0-reference" / "journal").iterdir())
    assert study.run_study([(0, 0)], tmp_path, options) == [row]
    assert sorted((tmp_path / "s0-0-reference" / "journal").iterdir()) == journal


def test_a_contradicted_end_is_watched_again_at_a_stricter_rtol():
    """G1 10/49: the watch at rtol 1e-6 read a slip of 1.7e-10 m a revolution at the
    certified mu_hi as a ratchet (`creep`), which the centre drift of its own integration
    error (1e-7 m a revolution) fed; at rtol 1e-8 the slip decays and the disk sticks.
    The stricter watch takes the first one's place where it decides; an end the exact
    Coulomb integrator contradicts is not watched again."""
    default = found(0.194305, [(0.194255, False), (0.194355, True)])
    lo, hi = default.mu_lo, default.mu_hi
    creep = {"outcome": "creep", "t_end": 2557.7, "reason": "ratchets"}
    stick = {"outcome": "stick", "t_end": 4837.3, "reason": "co-rotates"}
    open_ = {"outcome": "undetermined", "t_end": 12000.0, "reason": "budget"}
    row = {
        "seed": 10,
        "index": 49,
        "default": default,
        "ends": [judge.combine_watches(lo, open_), judge.combine_watches(hi, creep)],
    }
    assert judge.contradicted_ends(row) == [hi] and study.to_recheck(row) == [hi]
    confirmed = {**row, "ends": [judge.combine_watches(lo, creep), row["ends"][1]]}
    assert study.to_recheck(confirmed) == [hi]  # mu_lo's `creep`: does not stick, as claimed
    assert study.to_recheck(confirmed, confirmed=True) == [lo, hi]  # the control
    again = study.rewatched(row["ends"][1], stick)
    assert again["sticks"] is True and again["first"]["outcome"] == "creep"
    row["ends"][1] = again
    assert not judge.end_contradicted(row) and judge.silent_errors([row]) == 0
    line = report.end_watch_line([row])
    assert "confirmed 1, contradicted 0, open 1" in line
    assert "watched again at rtol / 100: 1 (decided there 1), then confirmed 1" in line
    kept = study.rewatched(judge.combine_watches(hi, creep), open_)
    assert kept["sticks"] is False and kept["stricter"] == open_  # undecided: it stands
    exact = judge.combine_watches(lo, open_, stick)  # the exact integrator: mu_lo sticks
    assert study.to_recheck({**row, "ends": [exact]}) == []
    campaign = campaigns.campaign(settings.locate_campaign("d", scenes.draw_scene(1, 0), "default"))
    point = campaign.points()[0].config
    first, strict = settings.watch_scene(point), settings.watch_scene(point, stricter=True)
    assert strict["numerics"]["rtol"] == pytest.approx(first["numerics"]["rtol"] / 100)
    assert strict["numerics"]["max_steps"] == first["numerics"]["max_steps"] * 4
