"""KernelRun (kernel/record.py): the one run-record type between Python and the kernel."""

import inspect
import math

import numpy as np
import pytest

from frictiondisk.kernel import driver
from frictiondisk.kernel import monitor as mon
from frictiondisk.kernel.record import KernelRun


def test_args_follow_the_positional_order_of_driver_run():
    run_fn = getattr(driver.run, "py_func", driver.run)  # plain function under NUMBA_DISABLE_JIT
    names = list(inspect.signature(run_fn).parameters)
    run = KernelRun.allocate(np.zeros(6), np.zeros(1, np.int8), 5, np.zeros(3), np.zeros((1, 3)))
    assert len(run.args()) == len(names)
    for name, arr in zip(names, run.args(), strict=True):
        assert arr is getattr(run, name), name


def test_allocate_sizes_buffers_from_the_kernel_constants():
    run = KernelRun.allocate(np.arange(6.0), np.ones(2, np.int8), capacity=7)
    assert run.rec_y.shape == (7, 6) and run.rec_m.shape == (7, 2)
    assert run.mf.shape == (mon.N_MF,) and run.mi.shape == (mon.N_MI,)
    assert run.ring_all.shape == (mon.RING, mon.N_RA) and run.ring_any.shape == (mon.RING, 2)
    assert run.rv.shape == (mon.REV_RING, mon.N_RV) and run.iopt.shape == (driver.N_IOPT,)
    assert run.status == 0 and math.isnan(run.t_end)
    assert run.steps == run.refused == run.recorded == 0 and not run.truncated
    assert run.recorded_rows()[1].shape == (0, 6)


def test_a_record_without_the_kernel_inputs_cannot_run():
    run = KernelRun.allocate(np.zeros(4), np.zeros(1, np.int8), revolutions=False)
    assert run.rv is None and math.isnan(run.slip_total)
    run.set_counters(steps=3, rejected=0, refused=1)
    run.finish(2, 1.5, np.ones(4))
    assert (run.steps, run.refused, run.status, run.t_end) == (3, 1, 2, 1.5)
    with pytest.raises(ValueError):
        run.run()
