"""Start-up benchmark: what a user waits for before and around the first run.

* warm `frictiondisk simulate campaigns/demo_pin.yaml` (kernel compiled and cached):
  wall time of the whole command, best of 5, and the run's own kernel time;
* the fixed start-up of `frictiondisk run`: wall time of a one-point campaign minus the
  kernel time of its runs (imports, loading the compiled kernel, the local Dask cluster,
  the netCDF files), best of 5 (several campaigns in one `run` pay it once:
  benchmarks/bench_together.py);
* for scale, measured alongside: a bare `python -c pass`, and `import numba` and
  `import dask.distributed` on their own (every run pays these).

Targets (issue 23): warm simulate <= 0.6 s; fixed start-up of run <= 0.7 s.

    python benchmarks/bench_startup.py
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import xarray as xr
from harness import Record

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


def wall(cmd: list[str]) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT)
    return time.perf_counter() - t0


def best(cmd: list[str]) -> float:
    return min(wall(cmd) for _ in range(REPEATS))


def simulate_times() -> tuple[float, float]:
    """(best wall time of the command [s], the run's kernel time [s])."""
    cmd = [*CLI, "simulate", "campaigns/demo_pin.yaml", "--json"]
    subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT)  # compile or load once
    out = subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT, text=True).stdout
    return best(cmd), float(json.loads(out)["wall_s"])


def run_fixed() -> tuple[float, float]:
    """(best wall time of a one-point campaign [s], its fixed part: wall - kernel [s])."""
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        spec = Path(tmp) / "c.yaml"
        spec.write_text(TINY)
        for k in range(REPEATS):
            out = Path(tmp) / f"o{k}"
            t = wall([*CLI, "run", str(spec), "-o", str(out)])
            with xr.open_dataset(out / "runs.nc") as runs:
                kernel = float(runs["wall_s"].sum())
            results.append((t, t - kernel))
    return min(results)


def main() -> int:
    bare = best([sys.executable, "-c", "pass"])
    numba = best([sys.executable, "-c", "import numba"]) - bare
    dask = best([sys.executable, "-c", "import dask.distributed"]) - bare
    sim_wall, sim_kernel = simulate_times()
    run_wall, fixed = run_fixed()
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
    record = Record("startup")
    record.number("python -c pass", bare, "s")
    record.number("import numba, beyond python's start", numba, "s")
    record.number("import dask.distributed, beyond python's start", dask, "s")
    record.number("warm simulate demo_pin", sim_wall, "s", "<= 0.6")
    record.number("fixed start-up of run", fixed, "s", "<= 0.7")
    record.ratio("warm simulate over bare python", sim_wall, bare)
    record.write()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
