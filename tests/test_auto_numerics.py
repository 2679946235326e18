"""numerics auto (frictiondisk.model.auto_numerics): a find_jump's tol chooses the numerics
keys it does not give, from the error model of its scene kind. The rules are checked on
a small synthetic table (known answers) and on the package's measured table (the
properties that must hold for any data: monotone in tol, within the stated fraction of
tol, explicit keys win)."""

from __future__ import annotations

import pytest

from frictiondisk.model import auto_numerics as auto
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.tasks.campaign import campaign_from_dict

HEADER = "kind,knob,rtol,atol,t_decide,is_reference,status,points,error,n_steps,t_simulated\n"


def table(*rows: str) -> auto.ErrorModel:
    """A synthetic model: rows 'kind,knob,rtol,atol,t,status,error,steps' (t_simulated 1)."""
    lines = []
    for row in rows:
        kind, knob, rtol, atol, t, status, error, steps = row.split(",")
        lines.append(f"{kind},{knob},{rtol},{atol},{t},0,{status},3,{error},{steps},1")
    return auto.parse_table("# synthetic\n" + HEADER + "\n".join(lines) + "\n")


SYNTHETIC = table(
    "pin,rtol,1e-4,1e-7,30,converged,1e-5,10",
    "pin,rtol,1e-6,1e-9,30,converged,1e-6,20",
    "pin,rtol,1e-6,1e-12,30,converged,2e-7,25",
    "pin,rtol,1e-8,1e-11,30,converged,3e-7,40",  # noisier than a looser setting
    "pin,rtol,1e-8,1e-14,30,converged,1e-10,45",
    "pin,rtol,1e-9,1e-15,30,failed,nan,60",  # never chosen
    "pin,t_decide,1e-8,1e-14,30,converged,1e-11,0",
    "pin,t_decide,1e-8,1e-14,120,converged,0,0",
    "disk_from_rest,rtol,1e-6,1e-9,30,converged,1e-8,50",
    "disk_from_rest,rtol,1e-8,1e-14,30,converged,1e-11,90",
    "disk_from_rest,t_decide,1e-8,1e-14,30,converged,6e-8,0",
    "disk_from_rest,t_decide,1e-8,1e-14,120,converged,1e-10,0",
)


def test_a_setting_is_rated_by_the_worst_error_measured_at_least_as_tight():
    # (1e-6, 1e-9) measured 1e-6, but (1e-8, 1e-11), tighter in both, measured 3e-7 < 1e-6
    assert SYNTHETIC.numerics_error("pin", 1e-6, 1e-9) == pytest.approx(1e-6)
    # the noisy tighter row lifts no looser one above its own, but bounds itself by the max
    assert SYNTHETIC.numerics_error("pin", 1e-8, 1e-11) == pytest.approx(3e-7)
    # an unmeasured setting is bounded by the tightest measured one at least as loose
    assert SYNTHETIC.numerics_error("pin", 1e-7, 1e-10) == pytest.approx(1e-6)
    assert SYNTHETIC.numerics_error("pin", 1e-10, 1e-16) == pytest.approx(1e-10)
    # nothing measured at least as loose in both: unknown, never a guess
    assert SYNTHETIC.numerics_error("pin", 1e-3, 1e-6) is None
    # the horizon: non-increasing in t_decide, unknown below the shortest measured
    assert SYNTHETIC.horizon_error("disk_from_rest", 60.0) == pytest.approx(6e-8)
    assert SYNTHETIC.horizon_error("disk_from_rest", 600.0) == pytest.approx(1e-10)
    assert SYNTHETIC.horizon_error("disk_from_rest", 10.0) is None


def test_the_cheapest_setting_within_the_fraction_of_tol_is_chosen():
    tol = 1.2e-5 / auto.ERROR_FRACTION  # room for (1e-4, 1e-7): 1e-5 plus the horizon's 1e-11
    choice = auto.choose(tol, ["pin"], {}, SYNTHETIC)
    assert (choice.rtol, choice.atol, choice.t_decide) == (1e-4, 1e-7, 30.0)
    assert choice.expected == pytest.approx(1e-5 + 1e-11)
    assert choice.expected <= auto.ERROR_FRACTION * tol and choice.reaches
    # room for 2.5e-7: (1e-6, 1e-12) costs 25 steps/s, less than (1e-8, 1e-14)
    choice = auto.choose(2.5e-7 / auto.ERROR_FRACTION, ["pin"], {}, SYNTHETIC)
    assert (choice.rtol, choice.atol) == (1e-6, 1e-12)
    # a failed setting is never chosen, even where nothing else fits
    choice = auto.choose(1e-12, ["pin"], {}, SYNTHETIC)
    assert (choice.rtol, choice.atol) == (1e-8, 1e-14) and not choice.reaches
    assert "cannot reach find_jump.tol 1e-12" in choice.warning()


def test_the_horizon_follows_the_tol_where_the_kind_needs_it():
    # disk from rest: 30 s is off by 6e-8, so a bound below that takes 120 s
    fraction = auto.ERROR_FRACTION
    assert auto.choose(1e-7 / fraction, ["disk_from_rest"], {}, SYNTHETIC).t_decide == 30.0
    assert auto.choose(1e-8 / fraction, ["disk_from_rest"], {}, SYNTHETIC).t_decide == 120.0
    # the pin's horizon error is 1e-11 at 30 s: it stays while the numerics fit beside it
    assert auto.choose(1e-9 / fraction, ["pin"], {}, SYNTHETIC).t_decide == 30.0


def test_where_the_horizon_alone_misses_the_tol_the_numerics_stay_cheap():
    # a disk whose mu* moves by 8e-7 between 120 s and the longest horizon: no numerics
    # can make up for it, so they are chosen within a tenth of it, not the tightest
    slow = table(
        "disk_from_rest,rtol,1e-4,1e-10,30,converged,5e-8,10",
        "disk_from_rest,rtol,1e-6,1e-12,30,converged,5e-9,30",
        "disk_from_rest,rtol,1e-8,1e-14,30,converged,1e-11,90",
        "disk_from_rest,t_decide,1e-8,1e-14,30,converged,1e-6,0",
        "disk_from_rest,t_decide,1e-8,1e-14,120,converged,8e-7,0",
    )
    choice = auto.choose(1e-8, ["disk_from_rest"], {}, slow)
    assert (choice.rtol, choice.atol, choice.t_decide) == (1e-4, 1e-10, 120.0)
    assert not choice.reaches and choice.expected == pytest.approx(8.5e-7)
    # where the horizon leaves room, the numerics fill what is left of the bound
    choice = auto.choose(2e-6 / auto.ERROR_FRACTION, ["disk_from_rest"], {}, slow)
    assert (choice.rtol, choice.t_decide) == (1e-4, 30.0) and choice.reaches


def test_a_point_of_several_kinds_is_rated_at_the_worst():
    choice = auto.choose(2.5e-7 / auto.ERROR_FRACTION, ["pin", "disk_from_rest"], {}, SYNTHETIC)
    pin = SYNTHETIC.numerics_error("pin", choice.rtol, choice.atol)
    rest = SYNTHETIC.numerics_error("disk_from_rest", choice.rtol, choice.atol)
    assert choice.expected == pytest.approx(max(pin, rest) + 6e-8)
    assert choice.kinds == ("disk_from_rest", "pin")


def test_a_kind_without_measurements_is_not_rated():
    choice = auto.choose(1e-6, ["disk_braked"], {}, SYNTHETIC)
    assert choice.chosen == () and choice.expected is None and choice.reaches
    assert (choice.rtol, choice.atol, choice.t_decide) == (1e-6, 1e-9, 30.0)
    assert "no error model for kind disk_braked" in choice.describe()


def test_given_keys_win_and_are_rated():
    choice = auto.choose(1e-8, ["pin"], {"rtol": 1e-6}, SYNTHETIC)
    assert choice.rtol == 1e-6 and choice.chosen == ("atol", "t_decide")
    # of the measured atol / rtol ratios, the one that reaches furthest; out of reach, the
    # horizon is not lengthened for an error (1e-11) negligible beside the numerics' 2e-7
    assert choice.atol == 1e-12 and choice.t_decide == 30.0
    assert choice.expected == pytest.approx(2e-7 + 1e-11)
    assert not choice.reaches and "rtol 1e-06" in choice.warning()
    given = {"rtol": 1e-6, "atol": 1e-9, "t_decide": 30.0}
    choice = auto.choose(1e-4, ["pin"], given, SYNTHETIC)
    assert choice.chosen == () and (choice.rtol, choice.atol) == (1e-6, 1e-9) and choice.reaches


# --- the package's measured table -------------------------------------------------------

TOLS = [10.0**-k for k in range(3, 11)]
KIND_SETS = [(kind,) for kind in auto.KINDS] + [("disk_from_rest", "stribeck")]


@pytest.mark.parametrize("kinds", KIND_SETS)
def test_a_smaller_tol_never_gives_looser_numerics(kinds):
    choices = [auto.choose(tol, kinds, {}) for tol in TOLS]
    for wide, narrow in zip(choices, choices[1:], strict=False):
        looser = (
            narrow.rtol >= wide.rtol
            and narrow.atol >= wide.atol
            and narrow.t_decide <= wide.t_decide
        )
        same = (narrow.rtol, narrow.atol, narrow.t_decide) == (wide.rtol, wide.atol, wide.t_decide)
        assert same or not looser, (wide.describe(), narrow.describe())
        assert narrow.expected <= wide.expected * (1 + 1e-9)


@pytest.mark.parametrize("kinds", KIND_SETS)
def test_the_expected_error_is_within_the_stated_fraction_of_tol(kinds):
    model = auto.error_model()
    for tol in TOLS:
        choice = auto.choose(tol, kinds, {})
        assert choice.chosen == auto.AUTO_KEYS
        assert choice.reaches == (choice.expected <= auto.ERROR_FRACTION * tol * (1 + 1e-9))
        # recomputed from the table: the numerics' and the horizon's errors, worst kind
        worst = max(
            model.numerics_error(kind, choice.rtol, choice.atol)
            + model.horizon_error(kind, choice.t_decide)
            for kind in kinds
        )
        assert choice.expected == pytest.approx(worst)
        if not choice.reaches:
            assert "cannot reach" in choice.warning()


def test_every_kind_is_measured_and_the_table_names_its_command_and_commit():
    model = auto.error_model()
    assert model.kinds() == set(auto.KINDS)
    generated = [line for line in model.provenance.splitlines() if "generated by:" in line]
    assert generated and ", at commit " in generated[0]
    assert "frictiondisk.studies.error_model" in model.provenance  # its generator
    for kind in auto.KINDS:
        assert model.settings(kind) and model.horizons()


def test_scene_kinds():
    def kinds(**keys):
        return auto.scene_kinds(scene_from_dict(keys))

    assert kinds(scene="pin") == ("pin",)
    assert kinds(scene="disk", params={"phidot0": 1.1}) == ("disk_corotating",)
    assert kinds(scene="disk") == ("disk_from_rest",)
    assert kinds(scene="disk", params={"beta_b": 0.005, "phidot0": 1.1}) == ("disk_braked",)
    assert kinds(scene="pin", contact={"stribeck": {"r": 0.8}}) == ("pin", "stribeck")


# --- in a campaign -----------------------------------------------------------------------


def pin_line(numerics=None, tol=1e-8, **task):
    data = {
        "name": "auto",
        "scene": "pin",
        "find_jump": {"bracket": [0.05, 0.5], "tol": tol, "along": {"params.x_ms": [0.1]}, **task},
    }
    if numerics is not None:
        data["numerics"] = numerics
    return campaign_from_dict(data)


def test_a_campaign_runs_the_numerics_its_tol_chose():
    campaign = pin_line()
    choice = campaign.numerics_choice
    assert choice == auto.choose(1e-8, ["pin"], {})
    num = campaign.points()[0].config.numerics
    assert (num.rtol, num.atol, num.t_decide) == (choice.rtol, choice.atol, choice.t_decide)
    # `auto` written out is the same as not given: same canonical form, same hash
    assert pin_line({"rtol": "auto", "atol": "auto", "t_decide": "auto"}) == campaign
    assert pin_line({"rtol": "auto"}).content_hash() == campaign.content_hash()
    # a looser tol: no tighter numerics
    loose = pin_line(tol=1e-4).base.numerics
    assert loose.rtol >= num.rtol and loose.atol >= num.atol


def test_explicit_numerics_keys_win():
    assert pin_line({"rtol": 1e-7}).base.numerics.rtol == 1e-7
    assert pin_line({"atol": 1e-13}).base.numerics.atol == 1e-13
    assert pin_line({"t_decide": 12.0}).base.numerics.t_decide == 12.0
    fast = pin_line({"preset": "fast"})
    assert (fast.base.numerics.rtol, fast.base.numerics.atol) == (1e-4, 1e-7)
    assert fast.numerics_choice.chosen == ("t_decide",)
    radau = pin_line({"method": "scipy-radau"})
    assert radau.numerics_choice.chosen == () and radau.base.numerics.rtol == 1e-6
    assert "no error model for method 'scipy-radau'" in radau.numerics_choice.describe()
    varied = pin_line(along={"params.x_ms": [0.1], "numerics.rtol": [1e-6, 1e-8]})
    assert varied.numerics_choice.chosen == () and varied.numerics_choice.expected is None


def test_fixed_numerics_that_cannot_reach_the_tol_are_flagged():
    choice = pin_line({"rtol": 1e-6}).numerics_choice
    assert not choice.reaches
    warning = choice.warning()
    assert warning.startswith("numerics cannot reach find_jump.tol 1e-08: expected mu* error")
    assert f"{choice.expected:.2g}" in warning and "rtol 1e-06" in warning
    assert warning.endswith("leave rtol out to let the tol choose them")
    # where no numerics reach the tol (a disk from rest: its horizon), the advice says so
    rest = campaign_from_dict(
        {
            "name": "rest",
            "scene": "disk",
            "find_jump": {"bracket": [0.105, 0.14], "tol": 1e-8, "along": {"params.x_ms": [0.1]}},
        }
    )
    floor = rest.numerics_choice.floor
    assert rest.numerics_choice.warning().endswith(f"loosen find_jump.tol to at least {floor:.2g}")
    assert pin_line({"rtol": 1e-6}, tol=1e-4).numerics_choice.warning() is None


@pytest.mark.parametrize("given", [{}, {"rtol": 1e-6}, {"t_decide": 30.0}])
@pytest.mark.parametrize("kinds", [["pin"], ["disk_from_rest"], ["pin", "disk_braked"]])
def test_the_floor_is_the_smallest_tol_the_numerics_reach(kinds, given):
    """The floor a refusal names (and run --tol-floor runs at) is reached, and a tol a
    few percent below it is not (two significant digits, rounded up)."""
    far_below = auto.choose(1e-300, kinds, given)
    floor = far_below.floor
    assert not far_below.reaches and floor is not None
    assert f"the smallest tol they reach is {floor:.2g}" in far_below.warning()
    assert auto.choose(floor, kinds, given).reaches
    assert not auto.choose(floor * 0.9, kinds, given).reaches
    assert auto.choose(floor * 1e-6, kinds, given).floor == floor  # whatever the tol


def test_a_campaign_varying_a_kind_key_is_rated_at_its_worst_kind():
    data = {
        "name": "brake",
        "scene": "disk",
        "find_jump": {"bracket": [0.1, 0.5], "tol": 1e-6, "along": {"params.beta_b": [0.0, 0.005]}},
    }
    choice = campaign_from_dict(data).numerics_choice
    assert set(choice.kinds) == {"disk_from_rest", "disk_braked"}


def test_a_scene_without_a_tol_keeps_todays_defaults():
    num = scene_from_dict({"scene": "pin", "numerics": {"rtol": "auto", "atol": "auto"}}).numerics
    assert (num.rtol, num.atol, num.t_decide) == (1e-6, 1e-9, 30.0)
    scan = campaign_from_dict({"name": "s", "scene": "pin", "scan": {"mu": [0.1, 0.2]}})
    assert scan.numerics_choice is None and scan.base.numerics.rtol == 1e-6
