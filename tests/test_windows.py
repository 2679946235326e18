"""The headline is the lowest rising jump that persists, certified with the grid below it
(frictiondisk/tasks/jump_search/jumps.py, docs/model.md section 7): sticking sets in mu with a known
answer, fed to a JumpSearch as a synthetic oracle."""

from __future__ import annotations

import numpy as np
import pytest

from frictiondisk.model.search_settings import OFF, Certify
from frictiondisk.tasks.jump_search.jumps import JumpSearch

TOL = 1e-4


def drive(search, sticks, reserve=None):
    """Answer every pending request: stick where sticks(mu), else stick_slip; returns the
    requests made."""
    made = []
    while not search.done:
        pending = list(search.pending())
        assert pending, "a search that is not done must ask for a run"
        for request in pending:
            made.append(request)
            outcome = "stick" if sticks(request.mu) else "stick_slip"
            signal = None if reserve is None else reserve(request.mu)
            search.feed(request, {"outcome": outcome, "reason": "oracle", "reserve": signal})
    return made


def grid(start, stop, step):
    return tuple(np.round(np.arange(start, stop + step / 2, step), 6))


def window_and_jump(mu):
    """A narrow sticking window [0.144, 0.152] below the main jump at 0.249."""
    return 0.144 <= mu <= 0.152 or mu >= 0.249


def misleading_reserve(mu):
    """A friction reserve that 'explains' the grid without the window (as on the Stribeck
    pin of issue 28: negative at 0.15, yet it sticks)."""
    return mu - 0.249


def test_a_window_the_adaptive_prescan_skips_is_found_below_the_headline():
    mus = grid(0.03, 0.6, 0.01)
    # the adaptive prescan trusts the reserve and skips 0.15; every grid value below the
    # headline is run in the end: the window comes to light, and the lowest rising jump
    # that persists is its rising edge
    search = JumpSearch(mus, TOL, 2, "decide", certify=Certify(), stride=8)
    made = drive(search, window_and_jump, misleading_reserve)
    first_scan = [r.mu for r in made if r.mode == "decide"][: len(range(0, len(mus), 8)) + 1]
    assert 0.15 not in first_scan
    res = search.result()
    assert res.status == "converged", res.reason
    assert res.mu_lo < 0.144 <= res.mu_hi and res.mu_hi - res.mu_lo <= TOL * (1 + 1e-9)
    assert [(w.lo, w.hi) for w in res.windows] == [pytest.approx((0.144, 0.152), abs=TOL)]
    assert not res.windows[0].narrow  # 80 tol wide: wider than the persistence width
    below = res.grid_below
    assert below.decided == below.total == len([m for m in mus if m < 0.144])
    assert below.resolution == pytest.approx(0.01)
    assert res.certification == "certified"


def test_an_isolated_sticking_value_is_a_window_never_the_headline():
    # the disk from rest at x_ms = 0.065: only mu = 0.065 itself sticks below the jump at
    # 0.072 (a grid value of the prescan)
    mus = grid(0.025, 0.395, 0.01)

    def sticks(mu):
        return abs(mu - 0.065) < 1e-12 or mu >= 0.072

    search = JumpSearch(mus, TOL, 2, "decide", certify=Certify(), stride=6)
    made = drive(search, sticks)
    res = search.result()
    assert res.status == "converged", res.reason
    assert res.mu_lo < 0.072 <= res.mu_hi  # the headline is the jump a user means
    narrow = [w for w in res.windows if w.narrow]
    assert len(narrow) == 1 and narrow[0].lo < 0.065 < narrow[0].hi
    assert narrow[0].width < TOL
    # the persistence run just above the isolated value was what showed it
    assert any(0.065 < r.mu <= 0.065 + search.persist * TOL + 1e-12 for r in made)
    assert res.certification == "certified"


def test_a_headline_that_persists_costs_one_run_and_certification_two():
    mus = grid(0.1, 0.2, 0.01)
    plain = JumpSearch(mus, TOL, 2, "decide", certify=OFF)
    certified = JumpSearch(mus, TOL, 2, "decide", certify=Certify(levels=1))
    n_plain = len(drive(plain, lambda mu: mu >= 0.1431))
    n_cert = len(drive(certified, lambda mu: mu >= 0.1431))
    # a dense prescan (11) leaves no grid value below mu* to fill; bisecting 0.01 to tol
    # takes 7 halvings, one run checks persistence, and the ladder re-runs the two ends
    assert n_plain == 11 + 7 + 1
    assert n_cert == n_plain + 2
    assert certified.result().mu_star == plain.result().mu_star
    assert plain.result().certification == "off"
    # 0.10 ... 0.14 lie below the jump: all run by the dense prescan
    assert plain.result().grid_below.decided == plain.result().grid_below.total == 5


def test_no_persisting_jump_gives_the_lowest_one_flagged_uncertain():
    mus = grid(0.1, 0.2, 0.01)
    for certify in (Certify(), OFF):
        search = JumpSearch(mus, TOL, 2, "decide", certify=certify)
        drive(search, lambda mu: abs(mu - 0.15) < 1e-12)
        res = search.result()
        assert res.status == "converged" and res.mu_lo < 0.15 <= res.mu_hi
        assert "no rising jump persists" in res.reason
        assert res.certification == "uncertain"
        assert [w.narrow for w in res.windows] == [True]


ISOLATED = """\
name: isolated_value
scene: disk
params: {x_ms: 0.065}
numerics: {t_decide: 60.0}
find_jump:
  tol: 1.0e-4
  prescan:
    mu: [0.045, 0.055, 0.065, 0.075, 0.085]
  along: {params.x0: [0.0]}
"""


def test_the_disk_s_isolated_sticking_value_is_a_window_and_the_jump_near_0_072_the_headline(
    tmp_path,
):
    # a disk from rest at x_ms = 0.065 sticks at mu = c_s x_ms / F_n = 0.065 exactly (it
    # creeps onto the master axis), not at 0.0653, and for good from about 0.072 on
    from frictiondisk import open_results
    from frictiondisk.engine.runner import run_campaign
    from frictiondisk.tasks.campaign import campaign_from_text

    run_campaign(campaign_from_text(ISOLATED, "<test>"), tmp_path, workers=2, progress=False)
    res = open_results(tmp_path)
    assert str(res.status.values[0]) == "converged", str(res.reason.values[0])
    assert 0.0715 < float(res.mu_lo[0]) < float(res.mu_hi[0]) < 0.0725
    narrow = res.window_narrow.values[0] == 1
    lo, hi = res.window_mu_lo.values[0][narrow], res.window_mu_hi.values[0][narrow]
    assert len(lo) == 1 and lo[0] < 0.065 < hi[0] and hi[0] - lo[0] < TOL
