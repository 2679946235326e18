"""Work units sized by cost and bookkeeping linear in the runs (no kernel: planners alone).

* engine/cluster.py `task_sizing`: a batch holds MIN_TASK_S to MAX_TASK_S of expected kernel
  time, estimated from the mean run time so far;
* the scan and basin planners cut their runs as the sizing asks, in a fixed order, and
  name each new request once (`new_requests`), so the driver's replay after a job costs
  nothing per pending request.
"""

from __future__ import annotations

import pytest

from frictiondisk.engine.cluster import MAX_TASK_S, MIN_TASK_S, task_sizing
from frictiondisk.tasks.basin.planner import BasinPlanner
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.jobs import Sizing
from frictiondisk.tasks.scan.planner import ScanPlanner

SCAN = """\
name: units_scan
scene: pin
scan: {mu: {start: 0.1, stop: 0.2, num: 23}, mode: decide}
"""
BASIN = """\
name: units_basin
scene: pin
basin:
  sample: {params.x0: {uniform: [-0.05, 0.05]}}
  target_se: 0.01
  max_samples: 12
  batch: 6
  seed: 1
  along: {params.mu: [0.12, 0.14]}
"""
STICK = {"outcome": "stick", "reason": "fake", "wall_s": 0.002}


@pytest.mark.parametrize(
    "overhead, mean, expected_s",
    [(0.003, 0.002, MIN_TASK_S), (0.02, 0.002, 0.38), (0.2, 0.002, MAX_TASK_S)],
)
def test_a_batch_holds_the_task_time_in_expected_kernel_time(overhead, mean, expected_s):
    sizing = task_sizing(overhead, mean, worker_threads=2, in_flight=1)
    assert expected_s - mean <= sizing.batch_runs * mean <= expected_s  # within one run
    assert sizing.max_jobs == 3 and sizing.workers == 2
    assert task_sizing(overhead, None, 2, 0).batch_runs == 1  # no run time known yet


def test_the_scan_names_each_run_once_and_cuts_batches_in_point_order():
    planner = ScanPlanner(campaign_from_text(SCAN))
    first = planner.new_requests()
    assert [i for i, _ in first] == list(range(23)) and planner.new_requests() == []
    planner.feed(1, first[1][1], STICK)  # the journal held point 1
    jobs = planner.jobs(Sizing(batch_runs=5, max_jobs=2, workers=2))
    assert [len(job.scenes) for _, job in jobs] == [5, 5]
    in_order = [planner.points[i].config.canonical() for i in (0, 2, 3, 4, 5)]
    assert list(jobs[0][1].scenes) == in_order  # in point order, point 1 skipped
    # near the end a batch is no more than an equal share per worker of what is left:
    # the batches shrink, so the workers end together
    rest = planner.jobs(Sizing(batch_runs=100, max_jobs=4, workers=2))
    assert [len(job.scenes) for _, job in rest] == [6, 3, 2, 1]
    rest += planner.jobs(Sizing(batch_runs=100, max_jobs=4, workers=2))
    assert planner.jobs(Sizing(batch_runs=100, max_jobs=4, workers=2)) == []
    for job_id, job in jobs + rest:
        made = planner.complete(job_id, [STICK] * len(job.scenes))
        assert all(result is STICK for _, _, result in made)
    assert planner.done and planner.progress() == (23, 23)


def test_the_basin_names_each_sample_once_and_the_next_batch_when_it_is_asked_for():
    planner = BasinPlanner(campaign_from_text(BASIN))
    first = planner.new_requests()
    assert [(i, r.index) for i, r in first] == [(i, j) for i in (0, 1) for j in range(6)]
    assert planner.new_requests() == []
    jobs = planner.jobs(Sizing(batch_runs=4, max_jobs=10, workers=2))
    assert [len(job.scenes) for _, job in jobs] == [4, 4, 2, 1, 1]  # shrinking shares
    for job_id, job in jobs:
        outcomes = [{"outcome": "stick_slip" if k % 2 else "stick"} for k in range(len(job.scenes))]
        planner.complete(job_id, outcomes)
    # a fraction near 1/2 with 6 samples is far from target_se: 6 more samples per point
    fresh = planner.new_requests()
    assert sorted((i, r.index) for i, r in fresh) == [(i, j) for i in (0, 1) for j in range(6, 12)]
    assert planner.new_requests() == []
