"""What a Dask worker executes (no I/O): a batch of independent runs, or a chain of one
point's sequential runs.

Independent runs (a prescan, the rounds of several jumps, the k - 1 points of a
multisection round) go out as batches (`run_batch`), sized by the driver so that a task
lasts long enough to amortize the scheduler's cost per task. Where a point's next step
fits in one task (a single run, or a few short ones), its state machine goes to one
worker (`run_bisection`), which advances it step after step, without a round trip each,
until it ends or has used its time budget; the driver journals the runs it made.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from typing import Any


@dataclasses.dataclass(frozen=True)
class Sealed:
    """A task's function and arguments as one object, which Dask ships as it is. Dask walks
    the nested lists and dicts of a task's arguments looking for futures (there are none
    here); for a batch of scenes that cost the driver about 0.5 ms per task."""

    function: Callable[..., Any]
    args: tuple


def run_sealed(sealed: Sealed) -> Any:
    """Execute a `Sealed` task."""
    return sealed.function(*sealed.args)


def noop() -> None:
    """An empty task: the driver times its round trip (the scheduler's cost per task)."""


def run_batch(canonicals: list[dict[str, Any]]) -> tuple[list[dict[str, Any]], float]:
    """Simulate each scene (`SceneConfig.canonical()`), in order.

    Returns (result summaries, wall time of the whole batch [s])."""
    t0 = time.perf_counter()
    results = [run_scene(canonical) for canonical in canonicals]
    return results, time.perf_counter() - t0


def run_scene(canonical: dict[str, Any]) -> dict[str, Any]:
    """Simulate the scene given as `SceneConfig.canonical()`; return `result.summary()`."""
    from frictiondisk.model.scene import scene_from_dict
    from frictiondisk.simulation.simulate import simulate

    return simulate(scene_from_dict(canonical)).summary()


def run_bisection(
    bisection,
    point_canonical: dict[str, Any],
    horizon_factor: float,
    campaign_dir: str,
    budget_s: float | None = None,
):
    """Advance `bisection` (a Bisection or JumpSearch) on this worker, one step after the
    other: to its end, or, with `budget_s`, until it has run for budget_s seconds.

    A run the campaign's journal already holds is read, not computed (read-only: the
    driver alone writes); a worker that cannot see campaign_dir simply computes.
    Returns (bisection, [(RunRequest, result summary), ...] of the runs computed here)."""
    from frictiondisk.model.scene import scene_from_dict
    from frictiondisk.model.search_settings import OFF
    from frictiondisk.search.requests import run_config
    from frictiondisk.simulation.simulate import simulate
    from frictiondisk.store.journal import Journal, run_key

    point_config = scene_from_dict(point_canonical)
    certify = getattr(bisection, "certify", OFF)  # the numerics of certification runs
    made = []
    t0 = time.perf_counter()
    while not bisection.done and bisection.pending():
        if budget_s is not None and time.perf_counter() - t0 >= budget_s:
            break
        # the first pending run first, as the driver feeds the runs of a batch
        # (plan.JumpPlanner.feed): the same search whatever worker or task runs it
        request = bisection.pending()[0]
        config = run_config(point_config, request, horizon_factor, certify)
        result = Journal.peek(campaign_dir, run_key(config))
        if result is None:
            result = simulate(config).summary()
            made.append((request, result))
        bisection.feed(request, result)
    return bisection, made


def run_recorded(canonical: dict[str, Any], dt_out: float):
    """Simulate the scene with its trajectory recorded every dt_out [s] (a trajectory
    campaign's one run); returns the SimulationResult."""
    from frictiondisk.model.scene import scene_from_dict
    from frictiondisk.simulation.simulate import simulate

    return simulate(scene_from_dict(canonical), record=True, dt_out=dt_out)


def warm_up() -> None:
    """Compile (or load from the cache) the kernel for both scenes in this process."""
    from frictiondisk.simulation.compile_notice import announce_compile

    announce_compile()
    for scene in ("pin", "disk"):
        run_scene(
            {
                "scene": scene,
                "contact": {"points": 2} if scene == "disk" else {},
                "numerics": {"t_decide": 0.5},
            }
        )


def run_samples(canonicals: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Simulate each scene (a basin job: sampled initial states); their summaries in order."""
    return [run_scene(canonical) for canonical in canonicals]
