"""What a Dask worker executes (no I/O but reading the journal): the jobs planners hand out
(frictiondisk.tasks.jobs), each by its own function.

Independent runs (a prescan, the rounds of several jumps, the k - 1 points of a
multisection round) go out as batches (`RunScenes`), sized by the driver so that a task
lasts long enough to amortize the scheduler's cost per task. Where a point's next step
fits in one task (a single run, or a few short ones), its search goes to one worker
(`RunSearch`), which advances it step after step, without a round trip each, until it
ends or has used its time budget; the driver journals the runs it made.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from typing import Any

from frictiondisk.tasks.jobs import RunRecorded, RunScenes, RunSearch


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


def run_job(job, campaign_dir: str) -> Any:
    """Execute one job of a planner (frictiondisk.tasks.jobs); `campaign_dir`: where a
    RunSearch may read the runs its campaign's journal already holds."""
    if isinstance(job, RunScenes):
        return [run_scene(scene) for scene in job.scenes]
    if isinstance(job, RunSearch):
        return run_search(job.search, job.scene_of, campaign_dir, job.budget_s)
    if isinstance(job, RunRecorded):
        return run_recorded(job.scene, job.dt_out)
    raise TypeError(f"not a job: {job!r}")


def run_scene(canonical: dict[str, Any]) -> dict[str, Any]:
    """Simulate the scene given as `SceneConfig.canonical()`; return `result.summary()`."""
    from frictiondisk.model.scene import scene_from_dict
    from frictiondisk.simulation.simulate import simulate

    return simulate(scene_from_dict(canonical)).summary()


def run_search(search, scene_of, campaign_dir: str, budget_s: float | None = None):
    """Advance `search` on this worker, one step after the other: to its end, or, with
    `budget_s`, until it has run for budget_s seconds. `scene_of(request)` is the scene of
    a requested run.

    A run the campaign's journal already holds is read, not computed (read-only: the
    driver alone writes); a worker that cannot see campaign_dir simply computes.
    Returns (search, [(request, result summary), ...] of the runs computed here)."""
    from frictiondisk.simulation.simulate import simulate
    from frictiondisk.store.journal import Journal
    from frictiondisk.store.journal_entry import run_key

    made = []
    t0 = time.perf_counter()
    while not search.done and search.pending():
        if budget_s is not None and time.perf_counter() - t0 >= budget_s:
            break
        # the first pending run first, as the driver feeds the runs of a batch
        # (tasks/in_order.py): the same search whatever worker or task runs it
        request = search.pending()[0]
        config = scene_of(request)
        result = Journal.peek(campaign_dir, run_key(config))
        if result is None:
            result = simulate(config).summary()
            made.append((request, result))
        search.feed(request, result)
    return search, made


def run_bisection(
    search,
    point_canonical: dict[str, Any],
    horizon_factor: float,
    campaign_dir: str,
    budget_s: float | None = None,
):
    """`run_search` of a jump search (a Bisection, CertifiedBisection or JumpSearch) at the
    point whose scene is `point_canonical`, its runs' scenes by tasks.jump_search.requests
    (certified at the search's own `certify`, if it has one)."""
    from frictiondisk.model.search_settings import OFF
    from frictiondisk.tasks.jump_search.requests import PointScenes

    certify = getattr(search, "certify", OFF)  # the numerics of certification runs
    scenes = PointScenes(point_canonical, horizon_factor, certify)
    return run_search(search, scenes, campaign_dir, budget_s)


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
