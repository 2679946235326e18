"""Basin stability (issue 12): run the basin campaigns, draw their figures, measure.

    python benchmarks/basin_study.py [--only NAME ...] [--measure] [--out out/basin] [--figures figures]

Runs campaigns/basin_pin_x0.yaml (fractions against mu), basin_pin_map.yaml with
basin_pin_boundary.yaml (the pin's map with the find_jump boundary) and basin_disk_map.yaml
(the braked disk's map) into OUT/<name>, resuming what is there (a changed kernel changes
every journal key, so after a kernel change everything is computed again), and writes
FIGURES/basin_pin_x0.png, basin_pin_map.png, basin_disk_map.png. `--only basin_disk_map`
redoes one figure. Prints each campaign's fractions and wall time.

`--measure` also times fresh basin runs of the pin (x0 ~ U[-0.05, 0.05], mu = 0.125,
2000 samples) with 1 and 2 Dask workers: runs per second of the whole campaign (driver,
journal, Dask) and of the kernel alone (sum of the runs' wall_s), and prints the samples a
standard error of 0.01 needs at each mu of basin_pin_x0 (p (1 - p) / 0.01^2, and what the
adaptive campaign took). Timings on a shared machine: compare only within one run.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

import xarray as xr

from frictiondisk.engine.runner import run_campaign
from frictiondisk.tasks.basin import stats as basin_stats
from frictiondisk.tasks.basin.table import summary_lines
from frictiondisk.tasks.campaign import campaign_from_text, load_campaign

FIGURES = {  # figure name -> (campaign, boundary campaign or None)
    "basin_pin_x0": ("basin_pin_x0", None),
    "basin_pin_map": ("basin_pin_map", "basin_pin_boundary"),
    "basin_disk_map": ("basin_disk_map", None),
}
MEASURE = """\
name: basin_rate
scene: pin
params: {x_ms: 0.1, mu: 0.125}
basin:
  sample: {params.x0: {uniform: [-0.05, 0.05]}}
  samples: 2000
  seed: 1
"""


def _run(campaigns: Path, out: Path, name: str) -> Path:
    t0 = time.perf_counter()
    summary = run_campaign(load_campaign(campaigns / f"{name}.yaml"), out / name, progress=False)
    print(
        f"{name}: {summary.runs_total} runs ({summary.runs_computed} computed now), "
        f"{time.perf_counter() - t0:.1f} s",
        flush=True,
    )
    return out / name


def make_figure(name: str, campaigns: Path, out: Path, figures: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from frictiondisk.figures.plotting import save_figure
    from frictiondisk.tasks.plot import figure_for_dir

    campaign, boundary = FIGURES[name]
    directory = _run(campaigns, out, campaign)
    boundary_dir = _run(campaigns, out, boundary) if boundary else None
    with xr.open_dataset(directory / "results.nc") as results:
        for line in summary_lines(results.load()):
            print("  " + line)
    fig = figure_for_dir(directory, boundary=boundary_dir)
    print(f"  figure: {save_figure(fig, figures / f'{name}.png')}", flush=True)


def measure(out: Path) -> None:
    print(f"load average before: {os.getloadavg()[0]:.2f} (2 cores, shared)")
    campaign = campaign_from_text(MEASURE, "<measure>")
    for workers in (1, 2):
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            summary = run_campaign(campaign, Path(tmp), workers=workers, progress=False)
            wall = time.perf_counter() - t0
            with xr.open_dataset(Path(tmp) / "runs.nc") as runs:
                kernel = float(runs.wall_s.sum())
        print(
            f"workers {workers}: {summary.runs_computed} runs in {wall:.1f} s (incl. ~start-up) "
            f"= {summary.runs_computed / wall:.0f} runs/s; kernel alone "
            f"{summary.runs_computed / kernel:.0f} runs/s per core "
            f"(mean {1e3 * kernel / summary.runs_computed:.2f} ms/run)",
            flush=True,
        )
    path = out / "basin_pin_x0" / "results.nc"
    if path.exists():
        with xr.open_dataset(path) as ds:
            for mu, p, n in zip(
                ds.mu.values, ds.not_stick_fraction.values, ds.n_samples.values, strict=True
            ):
                need = basin_stats.samples_for_error(float(p), 0.01)
                print(f"mu = {mu:.4f}: not stick {p:.3f}: SE 0.01 needs {need}, took {int(n)}")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--campaigns", type=Path, default=Path("campaigns"))
    parser.add_argument("--out", type=Path, default=Path("out/basin"))
    parser.add_argument("--figures", type=Path, default=Path("figures"))
    parser.add_argument("--only", nargs="*", choices=sorted(FIGURES), default=None)
    parser.add_argument("--measure", action="store_true")
    args = parser.parse_args(argv)
    for name in args.only if args.only is not None else FIGURES:
        make_figure(name, args.campaigns, args.out, args.figures)
    if args.measure:
        measure(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
