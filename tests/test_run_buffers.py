"""RunBuffers (simulation/buffers.py): the one run-record type between Python and the step
loop, with every number under a name."""

import math

import numpy as np
import pytest

from frictiondisk.kernel.records import REV_RING, RING
from frictiondisk.simulation.buffers import RUN_STATE, RunBuffers
from frictiondisk.verdict.params import VerdictParams


def test_allocate_sizes_buffers_from_the_kernel_constants():
    run = RunBuffers.allocate(np.arange(6.0), np.ones(2, np.int8), capacity=7)
    assert run.rec_y.shape == (7, 6) and run.rec_m.shape == (7, 2)
    assert run.phases.shape == (RING,) and run.intervals.shape == (RING,)
    assert run.revolutions.shape == (REV_RING,)
    assert run.state.dtype == RUN_STATE and run.thresholds == VerdictParams()
    assert run.status == 0 and math.isnan(run.t_end)
    assert run.steps == run.refused == run.recorded == 0 and not run.truncated
    assert run.recorded_rows()[1].shape == (0, 6)


def test_the_records_are_views_that_the_caller_sees_written():
    run = RunBuffers.allocate(np.zeros(4), np.zeros(1, np.int8))
    run.motion["r1"] = 0.25
    run.verdict["budget_spent"] = True
    assert run.state["motion"]["r1"] == 0.25 and run.budget_spent


def test_a_record_without_the_kernel_inputs_cannot_run():
    run = RunBuffers.allocate(np.zeros(4), np.zeros(1, np.int8), revolutions=False)
    assert run.revolutions is None and math.isnan(run.slip_total)
    run.set_counters(steps=3, rejected=0, refused=1)
    run.finish(2, 1.5, np.ones(4))
    assert (run.steps, run.refused, run.status, run.t_end) == (3, 1, 2, 1.5)
    with pytest.raises(ValueError):
        run.run()
