"""`make figures`: run every figure campaign (campaigns/fig*.yaml, and the traced Fig 11)
and draw its figure.

    python -m frictiondisk.cli.gallery [--campaigns campaigns] [--out out/figures] [--figures out/figures]

The campaigns run together, in one process on one set of workers (run_campaigns: each
into OUT/<name>/, resuming whatever is already there, like `frictiondisk run A.yaml
B.yaml -o OUT`). Then each figure is written as FIGURES/<name>.png and .pdf from the
netCDF files alone (by default under the ignored out/, so the tracked tree stays clean;
`make gallery` copies the PNGs into figures/, the gallery of docs/user-guide.md) (like
`frictiondisk plot`; size-versus-mu figures get their bisection runs). Printed: the wall
time of each figure's campaign (from the start of the run to its last point), the run's,
the drawing's and the total.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from frictiondisk.engine.runner import run_campaigns
from frictiondisk.tasks.campaign import load_campaign

TRACED = ("trace_fig11_betab_mu.yaml",)  # traced planes shown beside the figures (docs/trace.md)


def draw_figure(campaign, out_dir: Path, figure_root: Path) -> None:
    """Save the figure of the finished campaign in out_dir as FIGURES/<name>.png, .pdf."""
    import matplotlib

    matplotlib.use("Agg")
    from frictiondisk.figures.plotting import save_figure
    from frictiondisk.tasks.plot import figure_for_dir

    # the bisection runs belong to size-versus-mu figures (a converge prescan, Figs 7-8);
    # on a dense jump line they would hide it
    prescan = getattr(campaign.task, "prescan", None)
    show_runs = prescan is not None and prescan.mode == "converge"
    fig = figure_for_dir(out_dir, show_runs=show_runs)
    for suffix in (".png", ".pdf"):
        save_figure(fig, figure_root / f"{campaign.name}{suffix}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--campaigns", type=Path, default=Path("campaigns"))
    parser.add_argument("--out", type=Path, default=Path("out/figures"))
    parser.add_argument("--figures", type=Path, default=Path("out/figures"))
    args = parser.parse_args(argv)
    files = sorted(args.campaigns.glob("fig*.yaml"))
    files += [args.campaigns / name for name in TRACED if (args.campaigns / name).is_file()]
    if not files:
        print(f"no figure campaigns (fig*.yaml) in {args.campaigns}", file=sys.stderr)
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
        draw_figure(campaign, args.out / campaign.name, args.figures)
        where = f"{args.figures / campaign.name}.png, .pdf"
        print(f"{campaign.name:<26} {summary.wall_s:7.1f} s   {where}", flush=True)
    rest, corotating = args.out / "fig11_betab_mu", args.out / "fig11_betab_mu_corotating"
    if (rest / "results.nc").is_file() and (corotating / "results.nc").is_file():
        # Fig 11 with both starts and the Melan shakedown and collapse bounds
        from frictiondisk.tasks.find_jump.brake_figure import main as brake_figure

        for suffix in (".png", ".pdf"):
            brake_figure(
                [str(rest), str(corotating), "-o", str(args.figures / f"fig11_bounds{suffix}")]
            )
    drawn = time.perf_counter() - total - ran
    print(f"{'all campaigns, one run':<26} {ran:7.1f} s")
    print(f"{'drawing the figures':<26} {drawn:7.1f} s")
    print(f"{'all figures':<26} {time.perf_counter() - total:7.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
