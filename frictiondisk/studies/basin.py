"""Basin stability: run the basin campaigns and draw their figures.

    python -m frictiondisk.studies.basin [--only NAME ...] [-o out/basin] [--figures figures]

Runs campaigns/basin_pin_x0.yaml (fractions against mu), basin_pin_map.yaml with
basin_pin_boundary.yaml (the pin's map with the find_jump boundary) and basin_disk_map.yaml
(the braked disk's map) on the engine into OUT/<name>/, resuming what is there (a changed
kernel changes every journal key, so after a kernel change everything is computed again),
prints each campaign's fractions and writes FIGURES/basin_pin_x0.png, basin_pin_map.png
and basin_disk_map.png (docs/basin.md). `--only basin_disk_map` redoes one figure. What a
basin campaign costs per run is a benchmark: benchmarks/bench_basin.py.
"""

from __future__ import annotations

import sys
from pathlib import Path

from frictiondisk.studies import campaigns

FIGURES = {  # figure name -> (campaign, boundary campaign or None)
    "basin_pin_x0": ("basin_pin_x0", None),
    "basin_pin_map": ("basin_pin_map", "basin_pin_boundary"),
    "basin_disk_map": ("basin_disk_map", None),
}


def needed(names: list[str]) -> list[str]:
    """The campaigns the figures `names` draw on, each once, in order."""
    found = [c for name in names for c in FIGURES[name] if c is not None]
    return list(dict.fromkeys(found))


def draw(name: str, out: Path, figures: Path) -> Path:
    """Print the fractions of figure `name`'s campaign and draw it from the files in out."""
    import matplotlib

    matplotlib.use("Agg")
    from frictiondisk.figures.plotting import save_figure
    from frictiondisk.tasks.basin.figure import plot_basin
    from frictiondisk.tasks.basin.table import summary_lines

    campaign, boundary = FIGURES[name]
    results = campaigns.results(out / campaign)
    for line in summary_lines(results):
        print("  " + line)
    jump = campaigns.results(out / boundary) if boundary else None
    return save_figure(plot_basin(results, jump), figures / f"{name}.png")


def main(argv: list[str] | None = None) -> int:
    parser = campaigns.figure_study_parser(
        "python -m frictiondisk.studies.basin", __doc__.splitlines()[0], "out/basin"
    )
    parser.add_argument("--only", nargs="*", choices=sorted(FIGURES), default=None)
    args = parser.parse_args(argv)
    names = args.only if args.only is not None else list(FIGURES)
    campaigns.run_shipped(needed(names), args.campaigns, args.out, args.workers)
    for name in names:
        print(f"{name}: figure {draw(name, args.out, args.figures)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
