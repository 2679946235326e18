"""Start-up benchmark: what a user waits for before and around the first run.

* warm `frictiondisk simulate campaigns/demo_pin.yaml` (kernel compiled and cached):
  wall time of the whole command, best of 5, and the run's own kernel time;
* the fixed start-up of `frictiondisk run`: wall time of a one-point campaign minus the
  kernel time of its runs (imports, loading the compiled kernel, the local Dask cluster,
  the netCDF files), best of 5: in a process of its own, and handed to a warm server
  (`frictiondisk serve`, started for this benchmark in a private directory of its own);
* for scale, measured alongside: a bare `python -c pass`, and `import numba` and
  `import dask.distributed` on their own (every run pays these).

Targets (issue 23): warm simulate <= 0.6 s; fixed start-up of run <= 0.7 s.
simulate is never handed to a server; every command but the served ones runs with
FRICTIONDISK_NO_SERVER=1, so that a server the user left running changes nothing.

    python benchmarks/bench_startup.py
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import xarray as xr

ROOT = Path(__file__).resolve().parent.parent
CLI = [sys.executable, "-m", "frictiondisk.cli"]
TINY = """\
name: startup
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-2
  along: {params.x_ms: [0.1]}
"""
REPEATS = 5


ALONE = {**os.environ, "FRICTIONDISK_NO_SERVER": "1"}


def wall(cmd: list[str], env: dict | None = None) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT, env=env or ALONE)
    return time.perf_counter() - t0


def best(cmd: list[str]) -> float:
    return min(wall(cmd) for _ in range(REPEATS))


def simulate_times() -> tuple[float, float]:
    """(best wall time of the command [s], the run's kernel time [s])."""
    cmd = [*CLI, "simulate", "campaigns/demo_pin.yaml", "--json"]
    subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT)  # compile or load once
    out = subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT, text=True).stdout
    return best(cmd), float(json.loads(out)["wall_s"])


def run_fixed(env: dict | None = None) -> tuple[float, float]:
    """(best wall time of a one-point campaign [s], its fixed part: wall - kernel [s])."""
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        spec = Path(tmp) / "c.yaml"
        spec.write_text(TINY)
        for k in range(REPEATS):
            out = Path(tmp) / f"o{k}"
            t = wall([*CLI, "run", str(spec), "-o", str(out)], env)
            with xr.open_dataset(out / "runs.nc") as runs:
                kernel = float(runs["wall_s"].sum())
            results.append((t, t - kernel))
    return min(results)


def served_run_fixed() -> tuple[float, float, float]:
    """run_fixed() of commands handed to a warm server, and the server's own start [s]."""
    with tempfile.TemporaryDirectory() as servers:
        env = {**os.environ, "FRICTIONDISK_SERVER_DIR": servers}
        env.pop("FRICTIONDISK_NO_SERVER", None)
        t0 = time.perf_counter()
        serve = [*CLI, "serve", "--detach", "--idle-timeout", "600"]
        subprocess.run(serve, check=True, capture_output=True, cwd=ROOT, env=env)
        started = time.perf_counter() - t0
        try:
            return (*run_fixed(env), started)
        finally:
            subprocess.run([*CLI, "serve", "--stop"], capture_output=True, cwd=ROOT, env=env)


def main() -> int:
    bare = best([sys.executable, "-c", "pass"])
    numba = best([sys.executable, "-c", "import numba"]) - bare
    dask = best([sys.executable, "-c", "import dask.distributed"]) - bare
    sim_wall, sim_kernel = simulate_times()
    run_wall, fixed = run_fixed()
    served_wall, served_fixed, server_start = served_run_fixed()
    print(f"python -c pass            {bare:6.3f} s")
    print(f"import numba              {numba:6.3f} s   (beyond python's own start)")
    print(f"import dask.distributed   {dask:6.3f} s")
    print(
        f"warm simulate demo_pin    {sim_wall:6.3f} s   (kernel {sim_kernel:.3f} s)   "
        f"target <= 0.6 s: ratio {sim_wall / 0.6:.2f}"
    )
    print(
        f"run, one-point campaign   {run_wall:6.3f} s   fixed start-up {fixed:.3f} s   "
        f"target <= 0.7 s: ratio {fixed / 0.7:.2f}"
    )
    print(
        f"  handed to a warm server {served_wall:6.3f} s   fixed start-up {served_fixed:.3f} s   "
        f"target <= 0.7 s: ratio {served_fixed / 0.7:.2f}   "
        f"(the server started in {server_start:.2f} s, once)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
