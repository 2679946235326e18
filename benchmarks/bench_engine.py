"""Campaigns at the kernel's pace: how much of the workers' time a campaign of short runs
spends in the kernel, and what a run costs as the campaign grows.

Scans of the pin's decide runs (x_ms 0.1, mu from 0.13 to 0.30) of 40, 400, 4 000 and (with
--big) 40 000 runs (10 000 values of mu, each from 4 nearby x0: one axis holds at most
10 000 values), and a basin of 10 000 runs (x0 ~ U[-0.05, 0.05] at 10 values of mu,
1 000 samples each, decided within 30 s as in campaigns/basin_pin_x0.yaml), every one into a fresh folder on 2 workers (the default). For each:

* efficiency = (sum of the runs' kernel times, runs.nc wall_s) / (workers x wall);
* the cost per run: wall / runs, and the marginal cost from one size to the next,
  (wall_B - wall_A) / (B - A), which leaves out the fixed cost of a campaign;
* the driver's process CPU per run beyond the kernel, (CPU - kernel) / runs: the Python
  around the runs (workers' and driver's), which a busy machine moves less than walls.

The basin is run on 1 worker too: its fractions must be identical. The first lines time
simulate()'s Python around the kernel (the least of many calls of the pin decision run).
Every campaign of the run shares the process (its imports and kernel load are paid once,
by a small campaign before the timed ones), so the numbers are the engine's, not start-up's.

    python benchmarks/bench_engine.py            # 40, 400, 4 000 runs and the basin
    python benchmarks/bench_engine.py --big      # and the 40 000-run scan (minutes)

Timings on a shared machine: compare only within one run; the load is printed beside
each number.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr
from harness import Record

from frictiondisk.engine.runner import run_campaign
from frictiondisk.engine.worker import warm_up
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.tasks.campaign import campaign_from_text

SCAN = """\
name: scan_{runs}
scene: pin
params: {{x_ms: 0.1}}
scan:
  mu: {{start: 0.13, stop: 0.30, num: {num}}}
  mode: decide
{along}"""
AXIS_MAX = 10_000  # values of one varied key (model/axes.py): more runs take 4 values of x0
ALONG = "  along: {params.x0: [0.0, 0.001, 0.002, 0.003]}\n"


def scan_text(runs: int) -> str:
    """The scan of `runs` decide runs: mu alone, or (over AXIS_MAX runs) mu times 4
    nearby initial deflections x0 [m], runs of the same kind."""
    if runs <= AXIS_MAX:
        return SCAN.format(runs=runs, num=runs, along="")
    return SCAN.format(runs=runs, num=runs // 4, along=ALONG)


BASIN = """\
name: basin_{runs}
scene: pin
params: {{x_ms: 0.1}}
numerics: {{mode: decide, t_decide: 30.0}}
basin:
  sample: {{params.x0: {{uniform: [-0.05, 0.05]}}}}
  samples: {samples}
  seed: 3
  along:
    params.mu: {{start: 0.112, stop: 0.140, num: {points}}}
"""

PIN_DECISION = {"scene": "pin", "params": {"mu": 0.13, "x_ms": 0.1}, "numerics": {"mode": "decide"}}
WORKERS = 2


def load() -> float:
    return os.getloadavg()[0]


def python_around(calls: int = 400) -> tuple[float, float]:
    """(least, median) [s] of simulate()'s time outside its kernel call (the result's
    wall_s) over `calls` calls of the pin decision run."""
    config = scene_from_dict(PIN_DECISION)
    simulate(config)
    around = []
    for _ in range(calls):
        t0 = time.perf_counter()
        result = simulate(config)
        around.append(time.perf_counter() - t0 - result.wall_s)
    return min(around), float(np.median(around))


def timed(text: str, workers: int = WORKERS) -> dict:
    """One fresh campaign: wall [s], process CPU [s], kernel sum [s], runs, the load, and
    its results.nc (loaded)."""
    campaign = campaign_from_text(text, "<bench_engine>")
    with tempfile.TemporaryDirectory(prefix="bench-engine-") as tmp:
        load_before = load()
        cpu0, t0 = time.process_time(), time.perf_counter()
        summary = run_campaign(campaign, Path(tmp), workers=workers, progress=False)
        wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
        with xr.open_dataset(Path(tmp) / "runs.nc") as runs:
            kernel = float(runs.wall_s.sum())
        with xr.open_dataset(Path(tmp) / "results.nc") as results:
            results = results.load()
    return {
        "wall": wall,
        "cpu": cpu,
        "kernel": kernel,
        "runs": summary.runs_computed,
        "load": (load_before + load()) / 2,
        "results": results,
        "workers": workers,
    }


def report(record: Record, label: str, m: dict) -> None:
    efficiency = m["kernel"] / (m["workers"] * m["wall"])
    per_run = m["wall"] / m["runs"]
    beyond = (m["cpu"] - m["kernel"]) / m["runs"]
    print(
        f"{label:<24} {m['runs']:>6} runs  wall {m['wall']:7.2f} s  kernel {m['kernel']:7.2f} s  "
        f"efficiency {efficiency:5.3f}  {1e3 * per_run:6.2f} ms/run  "
        f"CPU beyond kernel {1e3 * beyond:5.2f} ms/run  (load {m['load']:.1f})",
        flush=True,
    )
    record.number(f"{label}: efficiency", efficiency, "1", target=">= 0.67")
    record.number(f"{label}: wall per run", 1e3 * per_run, "ms")
    record.number(f"{label}: process CPU beyond the kernel per run", 1e3 * beyond, "ms")
    record.number(f"{label}: load", m["load"], "1")


def marginal(record: Record, small: tuple[int, dict], large: tuple[int, dict]) -> float:
    """(wall_B - wall_A) / (B - A) [s per run]."""
    (a, ma), (b, mb) = small, large
    cost = (mb["wall"] - ma["wall"]) / (b - a)
    record.number(f"cost per run from {a} to {b} runs", 1e3 * cost, "ms")
    print(f"cost per run from {a:>6} to {b:>6} runs: {1e3 * cost:6.2f} ms", flush=True)
    return cost


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--big", action="store_true", help="also the 40 000-run scan")
    parser.add_argument(
        "--basin-runs", type=int, default=10_000, help="runs of the basin (0: none)"
    )
    parser.add_argument(
        "--sizes", type=int, nargs="+", default=[40, 400, 4_000], help="runs of each scan"
    )
    args = parser.parse_args(argv)
    warm_up()
    record = Record("engine")
    least, median = python_around()
    print(
        f"simulate(): Python around the kernel {1e3 * least:.3f} ms least, "
        f"{1e3 * median:.3f} ms median (load {load():.1f})",
        flush=True,
    )
    record.number("simulate(): Python around the kernel, least", 1e3 * least, "ms", "<= 0.1")
    timed(scan_text(8))  # imports and first-use costs, paid once before the timings
    same = basin(record, args.basin_runs) if args.basin_runs else True
    record.write()  # kept so far: the 40 000-run scan takes long
    scans(record, args.sizes + ([40_000] if args.big else []))
    record.write()
    return 0 if same else 1


def basin(record: Record, runs: int) -> bool:
    """The basin on 2 workers and on 1; whether its fractions are identical."""
    points = 10
    samples = max(1, runs // points)
    text = BASIN.format(runs=points * samples, samples=samples, points=points)
    basins = {workers: timed(text, workers) for workers in (WORKERS, 1)}
    for workers, m in basins.items():
        report(record, f"basin, {workers} worker{'s' * (workers > 1)}", m)
    fractions = [m["results"].not_stick_fraction.values for m in basins.values()]
    same = bool(np.array_equal(fractions[0], fractions[1], equal_nan=True))
    print(f"basin: fractions identical on 1 and {WORKERS} workers: {same}", flush=True)
    record.number("basin: fractions identical on 1 and 2 workers", int(same), "1", "== 1")
    return same


def scans(record: Record, sizes: list[int]) -> None:
    """The scans of `sizes` runs, and the ratios of their marginal costs per run."""
    done = {}
    for runs in sizes:
        done[runs] = timed(scan_text(runs))
        report(record, f"scan of {runs}", done[runs])
        if len(done) >= 2:
            a, b = sizes[len(done) - 2], runs
            marginal(record, (a, done[a]), (b, done[b]))
        if len(done) >= 3:
            a, b, c = sizes[len(done) - 3 : len(done)]
            record.ratio(
                f"cost per run {b}-{c} over {a}-{b}",
                record.numbers[f"cost per run from {b} to {c} runs"]["value"],
                record.numbers[f"cost per run from {a} to {b} runs"]["value"],
                target="<= 1.2",
            )


if __name__ == "__main__":
    sys.exit(main())
