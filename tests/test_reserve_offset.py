"""The friction reserve's offset at the jump, learned from a finished point
(tasks/jump_search/reserve_offset.py, issue 48), and a deferred run's reserve as the aim of
the next probe (Bisection._aim_past). Synthetic oracles, no simulation: the pin line at
tol 1e-8, where contact compliance puts the reserve's zero 2.6e-6 x mu* above the jump
(46 tol at x_ms = 0.14)."""

import math

from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.find_jump.planner import JumpPlanner
from frictiondisk.tasks.jobs import RunScenes, Sizing
from frictiondisk.tasks.jump_search.bisection import Bisection
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.expanding import Expanding
from frictiondisk.tasks.jump_search.reserve_offset import learned_offset
from frictiondisk.tasks.jump_search.runs import BisectionResult, RunRecord, RunRequest

TOL = 1e-8
SLOPE = 1.26723443  # mu* = SLOPE x_ms (the pin line's reference)
OFFSET = -2.6e-6  # the reserve at the jump per unit mu
LINE = """\
name: offset
scene: pin
find_jump:
  bracket: [0.05, 0.5]
  tol: 1.0e-8
  along: {params.x_ms: {start: 0.06, stop: 0.14, num: 5}}
"""


def line_run(mu: float, x_ms: float) -> dict:
    """Stick at and above SLOPE x_ms; the reserve is mu less its zero, OFFSET x mu* above."""
    mu_star = SLOPE * x_ms
    outcome = "stick" if mu >= mu_star else "stick_slip"
    return {"outcome": outcome, "reserve": mu - mu_star * (1 - OFFSET), "reason": "oracle"}


def execute(job):
    if isinstance(job, RunScenes):
        return [line_run(c["params"]["mu"], c["params"]["x_ms"]) for c in job.scenes]
    bis, made = job.search, []
    while not bis.done:
        request = bis.pending()[0]
        result = line_run(request.mu, job.scene_of.point["params"]["x_ms"])
        bis.feed(request, result)
        made.append((request, result))
    return bis, made


def run_line():
    planner = JumpPlanner(campaign_from_text(LINE, "<test>"))
    first_done = {}  # point -> whether the first point was done when it started
    while not planner.done:
        for job, work in planner.jobs(Sizing(chain_s=1.0, workers=2)):
            for i in planner.bisections:
                first_done.setdefault(i, 0 in planner.results)
            planner.complete(job, execute(work))
    return planner, first_done


def test_the_far_end_of_a_line_starts_after_the_first_and_aims_at_the_jump():
    """Without the offset the far end's probes aim 46 tol above the jump and walk back;
    with it, learned from x_ms = 0.06, they aim at the jump."""
    planner, first_done = run_line()
    assert first_done == {0: False, 1: True, 2: True, 3: True, 4: True}
    results = [planner.results[i] for i in range(5)]
    for x_ms, res in zip((0.06, 0.08, 0.1, 0.12, 0.14), results, strict=True):
        assert res.status == "converged" and res.mu_lo < SLOPE * x_ms <= res.mu_hi
    assert planner.bisections[0].reserve_offset == 0.0
    # learned to within the first point's bracket: tol / 2 in 2.6e-6 x mu*, 2.5 %
    assert math.isclose(planner.bisections[4].reserve_offset, OFFSET, rel_tol=0.05)
    cold = [len(res.runs) for res in (results[0], results[4])]
    assert cold[1] < cold[0], cold


def result(mu_lo, mu_hi, reserve_hi, status="converged"):
    runs = (
        RunRecord(RunRequest(mu_lo), {"outcome": "stick_slip", "reserve": reserve_hi - TOL}),
        RunRecord(RunRequest(mu_hi), {"outcome": "stick", "reserve": reserve_hi}),
    )
    return BisectionResult(status, "", mu_lo, mu_hi, runs, ())


def test_the_offset_is_the_jump_less_the_reserves_zero_per_unit_mu():
    # the stick end at 0.1 + tol reads -4 tol: its zero lies 4.5 tol above mu*
    found = learned_offset(result(0.1, 0.1 + TOL, -4 * TOL), TOL)
    assert math.isclose(found, -4.5 * TOL / (0.1 + 0.5 * TOL), rel_tol=1e-6)


def test_an_offset_under_tol_or_a_failed_point_teaches_nothing():
    assert learned_offset(result(0.1, 0.1 + TOL, 0.2 * TOL), TOL) == 0.0
    assert learned_offset(result(0.1, 0.1 + TOL, -4 * TOL, "failed"), TOL) == 0.0
    assert learned_offset(None, TOL) == 0.0


def test_a_deferred_runs_reserve_aims_the_next_probe_at_the_jump():
    """The ends' secant lands 150 tol below mu*, in a band no horizon decides (the pin's
    x_ms = 0.14). The undetermined run there reads -150 tol: the next probe goes half a
    tol past the jump, not 8, 72, ... tol from the band; without that reading, the steps
    are geometric and cost more."""
    mu_star, far_zero = 0.1774128219, 0.1774128219 - 150 * TOL
    band = (far_zero - 20 * TOL, far_zero + 20 * TOL)

    def run(request, read_undetermined=True):
        mu = request.mu
        near = abs(mu - mu_star) < 1e-5  # near the jump the reserve is mu - mu*
        reserve = mu - mu_star if near else mu - far_zero  # far runs point at far_zero
        if band[0] <= mu <= band[1]:
            return {"outcome": "undetermined", "reserve": reserve if read_undetermined else None}
        return {"outcome": "stick" if mu >= mu_star else "stick_slip", "reserve": reserve}

    counts = []
    for read in (True, False):
        bis = Bisection((mu_star - 1e-4, mu_star + 1e-3), BisectionSettings(TOL, (1e-6, 10.0), 2,
                        expanding=Expanding(defer=True)))  # fmt: skip
        while not bis.done:
            request = bis.pending()[0]
            bis.feed(request, run(request, read))
        found = bis.result()
        assert found.status == "converged" and found.mu_lo < mu_star <= found.mu_hi
        assert not [r for r in found.runs if r.request.level and band[0] <= r.request.mu]
        counts.append(len(found.runs))
    assert counts[0] <= 5 and counts[0] < counts[1], counts
