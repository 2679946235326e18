"""Kernel benchmark: numba RODAS4 against the scipy Radau baseline, and CLI start-up.

Prints ratios measured in this process (both sides after JIT warm-up), so the numbers
mean something on a shared, noisy machine. Targets (issue 2): numba >= 50x faster than
the baseline on the same run with the same outcome; warm-cache `simulate` < 3 s.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate

ROOT = Path(__file__).resolve().parents[1]
BASELINE = {"method": "scipy-radau", "rtol": 1e-6, "atol": 1e-9, "h_max": 0.02}
KERNEL = {"method": "rodas4", "rtol": 1e-6, "atol": 1e-9}

CASES = {
    "pin decision run (mu 0.13, x_ms 0.1)": {
        "scene": "pin",
        "params": {"mu": 0.13, "x_ms": 0.1},
        "numerics": {"mode": "decide"},
    },
    "pin 200 s stick_slip run (mu 0.1265, x_ms 0.1)": {
        "scene": "pin",
        "params": {"mu": 0.1265, "x_ms": 0.1},
        "numerics": {"mode": "decide", "t_decide": 200.0},
    },
}


def best_wall(config, repeats):
    """Smallest wall time over repeats [s] and the last result."""
    walls = []
    for _ in range(repeats):
        res = simulate(config)
        walls.append(res.wall_s)
    return min(walls), res


def bench_runs():
    print("== one run: numba RODAS4 vs scipy Radau (rtol 1e-6, max_step 0.02 s) ==")
    for name, spec in CASES.items():
        kernel_cfg = scene_from_dict({**spec, "numerics": {**spec["numerics"], **KERNEL}})
        base_cfg = scene_from_dict({**spec, "numerics": {**spec["numerics"], **BASELINE}})
        simulate(kernel_cfg)  # JIT warm-up (compiles or loads the cache)
        t_kernel, r_kernel = best_wall(kernel_cfg, 20)
        t_base, r_base = best_wall(base_cfg, 2)
        same = r_kernel.outcome == r_base.outcome
        print(f"{name}")
        print(
            f"  numba   : {t_kernel * 1e3:9.2f} ms  outcome {r_kernel.outcome:<11} "
            f"R1 {r_kernel.R1:.9f} m  steps {r_kernel.n_steps}"
        )
        print(
            f"  scipy   : {t_base * 1e3:9.2f} ms  outcome {r_base.outcome:<11} "
            f"R1 {r_base.R1:.9f} m  steps {r_base.n_steps}"
        )
        print(
            f"  speed-up: {t_base / t_kernel:9.1f} x   (target >= 50 x)   same outcome: {same}   "
            f"|dR1| = {abs(r_kernel.R1 - r_base.R1):.2e} m"
        )


def cli_time(env, scene_file, repeats):
    walls = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(
            [sys.executable, "-m", "frictiondisk.cli", "simulate", str(scene_file), "--json"],
            check=True,
            env=env,
            capture_output=True,
            cwd=ROOT,
        )
        walls.append(time.perf_counter() - t0)
    return walls


def bench_startup():
    print("== `frictiondisk simulate` end to end (subprocess) ==")
    with tempfile.TemporaryDirectory() as tmp:
        scene_file = Path(tmp) / "scene.yaml"
        scene_file.write_text("scene: pin\nparams: {mu: 0.13}\n")
        env = dict(os.environ, NUMBA_CACHE_DIR=str(Path(tmp) / "numba-cache"))
        cold = cli_time(env, scene_file, 1)[0]
        warm = cli_time(env, scene_file, 3)
        print(f"  cold cache (compiles): {cold:6.2f} s")
        print(f"  warm cache (median)  : {statistics.median(warm):6.2f} s   (target < 3 s)")
        print(f"  cold / warm          : {cold / statistics.median(warm):6.1f} x")


if __name__ == "__main__":
    bench_runs()
    bench_startup()
