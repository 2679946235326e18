"""Well-posedness study: does the headline mu* move with the horizon and rtol?

Draws seeded random scenes (pin and disk; random x_ms, x0, m_s, omega_m, J_s, phidot0,
beta_b; a Stribeck curve on about 30 %) and locates every jump of each with a prescan and
bisection three times:

* `default`: the scene's numerics (t_decide 30 s, rtol 1e-6), certification on (the
  campaign default, find_jump.certify);
* `uncertified`: the same without certification (what the tool did before);
* `reference`: horizon x 8 and rtol / 100, no certification.

A scene *disagrees* when the headline mu* (the lowest rising jump) of a setting differs
from the reference's by more than tol, or one finds a jump where the other finds none. A
disagreement is *silent* when that setting calls the point converged and not `uncertain`.
With certification on, the count of silent disagreements must be 0. The extra wall time
of certification is the default's run time over the uncertified one's (same scenes).

    python benchmarks/study_wellposed.py                  # 50 scenes, 2 processes
    python benchmarks/study_wellposed.py --scenes 3 --processes 1
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import multiprocessing
import os
import sys
import time

import numpy as np

TOL = 1.0e-4
PRESCAN = tuple(round(0.02 + 0.03 * k, 4) for k in range(27))  # 0.02 ... 0.80
REFERENCE_HORIZON = 8.0
REFERENCE_RTOL = 0.01
STRIBECK_SHARE = 0.3


def draw_scene(seed: int, index: int) -> dict:
    """The scene dict of scene `index` of the study seeded `seed`."""
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
    if rng.uniform() < STRIBECK_SHARE:
        contact["stribeck"] = {
            "r": float(rng.uniform(0.6, 0.95)),
            "v_s": float(10.0 ** rng.uniform(-3.0, -1.5)),
        }
    return {"scene": scene, "params": params, "contact": contact}


@dataclasses.dataclass(frozen=True)
class Found:
    """The jumps one setting found for one scene."""

    status: str
    mu_star: float  # headline: the lowest rising jump (NaN: none)
    n_jumps: int
    certification: str
    runs: int
    wall_s: float  # kernel wall time of every run [s]


def locate(scene: dict, setting: str) -> Found:
    """Prescan and bisect every jump of `scene` under `setting` (module docstring)."""
    from frictiondisk.engine.tasks import run_bisection
    from frictiondisk.model.scene import scene_from_dict
    from frictiondisk.model.search_settings import OFF, Certify
    from frictiondisk.search.jumps import JumpSearch
    from frictiondisk.search.prescan import default_stride

    config = scene_from_dict(scene)
    if setting == "reference":
        num = config.numerics
        config = config.with_overrides(
            {
                "numerics.t_decide": num.t_decide * REFERENCE_HORIZON,
                "numerics.rtol": num.rtol * REFERENCE_RTOL,
            }
        )
    certify = Certify() if setting == "default" else OFF
    stride = default_stride(len(PRESCAN), "decide", config.numerics.stick_rule)
    search = JumpSearch(PRESCAN, TOL, 2, "decide", 2, certify, stride=stride)
    search, _ = run_bisection(search, config.canonical(), 2.0, os.devnull)
    result = search.result()
    runs = [run.result for run in result.runs]
    primary = result.primary
    return Found(
        status=result.status,
        mu_star=primary.mu_star if primary is not None and primary.rising else math.nan,
        n_jumps=len(result.jumps),
        certification=result.certification,
        runs=len(runs),
        wall_s=float(sum(run.get("wall_s", 0.0) for run in runs)),
    )


def study_scene(args: tuple[int, int]) -> dict:
    seed, index = args
    scene = draw_scene(seed, index)
    found = {setting: locate(scene, setting) for setting in SETTINGS}
    return {"index": index, "scene": scene, **found}


SETTINGS = ("default", "uncertified", "reference")


def disagrees(found: Found, reference: Found) -> bool:
    """Headline mu* more than TOL apart, or a jump on one side only."""
    a, b = found.mu_star, reference.mu_star
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) != math.isnan(b)
    return abs(a - b) > TOL * (1 + 1e-9)


def silent(found: Found, reference: Found) -> bool:
    """A disagreement the setting does not flag (converged and not uncertain)."""
    flagged = found.status != "converged" or found.certification == "uncertain"
    return disagrees(found, reference) and not flagged


def run_study(scenes: int, seed: int, processes: int) -> list[dict]:
    jobs = [(seed, index) for index in range(scenes)]
    if processes <= 1:
        return [study_scene(job) for job in jobs]
    with multiprocessing.get_context("spawn").Pool(processes) as pool:
        return list(pool.imap(study_scene, jobs))


def describe(scene: dict) -> str:
    params = ", ".join(f"{k} {v:.4g}" for k, v in scene["params"].items())
    stribeck = " Stribeck" if scene["contact"].get("stribeck") else ""
    return f"{scene['scene']}{stribeck}: {params}"


def report(rows: list[dict], wall_s: float) -> list[str]:
    lines = [f"well-posedness study: {len(rows)} scenes, tol {TOL:g}, {wall_s:.0f} s"]
    for setting in ("default", "uncertified"):
        differ = [r for r in rows if disagrees(r[setting], r["reference"])]
        quiet = [r for r in rows if silent(r[setting], r["reference"])]
        lines.append(f"  {setting:<12} differ from reference: {len(differ)}; silent: {len(quiet)}")
        for r in differ:
            f, ref = r[setting], r["reference"]
            lines.append(
                f"    scene {r['index']}: mu* {f.mu_star:.5f} ({f.certification}) vs "
                f"{ref.mu_star:.5f}; {describe(r['scene'])}"
            )
    flags: dict[str, int] = {}
    for r in rows:
        flags[r["default"].certification] = flags.get(r["default"].certification, 0) + 1
    lines.append(
        "  certification of the default: " + ", ".join(f"{k} {v}" for k, v in flags.items())
    )
    runs = {s: sum(r[s].runs for r in rows) for s in SETTINGS}
    walls = {s: sum(r[s].wall_s for r in rows) for s in SETTINGS}
    lines.append(
        "  runs: "
        + ", ".join(f"{s} {runs[s]}" for s in SETTINGS)
        + "; kernel wall time [s]: "
        + ", ".join(f"{s} {walls[s]:.1f}" for s in SETTINGS)
    )
    extra = walls["default"] / walls["uncertified"] - 1.0 if walls["uncertified"] > 0 else math.nan
    lines.append(f"  certification costs {100 * extra:+.0f} % kernel wall time over uncertified")
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=int, default=50)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--processes", type=int, default=2)
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    rows = run_study(args.scenes, args.seed, args.processes)
    lines = report(rows, time.perf_counter() - t0)
    print("\n".join(lines))
    return 1 if any(silent(r["default"], r["reference"]) for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
