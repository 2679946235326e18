"""What a Dask worker executes: one run from its canonical scene dict (no I/O)."""

from __future__ import annotations

from typing import Any


def run_scene(canonical: dict[str, Any]) -> dict[str, Any]:
    """Simulate the scene given as `SceneConfig.canonical()`; return `result.summary()`."""
    from frictiondisk.config import scene_from_dict
    from frictiondisk.simulate import simulate

    return simulate(scene_from_dict(canonical)).summary()


def warm_up() -> None:
    """Compile (or load from the cache) the kernel for both scenes in this process."""
    for scene in ("pin", "disk"):
        run_scene(
            {
                "scene": scene,
                "contact": {"points": 2} if scene == "disk" else {},
                "numerics": {"t_decide": 0.5},
            }
        )
