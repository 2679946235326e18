"""`between: [A, B]` (tasks/jump_search/sides.py): find_jump and trace locate the boundary
between any two motions or classes. The default [not_stick, stick] is the stick jump;
another pair is searched on verdicts alone, a run on neither side is retried and named
where it stops a search, and an unknown name is refused with the allowed ones."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from frictiondisk.engine.runner import run_campaign
from frictiondisk.model.scene import ConfigError
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.jump_search.bisection import Bisection
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.jumps import JumpSearch
from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK, Between
from frictiondisk.tasks.map.motions import outcome_order

TOL = 1e-4
# three motions along mu: stick_slip below 0.12, slide up to 0.2345, creep above
EDGES = (0.12, 0.2345)


def three_motions(request):
    if request.mu < EDGES[0]:
        return "stick_slip"
    return "slide" if request.mu < EDGES[1] else "creep"


def drive(search, outcome_of):
    runs = 0
    while not search.done:
        request = search.pending()[0]
        runs += 1
        search.feed(request, {"outcome": outcome_of(request), "reason": "test"})
    return runs


def test_the_default_is_the_stick_jump():
    assert NOT_STICK_STICK.side("stick") == "stick"
    assert all(NOT_STICK_STICK.is_low(o) for o in ("creep", "stick_slip", "slide"))
    assert NOT_STICK_STICK.side("undetermined") is None
    # every decided outcome has a side of the default, whatever names the verdict adds
    decided = [o for o in outcome_order(()) if o != "undetermined"]
    assert all(NOT_STICK_STICK.side(o) is not None for o in decided)


def test_a_boundary_between_two_motions_is_located_to_tol():
    search = JumpSearch(
        tuple(np.linspace(0.05, 0.3, 11)), TOL, 1, between=Between("slide", "creep")
    )
    drive(search, three_motions)
    res = search.result()
    assert res.status == "converged", res.reason
    assert [j.rising for j in res.jumps] == [True]
    assert res.mu_lo < EDGES[1] <= res.mu_hi and res.mu_hi - res.mu_lo <= TOL * (1 + 1e-9)
    # the stick_slip | slide change below is no boundary of this pair: not bisected
    assert not any(j.mu_lo < EDGES[0] < j.mu_hi for j in res.jumps)


def test_the_boundary_moves_with_the_motions_and_the_sides_swap():
    for edge in (0.15, 0.21):
        search = JumpSearch(
            tuple(np.linspace(0.05, 0.3, 11)), TOL, 1, between=Between("stick_slip", "slide")
        )
        drive(search, lambda r, e=edge: "stick_slip" if r.mu < e else "slide")
        assert search.result().mu_lo < edge <= search.result().mu_hi
    # B below A: a falling boundary
    search = JumpSearch(
        tuple(np.linspace(0.05, 0.3, 11)), TOL, 1, between=Between("slide", "stick_slip")
    )
    drive(search, lambda r: "stick_slip" if r.mu < 0.15 else "slide")
    assert [j.rising for j in search.result().jumps] == [False]


def test_a_third_motion_inside_the_bracket_stops_the_bisection_and_is_named():
    bisection = Bisection(
        (0.05, 0.3), BisectionSettings(TOL, (0.01, 1.0), 1, between=Between("stick_slip", "creep"))
    )
    drive(bisection, three_motions)
    res = bisection.result()
    assert res.status == "failed"
    assert "slide (neither stick_slip nor creep)" in res.reason


@pytest.mark.parametrize("task", ["find_jump", "trace"])
def test_an_unknown_motion_is_refused_with_the_field_and_the_allowed_names(task):
    body = {
        "find_jump": "  bracket: [0.03, 0.4]\n  along: {params.x_ms: [0.1]}\n",
        "trace": "  key: params.x_ms\n  range: [0.05, 0.15]\n  mu: [0.03, 0.3]\n",
    }[task]
    text = f"name: t\nscene: pin\n{task}:\n{body}  between: [not_stick, modulatd]\n"
    with pytest.raises(ConfigError) as info:
        campaign_from_text(text)
    message = str(info.value)
    assert f"{task}.between[1]" in message and "'modulatd'" in message
    assert "allowed: stick, not_stick" in message


def test_overlapping_sides_are_refused():
    text = (
        "name: t\nscene: pin\nfind_jump:\n  bracket: [0.03, 0.4]\n"
        "  along: {params.x_ms: [0.1]}\n  between: [not_stick, slide]\n"
    )
    with pytest.raises(ConfigError, match="share slide: give two disjoint sides"):
        campaign_from_text(text)


def test_the_default_between_keeps_the_campaign_hash():
    text = (
        "name: t\nscene: pin\nfind_jump:\n  bracket: [0.03, 0.4]\n  along: {params.x_ms: [0.1]}\n"
    )
    plain = campaign_from_text(text)
    named = campaign_from_text(text + "  between: [not_stick, stick]\n")
    assert plain.content_hash() == named.content_hash()
    assert "between" not in plain.canonical()["find_jump"]


def test_a_find_jump_between_two_motions_says_where_they_coexist(tmp_path, monkeypatch):
    """Fake verdicts: stick_slip below 1.2 x_ms + 0.3 |x0|, stick above: the boundary
    [stick_slip, stick] depends on the start x0, and results.nc says both are reached
    between the starts' mu*."""
    import sys

    sys.path.insert(0, "tests")
    from fake_simulate import install

    install(monkeypatch)
    text = """\
name: coexist
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-3
  between: [stick_slip, stick]
  along: {params.x_ms: [0.1], params.x0: [0.0, 0.1]}
"""
    run_campaign(campaign_from_text(text), tmp_path, workers=1, progress=False)
    with xr.open_dataset(tmp_path / "results.nc") as ds:
        assert ds.attrs["between"].startswith("[stick_slip, stick]")
        lo, hi = float(ds["coexist_lo"].squeeze()), float(ds["coexist_hi"].squeeze())
        assert "hysteresis" in ds.attrs["coexistence"]
    assert lo == pytest.approx(0.12, abs=1e-3) and hi == pytest.approx(0.15, abs=1e-3)


def test_find_jump_bisects_another_scene_key_with_its_units(tmp_path, monkeypatch):
    """The fake sticks where mu >= 1.2 x_ms: at mu 0.15, stick below x_ms = 0.125 and
    stick_slip above; a find_jump in params.x_ms between [stick, stick_slip] finds it."""
    import sys

    sys.path.insert(0, "tests")
    from fake_simulate import install

    install(monkeypatch)
    text = """\
name: in_xms
scene: pin
find_jump:
  parameter: params.x_ms
  bracket: [0.05, 0.2]
  tol: 1.0e-4
  between: [stick, stick_slip]
  along: {params.mu: [0.15, 0.18]}
"""
    run_campaign(campaign_from_text(text), tmp_path, workers=1, progress=False)
    with (
        xr.open_dataset(tmp_path / "results.nc") as ds,
        xr.open_dataset(tmp_path / "runs.nc") as runs,
    ):
        assert ds["mu_star"].attrs["units"] == "m" and ds.attrs["parameter"] == "params.x_ms"
        star = ds["mu_star"].values
        assert runs["mu"].attrs["units"] == "m"
    assert np.allclose(star, [0.15 / 1.2, 0.18 / 1.2], atol=1e-4)


def test_an_unknown_parameter_is_refused():
    text = (
        "name: t\nscene: pin\nfind_jump:\n  parameter: params.bogus\n  bracket: [0.03, 0.4]\n"
        "  along: {params.x_ms: [0.1]}\n"
    )
    with pytest.raises(ConfigError, match="find_jump.parameter"):
        campaign_from_text(text)


def test_a_trace_between_two_motions_follows_their_boundary(tmp_path, monkeypatch):
    """The fake's stick_slip | stick boundary is the line mu = 1.2 x_ms; traced between the
    two motions (on verdicts alone, no friction reserve) every point lies on it within
    two tol."""
    import sys

    sys.path.insert(0, "tests")
    from fake_simulate import install

    install(monkeypatch)
    text = """\
name: trace_between
scene: pin
trace:
  key: params.x_ms
  range: [0.05, 0.15]
  mu: [0.03, 0.3]
  tol: 1.0e-3
  resolution: 0.25
  first_look: {keys: 2, mu: 8}
  between: [stick_slip, stick]
"""
    run_campaign(campaign_from_text(text), tmp_path, workers=1, progress=False)
    with xr.open_dataset(tmp_path / "results.nc") as ds:
        assert ds.attrs["status"] == "converged", ds.attrs["reason"]
        assert ds.attrs["between"].startswith("[stick_slip, stick]")
        mu, x_ms = ds["mu_star"].values, ds["x_ms"].values
    assert mu.size >= 3
    assert np.all(np.abs(mu - 1.2 * x_ms) <= 2 * 1.0e-3)


SELF_CENTRING_STICK = """\
name: sc_stick
scene: pin
params: {omega_m: 0.8}
numerics: {mode: converge, t_max: 3000.0}
find_jump:
  between: [self_centring, stick]
  bracket: [0.03, 0.13]
  tol: 1.0e-3
  certify: {levels: 0}
  along:
    params.x_ms: [0.05, 0.1]
"""


def test_the_self_centring_stick_boundary_moves_with_the_offset_as_c_s_x_ms_over_f_n(tmp_path):
    """A pin stuck at radius R needs mu F_n >= c_s x_ms + g R and a sliding rest state
    mu F_n < c_s x_ms, both ending at r = 0: the boundary is mu = c_s x_ms / F_n (= x_ms
    with the default c_s / F_n = 1 1/m), and doubling the offset doubles it."""
    campaign = campaign_from_text(SELF_CENTRING_STICK, "<test>")
    run_campaign(campaign, tmp_path, workers=2, progress=False)
    p = campaign.base.params
    with xr.open_dataset(tmp_path / "results.nc") as ds:
        assert list(ds.status.values) == ["converged", "converged"], list(ds.reason.values)
        for x_ms, lo, hi in zip(ds.x_ms.values, ds.mu_lo.values, ds.mu_hi.values, strict=True):
            exact = p.c_s * x_ms / p.F_n
            assert hi - lo <= 1e-3 * (1 + 1e-9)
            assert lo - 1e-9 <= exact <= hi + 1e-9, (x_ms, lo, hi)
        assert list(ds.outcome_lo.values) == ["self_centring"] * 2
        assert list(ds.outcome_hi.values) == ["stick"] * 2
