"""A fake of frictiondisk.simulation.simulate.simulate for the tests of the engine and of
the tasks' contract with it (tests/test_task_contract.py): deterministic verdicts in
microseconds, no kernel (no numba compile, no runs). `install` puts it in place of the
real one, in this process; tests/fake_cli.py runs the command line with it."""

from __future__ import annotations

import math
import threading
import time

import numpy as np

from frictiondisk.engine import signals
from frictiondisk.simulation.result import SimulationResult, Trajectory


def jump_of(params: dict) -> float:
    """The fake's jump: a pin sticks where mu >= 1.2 x_ms + 0.3 |x0|."""
    return 1.2 * params["x_ms"] + 0.3 * abs(params.get("x0", 0.0))


class FakeSimulate:
    """simulate(config, record=False, dt_out=0.0) with verdicts from `jump_of`: stick on or
    above the jump, stick_slip below, the friction reserve mu - mu*; a recorded run gets a
    three-sample trajectory. Each run sleeps `delay` [s] (the GIL released, as the kernel
    does). After `stop_after` runs a stop is noted (as a signal handler does); a run with
    `fails(params, record)` raises (its worker crashes)."""

    def __init__(self, stop_after: int | None = None, fails=None, delay: float = 0.0):
        self.stop_after, self.fails, self.delay = stop_after, fails, delay
        self.runs = 0
        self.lock = threading.Lock()

    def __call__(self, config, record: bool = False, dt_out: float = 0.0) -> SimulationResult:
        params = config.canonical()["params"]
        with self.lock:
            self.runs += 1
            if self.runs == self.stop_after:
                signals.request_stop(KeyboardInterrupt)
        if self.delay:
            time.sleep(self.delay)
        if self.fails is not None and self.fails(params, record):
            raise RuntimeError("fake worker crash")
        star = jump_of(params)
        sticks = params["mu"] >= star
        return SimulationResult(
            outcome="stick" if sticks else "stick_slip",
            reason="fake verdict",
            R1=0.05,
            t_R1=1.0,
            size=0.05 if sticks else 0.1 + params["mu"],
            a=math.nan if sticks else 0.01,
            n_transitions=2,
            stick_fraction=1.0 if sticks else 0.4,
            t_end=10.0,
            n_steps=100,
            n_rejected=0,
            n_refused=0,
            cycle_converged=not sticks,
            # the kernel time a run claims [s]: the driver cuts batches of a few runs
            # (engine/cluster.py MIN_TASK_S / wall_s), so that a small campaign still
            # spans many jobs and a stop can fall between them
            wall_s=0.1,
            method="fake",
            trajectory=_trajectory() if record else None,
            reserve=params["mu"] - star,
        )


def _trajectory() -> Trajectory:
    t = np.array([0.0, 0.5, 1.0])
    zeros = np.zeros(3)
    return Trajectory(
        t,
        zeros + 0.1,
        zeros,
        zeros,
        zeros,
        None,
        None,
        zeros[:, None],
        zeros[:, None],
        np.array([[0], [1], [1]], np.int8),
    )


def install(monkeypatch, **kwargs) -> FakeSimulate:
    """A FakeSimulate in place of the real simulate (with `monkeypatch`: a pytest
    MonkeyPatch, or anything with its setattr) for the rest of the test; workers run in
    this process (threads), so they see it too."""
    from frictiondisk.simulation import simulate as simulate_module
    from frictiondisk.tasks.trajectory import files as trajectory_files

    fake = FakeSimulate(**kwargs)
    monkeypatch.setattr(simulate_module, "simulate", fake)
    monkeypatch.setattr(trajectory_files, "simulate", fake)
    return fake
