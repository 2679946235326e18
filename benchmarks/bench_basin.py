"""Basin campaigns: runs per second of the whole campaign (driver, journal, Dask) against the
kernel alone, on 1 and 2 workers (issue 12).

Times fresh basin runs of the pin (x0 ~ U[-0.05, 0.05], mu = 0.125, 2000 samples) with 1
and 2 Dask workers, each into a fresh folder (no journal reused): the speed-up of 2 workers
over 1, and the campaign's rate over the kernel's (the sum of its runs' wall_s). With a
basin_pin_x0 campaign already run (python -m frictiondisk.studies.basin, into --basin), it
also prints the samples a standard error of 0.01 needs at each of its mu
(p (1 - p) / 0.01^2) against what the adaptive campaign took.

    python benchmarks/bench_basin.py [--basin out/basin]

Timings on a shared machine: compare only within one run.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import xarray as xr
from harness import Record

from frictiondisk.engine.runner import run_campaign
from frictiondisk.engine.worker import warm_up
from frictiondisk.tasks.basin import stats as basin_stats
from frictiondisk.tasks.campaign import campaign_from_text

MEASURE = """\
name: basin_rate
scene: pin
params: {x_ms: 0.1, mu: 0.125}
basin:
  sample: {params.x0: {uniform: [-0.05, 0.05]}}
  samples: 2000
  seed: 1
"""


def timed(workers: int) -> tuple[float, int, float]:
    """(wall [s], runs, kernel [s]) of one fresh basin campaign on `workers` workers."""
    campaign = campaign_from_text(MEASURE, "<measure>")
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        summary = run_campaign(campaign, Path(tmp), workers=workers, progress=False)
        wall = time.perf_counter() - t0
        with xr.open_dataset(Path(tmp) / "runs.nc") as runs:
            kernel = float(runs.wall_s.sum())
    return wall, summary.runs_computed, kernel


def samples_needed(basin: Path) -> None:
    path = basin / "basin_pin_x0" / "results.nc"
    if not path.exists():
        return
    with xr.open_dataset(path) as ds:
        for mu, p, n in zip(
            ds.mu.values, ds.not_stick_fraction.values, ds.n_samples.values, strict=True
        ):
            need = basin_stats.samples_for_error(float(p), 0.01)
            print(f"mu = {mu:.4f}: not stick {p:.3f}: SE 0.01 needs {need}, took {int(n)}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--basin", type=Path, default=Path("out/basin"))
    args = parser.parse_args(argv)
    warm_up()
    record = Record("basin")
    walls = {}
    for workers in (1, 2):
        wall, runs, kernel = timed(workers)
        walls[workers] = wall
        print(
            f"workers {workers}: {runs} runs in {wall:.1f} s (incl. ~start-up) "
            f"= {runs / wall:.0f} runs/s; kernel alone {runs / kernel:.0f} runs/s per core "
            f"(mean {1e3 * kernel / runs:.2f} ms/run)",
            flush=True,
        )
        record.number(f"{workers} workers: runs per second", runs / wall, "1/s")
        record.ratio(f"{workers} workers: campaign wall over kernel sum", wall, kernel)
    record.ratio("speed-up, 2 workers over 1", walls[1], walls[2])
    samples_needed(args.basin)
    record.write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
