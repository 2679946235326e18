"""The study's scenes: seeded random pins and disks from one of two independent generators.

Generator 1 (`draw_scene`) is the one the verdict's rules were tuned on; generator 2
(`draw_scene2`) draws wider ranges from an independent stream: Stribeck r down to
0.6 with v_s 0.002-0.02 m/s, disks from rest with small J_s, partly spun disks, annulus
layouts, braked disks, and a slave frequency sqrt(c_s / m_s) around omega_m (the beat of
the two made the oscillating slip that a Stribeck disk from rest showed before the
sliding evidence read troughs).
"""

from __future__ import annotations

import math

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


def _log_uniform(rng, lo: float, hi: float) -> float:
    return float(10.0 ** rng.uniform(math.log10(lo), math.log10(hi)))


def _disk_of_generator_2(rng, params: dict, contact: dict) -> None:
    """A disk's spin, brake and contact layout (generator 2)."""
    omega_m = params["omega_m"]
    small = rng.random() < 0.5
    params["J_s"] = _log_uniform(rng, 0.002, 0.02) if small else _log_uniform(rng, 0.005, 0.2)
    start = str(rng.choice(["rest", "rest", "corotating", "partial"]))
    spins = {"rest": 0.0, "corotating": omega_m, "partial": float(rng.uniform(0.1, 0.9))}
    params["phidot0"] = spins[start] if start != "partial" else spins[start] * omega_m
    params["beta_b"] = 0.0 if rng.random() < 0.6 else _log_uniform(rng, 1e-4, 1e-2)
    if str(rng.choice(["ring", "ring", "annulus", "annulus"])) == "ring":
        contact["ring_radius"] = float(rng.uniform(0.02, 0.08))
    else:
        inner = float(rng.uniform(0.0, 0.04))
        contact["layout"] = "annulus"
        contact["inner_radius"] = inner
        contact["outer_radius"] = float(inner + rng.uniform(0.01, 0.05))
    contact["points"] = int(rng.choice([8, 12, 16]))


def draw_scene2(seed: int, index: int) -> dict:
    """Scene `index` of seed `seed` of generator 2 (module docstring), its own stream
    default_rng([seed, index, 2]): a pin for index % 4 == 0, else a disk.

    omega_m in [0.5, 2] rad/s, x_ms in [0.04, 0.16] m, x0 in [-0.03, 0.03] m, y0 in
    [-0.02, 0.02] m on a quarter, m_s log-uniform in [0.4, 2.5] kg (sqrt(c_s / m_s) 0.63 ...
    1.6 rad/s). A disk: J_s log-uniform in [0.002, 0.02] (half) or [0.005, 0.2] kg m^2;
    phidot0 0 (half), omega_m (a quarter) or [0.1, 0.9] omega_m; beta_b 0 (60 %) or
    log-uniform in [1e-4, 1e-2] N m s/rad; a ring of radius [0.02, 0.08] m or an annulus
    (inner [0, 0.04] m, width [0.01, 0.05] m), 8, 12 or 16 points. Stribeck on 60 %: r in
    [0.6, 0.95], v_s log-uniform in [0.002, 0.02] m/s."""
    rng = np.random.default_rng([seed, index, 2])
    scene = "pin" if index % 4 == 0 else "disk"
    params = {
        "omega_m": float(rng.uniform(0.5, 2.0)),
        "x_ms": float(rng.uniform(0.04, 0.16)),
        "x0": float(rng.uniform(-0.03, 0.03)),
        "m_s": _log_uniform(rng, 0.4, 2.5),
    }
    if rng.random() < 0.25:
        params["y0"] = float(rng.uniform(-0.02, 0.02))
    contact: dict = {}
    if scene == "disk":
        _disk_of_generator_2(rng, params, contact)
    if rng.random() < 0.6:
        contact["stribeck"] = {
            "r": float(rng.uniform(0.6, 0.95)),
            "v_s": _log_uniform(rng, 0.002, 0.02),
        }
    return {"scene": scene, "params": params, "contact": contact}


GENERATORS = {1: draw_scene, 2: draw_scene2}


def draw(generator: int, seed: int, index: int) -> dict:
    """Scene `index` of seed `seed` of `generator` (1 or 2)."""
    if generator not in GENERATORS:
        raise ValueError(f"generator must be one of {sorted(GENERATORS)}; got {generator!r}")
    return GENERATORS[generator](seed, index)


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
