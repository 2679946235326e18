"""Every jump of a point: prescan, then bisect each change (tasks/jump_search/jumps.py), and the
find_jump `prescan` end to end."""

import math

import numpy as np
import pytest
import xarray as xr
from conftest import coulomb_mu_star

from frictiondisk.engine.runner import run_campaign
from frictiondisk.model.search_settings import OFF, Certify
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.jump_search.bisection import RunRequest
from frictiondisk.tasks.jump_search.jumps import JumpSearch


def drive(search, outcome_of):
    """Answer every pending request with outcome_of(request) until done; returns the runs."""
    made = []
    while not search.done:
        for request in search.pending():
            outcome = outcome_of(request)
            made.append(request)
            search.feed(request, {"outcome": outcome, "reason": "test"})
    return made


def window(lo, hi):
    """Sticking set [lo, hi] in mu: stick inside, stick_slip outside."""
    return lambda r: "stick" if lo <= r.mu <= hi else "stick_slip"


def test_a_sticking_window_gives_a_rising_and_a_falling_jump():
    search = JumpSearch(tuple(np.linspace(0.05, 0.3, 26)), 1e-4, 2)
    drive(search, window(0.12345, 0.16789))
    res = search.result()
    assert res.status == "converged", res.reason
    assert [j.rising for j in res.jumps] == [True, False]
    rise, fall = res.jumps
    assert rise.mu_lo < 0.12345 <= rise.mu_hi and rise.width <= 1e-4 * (1 + 1e-9)
    assert fall.mu_lo <= 0.16789 < fall.mu_hi and fall.width <= 1e-4 * (1 + 1e-9)
    # the primary jump (the one single-jump code sees) is the rising one, and it is not
    # reported as monotone: a second jump exists
    assert (res.mu_lo, res.mu_hi) == (rise.mu_lo, rise.mu_hi)
    assert not res.monotone
    assert "rising at" in res.reason and "falling at" in res.reason


def test_a_single_rising_jump_is_monotone_and_its_ends_are_not_run_twice():
    mus = tuple(np.linspace(0.1, 0.2, 11))
    search = JumpSearch(mus, 1e-4, 2)
    made = drive(search, window(0.1431, 10.0))
    res = search.result()
    assert res.monotone and len(res.jumps) == 1
    assert res.mu_lo < 0.1431 <= res.mu_hi
    # prescan (11) + halvings of a 0.01 bracket to 1e-4 (7) + one persistence run above
    # the jump (docs/model.md section 7), no end run repeated
    assert len(made) == 11 + math.ceil(math.log2(0.01 / 1e-4)) + 1
    assert len(made) == len(set(made)) == len(res.runs)


def test_prescan_runs_use_their_own_mode_and_bisection_runs_the_points():
    search = JumpSearch((0.1, 0.2), 1e-2, 0, scan_mode="converge")
    made = drive(search, window(0.15, 1.0))
    assert {r.mode for r in made[:2]} == {"converge"}
    assert {r.mode for r in made[2:]} == {None}


def test_undetermined_prescan_values_are_retried_then_skipped_and_reported():
    def outcome(r):
        if math.isclose(r.mu, 0.15):
            return "undetermined"
        return "stick" if r.mu > 0.17 else "stick_slip"

    search = JumpSearch((0.1, 0.15, 0.2), 1e-3, 1, certify=Certify(levels=1))
    made = drive(search, outcome)
    assert RunRequest(0.15, 1) in made  # retried once with a longer horizon
    res = search.result()
    # the jump is still bisected between the determined neighbours, and the gap it leaves
    # below the headline makes the point uncertain, not failed (docs/model.md section 7)
    assert res.status == "converged"
    assert "prescan undetermined at mu = 0.15" in res.reason
    assert len(res.jumps) == 1 and res.jumps[0].mu_lo < 0.17 <= res.jumps[0].mu_hi
    assert res.grid_below.decided == 1 < res.grid_below.total == 2
    assert res.certification == "uncertain"


def drive_one_by_one(search, outcome_of):
    """As `drive`, one pending request at a time (a retry can withdraw the others)."""
    while not search.done:
        request = next(iter(search.pending()))
        search.feed(request, {"outcome": outcome_of(request), "reason": "test"})


def _bands(*bands):
    """Outcome by mu: bands of (lo, outcome), each up to the next lo."""

    def outcome(r):
        found = "stick_slip"
        for lo, what in bands:
            if r.mu >= lo - 1e-12:
                found = what
        return found

    return outcome


def test_a_change_that_fails_above_the_headline_leaves_the_headline_standing():
    """The lowest rising jump is bisected and certified; the falling change above it lies
    in a band undecided over 300 tol and fails. It cannot be a lower rising jump, so the
    point is converged on its headline and tells the failure in its reason."""
    mus = tuple(np.round(np.linspace(0.10, 0.30, 21), 10))
    outcome = _bands((0.1523, "stick"), (0.22, "undetermined"), (0.25, "stick_slip"))
    search = JumpSearch(mus, 1e-4, 1, certify=Certify(levels=1))
    drive_one_by_one(search, outcome)
    res = search.result()
    assert res.status == "converged", res.reason
    assert res.mu_lo < 0.1523 <= res.mu_hi
    assert "above mu*, a change in [0.21, 0.25] failed" in res.reason
    assert res.certification == "certified"
    assert any(j.status != "converged" for j in res.jumps)


def test_a_change_that_fails_below_the_headline_fails_the_point():
    """The same undecided band below the only rising jump that converged: it may hide a
    lower one, so there is no headline to certify."""
    mus = tuple(np.round(np.linspace(0.10, 0.30, 21), 10))
    outcome = _bands(
        (0.12, "undetermined"), (0.16, "stick"), (0.1823, "stick_slip"), (0.2541, "stick")
    )
    search = JumpSearch(mus, 1e-4, 1, certify=Certify(levels=1))
    drive_one_by_one(search, outcome)
    res = search.result()
    assert res.status == "failed", res.reason
    assert res.certification == "failed"


def test_a_grid_that_sticks_everywhere_fails_with_the_reason():
    search = JumpSearch((0.1, 0.2, 0.3), 1e-3, 0)
    drive(search, lambda r: "stick")
    res = search.result()
    assert res.status == "failed" and res.jumps == ()
    assert "every prescan value" in res.reason and "gave stick" in res.reason
    assert math.isnan(res.mu_star)


@pytest.mark.parametrize("certify", [Certify(levels=1), OFF])
def test_a_grid_on_which_nothing_sticks_is_the_answer_no_jump(certify):
    """No jump, every value decided not stick: an answer (mu* above the grid), certified
    only on the whole grid; one undecided value leaves it uncertain, never failed."""
    mus = tuple(np.round(np.linspace(0.10, 0.30, 21), 10))
    search = JumpSearch(mus, 1e-4, 1, certify=certify, stride=5)
    drive(search, lambda r: "stick_slip")
    res = search.result()
    assert res.status == "no_jump" and res.jumps == () and math.isnan(res.mu_star)
    assert res.grid_below.decided == res.grid_below.total == len(mus)
    assert res.certification == ("certified" if certify.enabled else "off")
    assert "no jump: no value from mu = 0.1 to 0.3 sticks" in res.reason
    # one grid value the coarse prescan skipped stays undecided after every retry
    search = JumpSearch(mus, 1e-4, 1, certify=certify, stride=5)
    drive(search, lambda r: "undetermined" if abs(r.mu - 0.22) < 1e-9 else "stick_slip")
    res = search.result()
    assert res.status == "no_jump" and res.grid_below.decided == len(mus) - 1
    assert res.certification == ("uncertain" if certify.enabled else "off")


def test_bad_prescan_values_are_refused():
    with pytest.raises(ValueError, match="at least 2 distinct"):
        JumpSearch((0.1, 0.1), 1e-3, 0)


PRESCAN_LINE = """\
name: prescan_line
scene: pin
params: {x0: 0.0}
numerics: {t_decide: 30.0}
find_jump:
  tol: 1.0e-4
  prescan: {mu: {start: 0.08, stop: 0.16, num: 9}}
  along:
    params.x_ms: [0.1]
"""


def test_prescan_campaign_finds_the_jump_of_the_oracle_and_writes_every_jump(tmp_path):
    """Pin, x_ms = 0.1 m: the Coulomb oracle mu* = c_s x_ms + g R1 lies in the bracket of
    the rising jump from the limit cycle to sticking; results.nc lists every jump."""
    run_campaign(campaign_from_text(PRESCAN_LINE), tmp_path / "c", 1, None, False, False)
    res = xr.open_dataset(tmp_path / "c" / "results.nc").load()
    runs = xr.open_dataset(tmp_path / "c" / "runs.nc").load()
    n = int(res["n_jumps"].values[0])
    assert n >= 1
    lo = res["jump_mu_lo"].values[0, :n]
    hi = res["jump_mu_hi"].values[0, :n]
    rising = res["jump_rising"].values[0, :n]
    assert np.all(hi - lo <= 1e-4 * (1 + 1e-9))
    # the limit-cycle -> sticking jump: the last rising jump, where R1 decides
    last = np.flatnonzero(rising == 1)[-1]
    k = np.flatnonzero((runs["mu"].values == hi[last]) & (runs["outcome"].values == "stick"))[0]
    oracle = coulomb_mu_star(float(runs["R1"].values[k]))
    assert lo[last] - 2e-5 < oracle <= hi[last] + 2e-5
    assert res["scan_outcome"].shape == (1, 9)
    assert set(runs["mode"].values) == {"decide"}
    assert res.attrs["prescan_mode"] == "decide"
