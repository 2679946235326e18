"""The study's scenes: seeded random pins and disks, half of them with a Stribeck curve."""

from __future__ import annotations

import numpy as np


def draw_scene(seed: int, index: int) -> dict:
    """The scene dict of scene `index` of the study seeded `seed`: a pin for even index, a
    disk for odd; a Stribeck curve on every other pin and every other disk.

    x_ms in [0.05, 0.15] m, x0 in [-0.03, 0.03] m, m_s in [0.5, 2] kg, omega_m in
    [0.6, 1.6] rad/s; a disk also J_s in [0.005, 0.2] kg m^2, phidot0 0 or omega_m and
    beta_b 0 or drawn from [0, 0.01] N m s/rad; Stribeck: r in [0.6, 0.95], v_s =
    10^[-3, -1.5] m/s."""
    rng = np.random.default_rng([seed, index])
    scene = "disk" if index % 2 else "pin"
    omega_m = float(rng.uniform(0.6, 1.6))
    params = {
        "x_ms": float(rng.uniform(0.05, 0.15)),
        "x0": float(rng.uniform(-0.03, 0.03)),
        "m_s": float(rng.uniform(0.5, 2.0)),
        "omega_m": omega_m,
    }
    if scene == "disk":
        params["J_s"] = float(rng.uniform(0.005, 0.2))
        params["phidot0"] = float(rng.choice([0.0, omega_m]))
        params["beta_b"] = float(rng.choice([0.0, rng.uniform(0.0, 0.01)]))
    contact: dict = {}
    stribeck = {"r": float(rng.uniform(0.6, 0.95)), "v_s": float(10.0 ** rng.uniform(-3, -1.5))}
    if (index // 2) % 2 == 1:
        contact["stribeck"] = stribeck
    return {"scene": scene, "params": params, "contact": contact}


def braked(scene: dict) -> bool:
    """A disk with a brake (beta_b > 0): the class the co-rotation verdict decides."""
    return scene["scene"] == "disk" and scene["params"].get("beta_b", 0.0) > 0.0


def coulomb_pin(scene: dict) -> bool:
    """A pin with Coulomb friction: the exact Coulomb integrator watches it too."""
    stribeck = scene.get("contact", {}).get("stribeck") or {}
    return scene["scene"] == "pin" and stribeck.get("r", 1.0) == 1.0


def describe(scene: dict) -> str:
    """One line: body, Stribeck or not, and the drawn parameters."""
    params = ", ".join(f"{k} {v:.4g}" for k, v in scene["params"].items())
    stribeck = " Stribeck" if scene["contact"].get("stribeck") else ""
    return f"{scene['scene']}{stribeck}: {params}"


def parse_seeds(text: str) -> list[int]:
    """'1-10' -> 1 ... 10; '1,3' -> 1, 3."""
    if "-" in text:
        first, last = text.split("-")
        return list(range(int(first), int(last) + 1))
    return [int(s) for s in text.split(",")]


def parse_scene(text: str) -> tuple[int, int]:
    """'3/14' -> (seed 3, scene 14), as the study's tables name a scene."""
    seed, _, index = text.partition("/")
    if not index:
        raise ValueError(f"a scene is SEED/INDEX, e.g. 3/14; got {text!r}")
    return int(seed), int(index)
