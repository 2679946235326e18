"""What certification costs on the paper's figures: the six find_jump figure campaigns as
shipped (certification on) against the same with `find_jump.certify: false`, each as one
run of all six (`frictiondisk run A.yaml ... F.yaml -o DIR`, 2 workers), alternately
(the order flips every repetition), into fresh folders (no journal reused).

It prints the wall time and the kernel time (sum of runs.nc wall_s) of both, their
ratios (target: certification <= +25 % wall time, issue 28), and whether every point's
mu* of the uncertified run lies within its bracket width of the certified one's.

    python benchmarks/bench_certify_cost.py [--repeat 2] [--quick]

--quick keeps the two ends of each campaign's line: a smoke check, not the number.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr
from bench_together import CAMPAIGNS, campaign_files, kernel_seconds
from harness import Record

TARGET = 0.25  # certification's extra wall time (issue 28)


def run_all(files: list[Path], out: Path) -> float:
    """Wall time [s] of one `frictiondisk run` of all the files into out."""
    t0 = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "frictiondisk.cli", "run", *map(str, files), "-o", str(out)],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    return time.perf_counter() - t0


def agree(on: Path, off: Path) -> list[str]:
    """Points whose mu* differ by more than the larger bracket width."""
    problems = []
    for name in CAMPAIGNS:
        with (
            xr.open_dataset(on / name / "results.nc") as a,
            xr.open_dataset(off / name / "results.nc") as b,
        ):
            width = np.maximum(a.mu_hi - a.mu_lo, b.mu_hi - b.mu_lo).values.ravel()
            diff = np.abs(a.mu_star - b.mu_star).values.ravel()
            for k in np.flatnonzero(diff > width * (1 + 1e-9)):
                problems.append(f"{name} point {k}: {diff[k]:.3g} apart")
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    times: dict[str, list[float]] = {"on": [], "off": []}
    kernel: dict[str, list[float]] = {"on": [], "off": []}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        files = {}
        for mode in ("on", "off"):
            (tmp / f"files_{mode}").mkdir()
            files[mode] = campaign_files(tmp / f"files_{mode}", args.quick, certify=mode == "on")
        last = {}
        for rep in range(args.repeat):
            for mode in ("on", "off") if rep % 2 == 0 else ("off", "on"):
                out = tmp / f"{mode}_{rep}"
                times[mode].append(run_all(files[mode], out))
                kernel[mode].append(kernel_seconds(out))
                last[mode] = out
                print(
                    f"rep {rep} certify {mode}: {times[mode][-1]:.1f} s, kernel {kernel[mode][-1]:.1f} s"
                )
        wall = statistics.median(times["on"]) / statistics.median(times["off"]) - 1.0
        work = statistics.median(kernel["on"]) / statistics.median(kernel["off"]) - 1.0
        print(f"certification costs {100 * wall:+.0f} % wall time, {100 * work:+.0f} % kernel time")
        print(
            f"target: at most {100 * TARGET:+.0f} % wall time: {'met' if wall <= TARGET else 'NOT met'}"
        )
        problems = agree(last["on"], last["off"])
        print("mu* certified vs uncertified: " + ("; ".join(problems) or "within each bracket"))
    record = Record("certify_cost")
    median = {mode: statistics.median(times[mode]) for mode in times}
    kernels = {mode: statistics.median(kernel[mode]) for mode in kernel}
    record.ratio("wall, certified over uncertified", median["on"], median["off"], "<= 1.25")
    record.ratio("kernel, certified over uncertified", kernels["on"], kernels["off"])
    record.number("mu* outside the other's bracket", len(problems), "1", "== 0")
    record.write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
