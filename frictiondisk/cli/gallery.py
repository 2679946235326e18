"""`make figures`: run every figure campaign (campaigns/fig*.yaml, and the traced Fig 11)
and draw its figure.

    python -m frictiondisk.cli.gallery [--campaigns campaigns] [--out out/figures] [--figures out/figures]

Each campaign runs into OUT/<name> (resuming whatever is already there, like
`frictiondisk run`), and its figure is written as FIGURES/<name>.png and .pdf from the
netCDF files alone (by default under the ignored out/, so the tracked tree stays clean;
`make gallery` copies the PNGs into figures/, the gallery of docs/user-guide.md) (like `frictiondisk plot`; size-versus-mu figures get their bisection
runs). The wall time of each figure is printed, and the total.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from frictiondisk.engine.runner import run_campaign
from frictiondisk.model.campaign import load_campaign

TRACED = ("trace_fig11_betab_mu.yaml",)  # traced planes shown beside the figures (docs/trace.md)


def make_figure(campaign_file: Path, out_root: Path, figure_root: Path) -> tuple[str, float]:
    """Run one campaign and save its figure; returns (name, wall time [s])."""
    import matplotlib

    matplotlib.use("Agg")
    from frictiondisk.cli.plot import figure_for_dir
    from frictiondisk.figures.plotting import save_figure

    t0 = time.perf_counter()
    campaign = load_campaign(campaign_file)
    out_dir = out_root / campaign.name
    run_campaign(campaign, out_dir, workers=2, progress=False)
    # the bisection runs belong to size-versus-mu figures (a converge prescan, Figs 7-8);
    # on a dense jump line they would hide it
    prescan = getattr(campaign.task, "prescan", None)
    show_runs = prescan is not None and prescan.mode == "converge"
    fig = figure_for_dir(out_dir, show_runs=show_runs)
    for suffix in (".png", ".pdf"):
        save_figure(fig, figure_root / f"{campaign.name}{suffix}")
    return campaign.name, time.perf_counter() - t0


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
    for path in files:
        name, wall = make_figure(path, args.out, args.figures)
        print(f"{name:<24} {wall:7.1f} s   {args.figures / name}.png, .pdf", flush=True)
    rest, corotating = args.out / "fig11_betab_mu", args.out / "fig11_betab_mu_corotating"
    if (rest / "results.nc").is_file() and (corotating / "results.nc").is_file():
        # Fig 11 with both starts and the Melan shakedown and collapse bounds
        from frictiondisk.figures.brake import main as brake_figure

        for suffix in (".png", ".pdf"):
            brake_figure(
                [str(rest), str(corotating), "-o", str(args.figures / f"fig11_bounds{suffix}")]
            )
    print(f"{'all figures':<24} {time.perf_counter() - total:7.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
