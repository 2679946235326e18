"""Work units below a point (tasks/find_jump/planner.py): however the runs are cut into tasks
(batch size, chains, workers) and whatever order the tasks come back in, the planner
reaches the same results. Synthetic outcomes, no simulation."""

import random

import pytest

from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.find_jump.planner import JumpPlanner
from frictiondisk.tasks.jobs import RunScenes, Sizing
from frictiondisk.tasks.jump_search.prescan import default_stride

PRESCAN = """\
name: units
scene: pin
find_jump:
  tol: 1.0e-6
  split: {split}
  prescan: {{mu: {{start: 0.05, stop: 0.4, num: 8}}}}
  along: {{params.x_ms: {{start: 0.02, stop: 0.2, num: 4}}}}
"""
WARM = """\
name: units
scene: pin
find_jump:
  bracket: [0.05, 0.4]
  tol: 1.0e-6
  split: {split}
  along: {{params.x_ms: {{start: 0.02, stop: 0.2, num: 5}}}}
"""


def outcome(mu: float, x_ms: float) -> str:
    """Stick above 0.1 + x_ms, and in a narrow window below it (two jumps and a third)."""
    window = 0.06 + x_ms <= mu <= 0.075 + x_ms
    return "stick" if mu >= 0.1 + x_ms or window else "stick_slip"


def fake(canonical):
    params = canonical["params"]
    return {"outcome": outcome(params["mu"], params["x_ms"]), "reason": "oracle", "wall_s": 0}


def execute(job):
    """What a worker would return, with outcomes from the oracle."""
    if isinstance(job, RunScenes):
        return [fake(c) for c in job.scenes]
    bis, point, budget = job.search, job.scene_of.point, job.budget_s
    made = []
    while not bis.done:
        request = bis.pending()[0]  # the first pending run first, as worker.run_search
        x_ms = point["params"]["x_ms"]
        result = {"outcome": outcome(request.mu, x_ms), "reason": "oracle", "wall_s": 0}
        bis.feed(request, result)
        made.append((request, result))
        if budget is not None and len(made) >= 3:  # a small budget, in runs
            break
    return bis, made


def run_planner(text: str, sizing: Sizing, rng: random.Random):
    planner = JumpPlanner(campaign_from_text(text, "<test>"))
    in_flight = []
    journaled = []
    while not planner.done:
        planner.requests()
        in_flight += planner.jobs(sizing)
        assert in_flight, "stalled"
        job, work = in_flight.pop(rng.randrange(len(in_flight)))
        journaled += planner.complete(job, execute(work))
    results = [planner.results[i] for i in range(len(planner.points))]
    return results, sorted((i, r.mu, r.level, r.strict) for i, r, _ in journaled)


@pytest.mark.parametrize("template", [PRESCAN, WARM])
@pytest.mark.parametrize("split", [2, 4])
def test_results_do_not_depend_on_how_runs_are_cut_or_their_order(template, split):
    text = template.format(split=split)
    sizings = [
        Sizing(),  # one run per task, no chains
        Sizing(batch_runs=5, chain_s=1.0, max_jobs=2, workers=2),
        Sizing(batch_runs=64, chain_s=1.0, max_jobs=None, workers=16),
        Sizing(batch_runs=1, chain_s=None, max_jobs=1, workers=1),
    ]
    reference, runs = run_planner(text, sizings[0], random.Random(0))
    assert all(r.status == "converged" for r in reference), [r.reason for r in reference]
    assert len(runs) == len(set(runs))  # no run computed twice
    for k, sizing in enumerate(sizings[1:]):
        results, again = run_planner(text, sizing, random.Random(k + 1))
        assert results == reference
        assert again == runs


def test_a_row_starts_its_ends_cold_and_every_inner_point_warm():
    """Coarse to fine: the ends start cold, every inner point interpolates its bracket
    from the two that bound it, which saves search runs (results.nc warm_start)."""
    planner = JumpPlanner(campaign_from_text(WARM.format(split=2), "<test>"))
    while not planner.done:
        for job, work in planner.jobs(Sizing(chain_s=1.0)):
            planner.complete(job, execute(work))
    assert [planner.warm[i] for i in range(5)] == [False, True, True, True, False]
    assert all(r.status == "converged" for r in planner.results.values())
    assert planner.runs_saved() > 0


def test_a_prescan_goes_out_at_once_in_batches_across_workers():
    planner = JumpPlanner(campaign_from_text(PRESCAN.format(split=2), "<test>"))
    jobs = planner.jobs(Sizing(batch_runs=3, chain_s=1.0, workers=4))
    sizes = [len(work.scenes) for _, work in jobs if isinstance(work, RunScenes)]
    stride = default_stride(8, "decide", "corotation")  # the adaptive prescan's coarse grid
    coarse = len(set(range(0, 8, stride)) | {7})
    assert stride > 1 and sum(sizes) == 4 * coarse  # every coarse value of every point, once
    assert max(sizes) == 3
    # a window of 2 tasks hands out 2 tasks; the rest follow as tasks come back
    planner = JumpPlanner(campaign_from_text(PRESCAN.format(split=2), "<test>"))
    assert len(planner.jobs(Sizing(batch_runs=3, max_jobs=2, workers=4))) == 2


class NeedlessSecond:
    """A search that wants runs a and b at once, and for which a's result makes b needless
    (as a sticking grid value below a headline makes that headline's bisection needless)."""

    def __init__(self, a, b):
        self.a, self.b, self.fed = a, b, []

    @property
    def done(self):
        return self.a in self.fed

    def pending(self):
        return [r for r in (self.a, self.b) if r not in self.fed] if not self.done else []

    def feed(self, request, result):
        assert request in self.pending()
        self.fed.append(request)

    def result(self):
        return tuple(self.fed)


@pytest.mark.parametrize("first_back", ["a", "b"])
def test_a_search_takes_its_results_in_its_own_order_not_in_arrival_order(first_back):
    # with 16 workers b can come back before a; fed on arrival, the search would count b,
    # and with one worker it never runs: a campaign's runs then depended on timing
    planner = JumpPlanner(campaign_from_text(PRESCAN.format(split=2), "<test>"))
    a, b = object(), object()
    planner.bisections = {0: NeedlessSecond(a, b)}
    planner.points = planner.points[:1]
    order = [a, b] if first_back == "a" else [b, a]
    for request in order:
        planner.feed(0, request, {"outcome": "stick"})
    assert planner.results[0] == (a,)
    assert 0 not in planner.arrived
