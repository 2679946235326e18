"""The cases behind the verdict's thresholds: one row per case, the exact scene, the rule it
exercises, the VerdictParams field it pins and the verdict it must get.

The thresholds live in frictiondisk/verdict/params.py with a one-line reason each; the
story of why each has its value lives here, next to a scene that shows it. "Study seed s
scene k" is scene k of seed s of the well-posedness study (frictiondisk/studies/wellposed/scenes.py
`draw_scene`, with the numerics a find_jump campaign at tol 1e-4 gives it). A row that a
dedicated test already runs with more checks names that test in `covered_by` and is not
run again here (the suite stays fast); the others run here, a few milliseconds each.
Where loosening the pinned threshold flips the verdict back to what the old rule said,
`loosened` holds that change and the verdict it gives: the row then shows what the
threshold is for.
"""

from __future__ import annotations

import dataclasses
import importlib

import pytest

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict.params import VerdictParams

STUDY_NUMERICS = {"rtol": 1e-5, "atol": 1e-8}  # what tol 1e-4 gives a pin of the study
SEED_2_SCENE_24 = {
    "scene": "pin",
    "params": {
        "m_s": 0.6745476336824494,
        "omega_m": 0.9943444417194423,
        "x0": 0.021310573216321738,
        "x_ms": 0.10299311299402525,
    },
    "numerics": STUDY_NUMERICS,
}
SEED_6_SCENE_32 = {
    "scene": "pin",
    "params": {
        "m_s": 1.2069731545667204,
        "omega_m": 0.623475036185456,
        "x0": -0.01241591952237234,
        "x_ms": 0.07645794844189288,
    },
    "numerics": STUDY_NUMERICS,
}
SEED_0_SCENE_0 = {
    "scene": "pin",
    "params": {
        "m_s": 0.5247914532927936,
        "omega_m": 1.2369616873214544,
        "x0": -0.027541588563828316,
        "x_ms": 0.07697867137638703,
    },
    "numerics": STUDY_NUMERICS,
}
SEED_5_SCENE_29 = {
    "scene": "disk",
    "params": {
        "J_s": 0.19456292266425598,
        "beta_b": 0.003253361480378537,
        "m_s": 1.5765768381017538,
        "omega_m": 0.8600184386410115,
        "phidot0": 0.8600184386410115,
        "x0": 0.020064640547567195,
        "x_ms": 0.06899156812280913,
    },
    "numerics": {"atol": 1e-12},
}
SEED_2_SCENE_45 = {
    "scene": "disk",
    "params": {
        "J_s": 0.12874130142481077,
        "beta_b": 0.00913919110974299,
        "m_s": 1.9022156268677537,
        "omega_m": 1.2615713082936066,
        "phidot0": 1.2615713082936066,
        "x0": -0.017332532437607392,
        "x_ms": 0.06883882400765393,
    },
    "numerics": {"atol": 1e-12},
}


def at(scene: dict, mu: float, **numerics) -> dict:
    """`scene` at friction coefficient mu, with numerics overrides."""
    return {
        **scene,
        "params": {**scene["params"], "mu": mu},
        "numerics": {**scene.get("numerics", {}), **numerics},
    }


@dataclasses.dataclass(frozen=True)
class Case:
    """One row: a scene that pins a threshold of the verdict."""

    name: str  # where the case comes from
    scene: dict  # the exact scene, as scene_from_dict takes it (None: a synthetic case)
    rule: str  # the rule it exercises (module.function in frictiondisk/verdict/)
    threshold: str  # the VerdictParams field it pins
    outcome: str  # the verdict the scene must get
    says: str  # words its reason must hold ("" for any)
    story: str  # what happened, and what the old rule made of it
    covered_by: str = ""  # "tests/file.py::test" that runs it with more checks
    loosened: tuple = ()  # ((field, value), ...) that flip the verdict, and ...
    loosened_outcome: str = ""  # ... the verdict it then gets ...
    loosened_says: str = ""  # ... and words of its reason


CASES = (
    Case(
        "study seed 2 scene 24, mu = 0.105",
        at(SEED_2_SCENE_24, 0.105),
        "grazing.grazes_inward",
        "graze_margin",
        "stick",
        "creeps onto the rim of its sticking disc",
        "a pin creeping onto its sticking disc, its slip per revolution falling from 1.4e-5 "
        "to 1.8e-8 m over 2 400 s, was read as a cycle within cycle_tol 1e-6 m; watched on, "
        "it sticks at 4 771 s. A repeat within the tolerance needs its slip per period shown "
        "steady (steady_fall), so it stayed undetermined; each of its slips carries it inward "
        "(m_s omega_m^2 = 0.667 < c_s), and the rim rule names it stick at 118 s",
        loosened=(("graze_margin", 1.5),),
        loosened_outcome="undetermined",
        loosened_says="without evidence that it will not stick",
    ),
    Case(
        "study seed 2 scene 24, mu = 0.103125",
        at(SEED_2_SCENE_24, 0.103125),
        "grazing.grazes_inward",
        "graze_slip",
        "stick",
        "creeps onto the rim of its sticking disc",
        "a pin on the rim of its sticking disc slips about 5e-11 m a cycle, at the friction "
        "law's floor: a slip that does not fall there was read as a departure from sticking, "
        "and the point's certified mu* lay 1.3 tol above the jump. No departure below s0 "
        "(depart_steps), and each slip, short beside its circle, carries it inward",
        loosened=(("graze_slip", 1e-12),),
        loosened_outcome="undetermined",
        loosened_says="without evidence that it will not stick",
    ),
    Case(
        "study seed 6 scene 32, mu = 0.07647",
        at(SEED_6_SCENE_32, 0.07647),
        "sliding.steady_sliding",
        "verdict_z",
        "undetermined",
        "without evidence that it will not stick",
        "slid 2.4, 2.5, 1.8, 1.8, 1.4, 1.3 e-2 m a revolution and was read as sliding at "
        "121 s; it sticks at 292 s. A fall that alternates on its way shows in the slope of "
        "ln(slip) over slide_revs revolutions",
    ),
    Case(
        "issue 50 disk d1 (Stribeck, from rest), mu = 0.1516406",
        None,
        "sliding.lowest_slip_holds",
        "envelope_periods",
        "stick",
        "",
        "the lower end of a certified bracket: its slip per revolution oscillates 2-4 % with "
        "a period of 5 revolutions (the beat of the slave's spring-mass frequency with the "
        "revolution) while its troughs fall 0.2204, 0.2167, 0.2128 m; a fall of 0.6 % a "
        "revolution is never established over 8 revolutions, and it was read as sliding at "
        "91.5 s. It sticks at 170.8 s. The lowest slip of the newest 2 periods against the 2 "
        "before sees the fall, and the run is extended until it sticks",
        covered_by="tests/test_sliding_envelope.py::test_an_oscillating_slip_whose_troughs_"
        "fall_is_watched_until_it_sticks",
    ),
    Case(
        "issue 50 disk d1 (Stribeck, from rest), mu = 0.15162",
        None,
        "sliding.envelope_window",
        "envelope_min_revs",
        "slide",
        "",
        "the same oscillation about a level (it slides a steady 0.2377 m a revolution to "
        "8000 s) is still read as sliding, at 160 s instead of 85 s: 2 windows of 10 "
        "revolutions (2 periods) must show the lowest slip not falling",
        covered_by="tests/test_sliding_envelope.py::test_a_slip_that_oscillates_about_a_level_"
        "is_still_a_sliding_state",
    ),
    Case(
        "study seed 6 scene 32, mu = 0.0765753",
        at(SEED_6_SCENE_32, 0.0765753),
        "grazing.grazes_inward",
        "graze_revs",
        "stick",
        "creeps onto the rim of its sticking disc",
        "every fifth revolution of its creep sticks whole (slip 4e-14 m); read step against "
        "step eight back such a revolution hid the trend and the old rule called a cycle. "
        "The approach is judged half against half over approach_steps (undetermined); 8 "
        "revolutions in a row that each slip a little inward are the rim rule's stick at 191 s",
        loosened=(("graze_margin", 1.5),),
        loosened_outcome="undetermined",
        loosened_says="without evidence that it will not stick",
    ),
    Case(
        "study seed 0 scene 0, mu = 0.085",
        at(SEED_0_SCENE_0, 0.085),
        "extrapolation.shakedown_limit",
        "shakedown_zero",
        "stick",
        "shakes down to co-rotation",
        "its slip per revolution switches irregularly between two levels (1.45e-8 and "
        "1.28e-8 m) while both fall 0.13 % a revolution; watched, the old rule read a cycle "
        "repeating within 2e-8 m. Extrapolated, the fall reaches nothing",
    ),
    Case(
        "study seed 0 scene 0, mu = 0.08",
        None,
        "extrapolation.shakedown_limit",
        "shakedown_zero",
        "stick",
        "shakes down",
        "its slip per revolution falls like a power law for 80 s, then levels off at a cycle "
        "slipping 3.5e-7 m a revolution: the shakedown read at 81 s is a prediction that "
        "watching (evidence observe) refutes",
        covered_by="tests/test_sections.py::test_an_extrapolated_shakedown_is_a_prediction_"
        "that_watching_can_refute",
    ),
    Case(
        "study seed 5 scene 29, mu = 0.129063",
        at(SEED_5_SCENE_29, 0.129063),
        "corotation._limit_slip, corotation_verdict",
        "limit_drift",
        "creep",
        "Koiter",
        "its slip per revolution, 1.66e-7 ... 9.9e-9 m over 16 revolutions, was read as a "
        "ratchet at 124 s: the same limit estimate made 1 ... 4 revolutions earlier lay "
        "higher (10.3 ... 9.1e-9 m), spread 13 %; watched it falls on and sticks at 482 s. "
        "The rules now wait; its own circle lies below Melan's bound, so Koiter decides",
        loosened=(("limit_drift", 1.0), ("bound_blocks", 300)),
        loosened_outcome="creep",  # the rules' own ratchet at 124 s, the old misreading
        loosened_says="ratchets on its small orbit at t = 124.2 s",
    ),
    Case(
        "study seed 2 scene 45, mu = 0.339131",
        at(SEED_2_SCENE_45, 0.339131),
        "corotation._limit_slip",
        "limit_drift",
        "creep",
        "Koiter",
        "its first 39 revolutions on the small orbit: watched, the slip levels off at 2.2e-8 "
        "m and the disk ratchets (creep at 647 s); its limit estimates rose to the newest, "
        "so no shakedown is read from them",
    ),
    Case(
        "study seed 1 scene 17, mu = 0.2945",
        None,
        "corotation._shown_not_falling",
        "fall_z",
        "stick",
        "",
        "a slip scattering about a level that falls 9 % a revolution (7e-9 m at 44 s, 6.5e-10 "
        "m at 600 s) was read `creep` at 59 s on one revolution's scatter",
        covered_by="tests/test_creep_limit.py::test_a_slip_that_falls_about_its_scatter_is_"
        "not_a_ratchet",
    ),
    Case(
        "study seed 5 scene 11, mu = 0.26081",
        None,
        "corotation.on_orbit, horizon_evidence.shaken_down",
        "verdict_revs",
        "creep",
        "Koiter",
        "the section's shakedown (power-law limit) read a late-levelling ratchet as `stick` "
        "at 151 s; watched it ratchets for good at 374 s. On the small orbit the co-rotation "
        "rule reads the slip",
        covered_by="tests/test_creep_limit.py::test_the_braked_disk_whose_ratchet_looked_like_"
        "shakedown_is_not_stick",
    ),
    Case(
        "study seed 1 scene 11, mu = 0.14504",
        None,
        "sliding.lowest_slip_holds, sliding._trend_not_falling",
        "envelope_min_revs",
        "stick",
        "",
        "a Stribeck disk from rest spins up at every revolution while its slip per "
        "revolution rises now and then: read as sliding at 145 s, it sticks at 162 s. A "
        "guard on the climbing spin held it until NUMERICS_VERSION 9; the lowest-slip "
        "comparison holds it alone (with verdict_z 10), and so does the slope test alone "
        "(with envelope_min_revs 1, envelope_periods 0.1); both loosened, it slides at 116 s",
        covered_by="tests/test_sections.py::test_a_disk_spinning_up_is_not_a_sliding_state",
    ),
    Case(
        "study seed 1 scene 43, mu = 0.17501",
        None,
        "section_evidence._contracts",
        "contract_slip_fall_stribeck",
        "undetermined",
        "",
        "its section contracts by 0.59 a revolution while its slip falls a steady 0.96 of the "
        "fall before; under a Stribeck law the falling slip speed feeds its own fall (it "
        "sticks at 1 265 s): read as a cycle, it was called `slide` at 350 s",
        covered_by="tests/test_sections.py::test_a_stribeck_disk_spinning_up_is_extended_not_"
        "called_sliding",
    ),
    Case(
        "study seed 2 scene 18, mu = 0.0885",
        None,
        "section_evidence._contracts",
        "q_max",
        "stick",
        "",
        "a Stribeck pin's cycle drifts onto sticking (its section moves 2e-3 m a cycle, the "
        "slip per cycle falls): called stick_slip at 91 s, it sticks at 141.7 s",
        covered_by="tests/test_sections.py::test_a_transient_towards_sticking_is_extended_not_"
        "classified",
    ),
    Case(
        "study seed 6 scene 10, mu = 0.151858",
        None,
        "section_evidence._contracts, _slip_ratio_bound",
        "contract_slip_fall",
        "stick",
        "",
        "contracts by 0.665 a revolution towards a cycle that still slips, read `slide` at "
        "46 s; its slip falls ever slower and it sticks at 102 s",
        covered_by="tests/test_sections.py::test_a_contraction_towards_an_unstable_cycle_is_"
        "extended_until_it_sticks",
    ),
    Case(
        "study seed 8 scene 21, Melan bound 0.41185",
        None,
        "shakedown_bound.bound_verdict",
        "bound_blocks",
        "stick",
        "Melan",
        "the rules alone leave mu = 0.4098 ... 0.4138 undecided at the 240 s horizon; the "
        "bound decides three tol either side",
        covered_by="tests/test_shakedown_verdict.py::test_the_bound_decides_both_sides_where_"
        "the_rules_cannot",
    ),
    Case(
        "Fig 11 co-rotating start, beta_b = 0.0275, mu = 0.705794",
        None,
        "shakedown_bound.holds_here",
        "bound_solver_rtol",
        "creep",
        "Koiter",
        "15 tol below its own circle's Melan bound its slip falls below eps T within 80 s, "
        "read as `stick` by the rules; the stick waits while its circle cannot hold it",
        covered_by="tests/test_shakedown_verdict.py::test_a_stick_of_the_rules_waits_while_its_"
        "own_circle_cannot_hold_it",
    ),
    Case(
        "the default pin at x_ms = 0.05, mu = 0.0501",
        {"scene": "pin", "params": {"mu": 0.0501, "x_ms": 0.05}},
        "extrapolation.shakedown_limit",
        "shakedown_depth",
        "stick_slip",
        "sticking and sliding alternate",
        "its slip per revolution falls 3.1e-2 -> 5.3e-3 m in 10 revolutions, geometric to the "
        "eye, then levels off at a stick-slip cycle: no limit is read from a first fall",
        loosened=(("shakedown_depth", 1.0),),
        loosened_outcome="stick",
        loosened_says="shakes down",
    ),
    Case(
        "the default disk at x_ms = 0.065, mu = 0.0653",
        {"scene": "disk", "params": {"mu": 0.0653, "x_ms": 0.065}},
        "extrapolation.aitken_limit",
        "aitken_slowing",
        "stick_slip",
        "sticking and sliding alternate",
        "fell 9.9e-4 then 8.4e-4 m in 4 revolutions each, an almost linear fall that "
        "extrapolated to 0, then kept a cycle slipping 2e-3 m",
    ),
    Case(
        "the default disk at x_ms = 0.065, mu = 0.06505",
        {"scene": "disk", "params": {"mu": 0.06505, "x_ms": 0.065}},
        "extrapolation.shakedown_limit",
        "shakedown_steps",
        "stick_slip",
        "sticking and sliding alternate",
        "slid 0.317 -> 2.7e-3 m a revolution without sticking as a whole, then kept a "
        "stick-slip cycle slipping 4e-4 m: a slave that slides ever less must first stick",
    ),
    Case(
        "the demo disk at x_ms = 0.12, mu = 0.142785",
        None,
        "section_evidence.section_evidence",
        "shakedown_zero",
        "stick_slip",
        "",
        "1.4e-9 m a revolution falling to a limit of 8.2e-10 m (below eps T), then rising "
        "again, at 1 500 s: a floor below eps T is a cycle there, not sticking",
        covered_by="tests/test_sections.py::test_a_slip_that_falls_to_nothing_is_shakedown",
    ),
    Case(
        "the default disk braked at beta_b = 0.005 from rest, mu = 0.22",
        {"scene": "disk", "params": {"beta_b": 0.005, "mu": 0.22}},
        "corotation._limit_slip",
        "limit_min_spacing",
        "stick",
        "co-rotates with the master",
        "at a spacing of 2 revolutions the last fast transient read as the limit (4.5e-8 m at "
        "51 s, true limit 0)",
    ),
    Case(
        "the default pin at rtol 1e-8, mu = 0.2",
        {"scene": "pin", "params": {"mu": 0.2}, "numerics": {"rtol": 1e-8}},
        "corotation.still",
        "verdict_revs",
        "stick",
        "co-rotates with the master",
        "a stuck pin at rtol 1e-8 drifts 1.5e-9 m a revolution, more than one step's "
        "tolerance: stillness allows the tolerance accumulated over the revolution's steps",
    ),
    Case(
        "the exact Coulomb pin creeping onto its rim",
        None,
        "rim_approach.rim_limit",
        "rim_min_fall",
        "stick",
        "rim of its sticking disc",
        "just above c_s x_ms / F_n the pin's stick onsets approach the rim of its sticking "
        "disc as 1/n without entering it: it sticks in the limit",
        covered_by="tests/test_coulomb.py::test_a_pin_creeping_onto_the_rim_of_its_sticking_"
        "disc_sticks_in_the_limit",
    ),
    Case(
        "the exact Coulomb pin on a stick-slip cycle, watched",
        None,
        "rim_approach.repeats",
        "rim_max_ratio_drift",
        "stick_slip",
        "",
        "a watched cycle must show its onsets repeat off the rim",
        covered_by="tests/test_coulomb.py::test_a_watched_stick_slip_cycle_needs_its_onsets_to_"
        "repeat",
    ),
)


SELF_CENTRING_PIN = {"scene": "pin", "params": {"mu": 0.095, "omega_m": 0.8}}
LARGE_CYCLE_PIN = {"scene": "pin", "params": {"mu": 0.05, "omega_m": 1.5, "x0": 0.4, "vy0": 0.5}}
CONVERGE_60 = {"mode": "converge", "t_max": 60.0}
CONVERGE_90 = {"mode": "converge", "t_max": 90.0}
MOTION_TEST = "tests/test_motion_evidence.py::"

# The pure-sliding motions (verdict/motion_evidence.py): each was `slide` before issue 49
MOTION_CASES = (
    Case(
        "self-centring pin (issue 49), 60 s",
        at(SELF_CENTRING_PIN, 0.095, **CONVERGE_60),
        "self_centring.rest",
        "own_rest_zero",
        "self_centring",
        "self-centres",
        "its largest speed per own period falls by a steady 0.730 to rest at |r| = 0.0312238 "
        "m, where it still slips: the old rules had no name for it and said `slide`",
        loosened=(("own_rest_zero", 0.0),),
        loosened_outcome="slide",
        loosened_says="neither comes to rest",
    ),
    Case(
        "large sliding cycle of the pin (issue 49), 90 s",
        at(LARGE_CYCLE_PIN, 0.05, **CONVERGE_90),
        "slide_cycle.cycle",
        "own_motion_keep",
        "slide_cycle",
        "contracts by 0.79",
        "its own section contracts by 0.794 a period towards a whirl at the support's own "
        "frequency, while the master-revolution section steps 0.75 m a revolution",
        loosened=(("own_motion_keep", 2.0),),
        loosened_outcome="slide",
        loosened_says="neither comes to rest",
    ),
    Case(
        "the default pin departing from sticking at the 30 s horizon",
        {"scene": "pin", "params": {"mu": 0.12}},
        "label._by_window",
        "depart_steps",
        "stick_slip",
        "sticking and sliding alternate in the final window",
        "a departure is evidence of not-stick; the run has shown sticking and sliding "
        "alternating, and that is its name (not converged). Named `slide` for a while, which "
        "a user reads as 'never sticks' (the paper's stick-slip demo read `slide`); in the "
        "pin maps of issue 49, 32 runs so named at 30 s go on to the large sliding cycle and "
        "15 self-centre: `cycle_converged` false says it has not settled",
    ),
    Case(
        "the modulated braked disk (issue 49), J_s 0.3, 48 points",
        None,
        "modulated.envelope",
        "env_tol",
        "modulated",
        "",
        "three envelopes of 136.5 s agree in period and depth (0.0312 m)",
        covered_by=MOTION_TEST + "test_the_example_disk_is_a_modulated_cycle",
    ),
    Case(
        "the circular whirl of the braked disk, J_s 0.1, 48 points",
        None,
        "modulated.envelope",
        "env_min_depth",
        "slide_cycle",
        "",
        "its ring's ripple of 1e-5 m keeps its section from repeating within cycle_tol",
        covered_by=MOTION_TEST + "test_the_whirl_below_the_torus_bifurcation_is_a_sliding_cycle",
    ),
    Case(
        "the 12-point whirl's layout ripple",
        None,
        "envelopes.aliased_ripple",
        "layout_alias",
        "slide_cycle",
        "",
        "0.69 % ripple at N |Omega - phidot| aliased into a 19.5 s beat: not a modulation",
        covered_by=MOTION_TEST + "test_the_ripple_of_a_12_point_ring_is_no_modulation",
    ),
    Case(
        "a sliding regime shorter than its evidence",
        None,
        "motion_evidence.judge",
        "own_slide_steps",
        "slide",
        "",
        "a sticking phase ends the regime; too few own periods after it name nothing",
        covered_by=MOTION_TEST + "test_too_few_sliding_rows_are_no_evidence",
    ),
)
CASES = CASES + MOTION_CASES

RUN_HERE = [case for case in CASES if not case.covered_by]


def test_every_row_pins_a_field_of_the_record():
    fields = {f.name for f in dataclasses.fields(VerdictParams)}
    assert {case.threshold for case in CASES} <= fields
    for case in CASES:
        assert (case.scene is None) == bool(case.covered_by), case.name
        assert not case.loosened or case.loosened_outcome, case.name


def test_every_covering_test_exists():
    for case in CASES:
        if case.covered_by:
            path, name = case.covered_by.split("::")
            module = importlib.import_module(path.removeprefix("tests/").removesuffix(".py"))
            assert callable(getattr(module, name, None)), case.covered_by


def test_every_rule_named_exists():
    """Each row's rule (module.function, or a function of the module named before it)
    is a function of frictiondisk/verdict/."""
    for case in CASES:
        module = None
        for part in case.rule.split(", "):
            if "." in part:
                module, _, name = part.rpartition(".")
            else:
                name = part
            found = importlib.import_module(f"frictiondisk.verdict.{module}")
            assert callable(getattr(found, name, None)), f"{case.name}: {part}"


@pytest.mark.parametrize("case", RUN_HERE, ids=[case.name for case in RUN_HERE])
def test_the_case_gets_its_verdict(case):
    res = simulate(scene_from_dict(case.scene))
    assert res.outcome == case.outcome, res.reason
    assert case.says in res.reason


@pytest.mark.parametrize(
    "case",
    [case for case in RUN_HERE if case.loosened],
    ids=[case.name for case in RUN_HERE if case.loosened],
)
def test_loosening_the_threshold_gives_the_old_verdict(case):
    res = simulate(scene_from_dict(case.scene), verdict=VerdictParams(**dict(case.loosened)))
    assert res.outcome == case.loosened_outcome, res.reason
    assert case.loosened_says in res.reason
