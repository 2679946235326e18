"""What a Dask worker executes (no I/O): one run, or the rest of one point's bisection.

A bisection's runs are sequential and a decision run takes 1-7 ms, less than one Dask
round trip (3-10 ms), so a find_jump point is shipped whole: the worker advances the
pure `Bisection` to its end and returns it with the runs it made; the driver journals
them. Scan runs (converge mode, 0.1-1 s each) go one per task.
"""

from __future__ import annotations

from typing import Any


def run_scene(canonical: dict[str, Any]) -> dict[str, Any]:
    """Simulate the scene given as `SceneConfig.canonical()`; return `result.summary()`."""
    from frictiondisk.config import scene_from_dict
    from frictiondisk.simulate import simulate

    return simulate(scene_from_dict(canonical)).summary()


def run_bisection(
    bisection, point_canonical: dict[str, Any], horizon_factor: float, campaign_dir: str
):
    """Advance `bisection` (frictiondisk.bisection.Bisection) to its end on this worker.

    A run the campaign's journal already holds is read, not computed (read-only: the
    driver alone writes); a worker that cannot see campaign_dir simply computes.
    Returns (bisection, [(RunRequest, result summary), ...] of the runs computed here)."""
    from frictiondisk.campaign.journal import Journal, run_key
    from frictiondisk.campaign.requests import run_config
    from frictiondisk.config import scene_from_dict
    from frictiondisk.simulate import simulate

    point_config = scene_from_dict(point_canonical)
    made = []
    while not bisection.done:
        for request in bisection.pending():
            if bisection.done:
                break
            config = run_config(point_config, request, horizon_factor)
            result = Journal.peek(campaign_dir, run_key(config))
            if result is None:
                result = simulate(config).summary()
                made.append((request, result))
            bisection.feed(request, result)
    return bisection, made


def warm_up() -> None:
    """Compile (or load from the cache) the kernel for both scenes in this process."""
    from frictiondisk.compile_notice import announce_compile

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
