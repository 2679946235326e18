"""`make figures`: run every figure campaign (campaigns/fig*.yaml, and the traced Fig 11)
and draw its figure.

    python -m frictiondisk.cli.figure_campaigns [--campaigns campaigns] [--out out/figures]
        [--figures out/figures] [--only NAME ...] [--formats png,pdf]

The campaigns run together, in one process on one set of workers (run_campaigns: each
into OUT/<name>/, resuming whatever is already there, like `frictiondisk run A.yaml
B.yaml -o OUT`). Then each figure is written as FIGURES/<name>.png and .pdf from the
netCDF files alone (by default under the ignored out/, so the tracked tree stays clean;
`make gallery` draws the gallery's PNGs into figures/, frictiondisk/cli/gallery.py) (like
`frictiondisk plot`; size-versus-mu figures get their bisection runs). `--only` names the
campaigns (campaigns/NAME.yaml) instead of the figure campaigns. Printed: the wall time of
each figure's campaign (from the start of the run to its last point), the run's, the
drawing's and the total.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from frictiondisk.engine.runner import run_campaigns
from frictiondisk.tasks.campaign import load_campaign

TRACED = ("trace_fig11_betab_mu.yaml",)  # traced planes shown beside the figures (docs/trace.md)
BOUNDS_FIGURE = "fig11_bounds"  # Fig 11 with both starts and its bounds, when both are run
FIG11 = ("fig11_betab_mu", "fig11_betab_mu_corotating")  # the two starts it draws


def draw_figure(campaign, out_dir: Path, figure_root: Path, formats: list[str]) -> None:
    """Save the figure of the finished campaign in out_dir as FIGURES/<name>.<format>."""
    import matplotlib

    matplotlib.use("Agg")
    from frictiondisk.figures.plotting import save_figure
    from frictiondisk.tasks.plot import figure_for_dir

    # the bisection runs belong to size-versus-mu figures (a converge prescan, Figs 7-8);
    # on a dense jump line they would hide it
    prescan = getattr(campaign.task, "prescan", None)
    show_runs = prescan is not None and prescan.mode == "converge"
    fig = figure_for_dir(out_dir, show_runs=show_runs)
    for suffix in formats:
        save_figure(fig, figure_root / f"{campaign.name}.{suffix}")


def campaign_files(folder: Path, only: list[str] | None) -> list[Path]:
    """The campaign files to run: FOLDER/NAME.yaml of each of `only`, else the figure
    campaigns (fig*.yaml) and the traced planes (TRACED)."""
    if only is not None:
        return [folder / f"{name}.yaml" for name in only]
    files = sorted(folder.glob("fig*.yaml"))
    return files + [folder / name for name in TRACED if (folder / name).is_file()]


def draw_bounds(out: Path, figures: Path, formats: list[str]) -> None:
    """Fig 11 with both starts and the Melan shakedown and collapse bounds, if both ran."""
    rest, corotating = (out / name for name in FIG11)
    if (rest / "results.nc").is_file() and (corotating / "results.nc").is_file():
        from frictiondisk.studies.brake.bounds_figure import main as brake_figure

        for suffix in formats:
            target = figures / f"{BOUNDS_FIGURE}.{suffix}"
            brake_figure([str(rest), str(corotating), "-o", str(target)])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--campaigns", type=Path, default=Path("campaigns"))
    parser.add_argument("--out", type=Path, default=Path("out/figures"))
    parser.add_argument("--figures", type=Path, default=Path("out/figures"))
    parser.add_argument("--only", nargs="+", metavar="NAME", help="campaigns/NAME.yaml only")
    parser.add_argument("--formats", default="png,pdf", help="comma-separated: png, pdf, svg")
    args = parser.parse_args(argv)
    formats = [f.strip() for f in args.formats.split(",") if f.strip()]
    files = campaign_files(args.campaigns, args.only)
    missing = [str(path) for path in files if not path.is_file()]
    if not files or missing:
        print(f"no figure campaigns in {args.campaigns}: {missing}", file=sys.stderr)
        return 2
    total = time.perf_counter()
    campaigns = [load_campaign(path) for path in files]
    # the traces first (TaskEntry.starts_first): the run offers free workers in this order,
    # and a trace has few runs in flight for long (one correction per curve end), so the
    # lines fill round it instead of leaving it alone at the end (docs/benchmarks.md)
    first = sorted(campaigns, key=lambda campaign: not campaign.entry.starts_first)
    ran_first = run_campaigns(first, args.out, workers=2, progress=False)
    summaries = dict(zip((campaign.name for campaign in first), ran_first, strict=True))
    ran = time.perf_counter() - total
    for campaign in campaigns:
        summary = summaries[campaign.name]
        draw_figure(campaign, args.out / campaign.name, args.figures, formats)
        where = f"{args.figures / campaign.name}.{', .'.join(formats)}"
        print(f"{campaign.name:<26} {summary.wall_s:7.1f} s   {where}", flush=True)
    draw_bounds(args.out, args.figures, formats)
    drawn = time.perf_counter() - total - ran
    print(f"{'all campaigns, one run':<26} {ran:7.1f} s")
    print(f"{'drawing the figures':<26} {drawn:7.1f} s")
    print(f"{'all figures':<26} {time.perf_counter() - total:7.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
