"""Fig 11 with its oracles: mu*(beta_b) from rest and from a co-rotating start, with the
Melan shakedown and collapse bounds at each run's orbit radius.

    python -m frictiondisk.studies.brake.bounds_figure REST_DIR [COROTATING_DIR] -o fig.png

Each DIR holds a finished find_jump campaign along params.beta_b (results.nc). The bounds
come from frictiondisk.verdict.admissibility at the radius of the sticking run at mu_hi (`size_hi`,
else its first sticking radius `R1_hi`), for the campaign's ring of contacts. The collapse
bound is never read by the classifier; the shakedown bound decides a braked disk on its
small orbit (frictiondisk/verdict/shakedown_verdict.py, at the disk's own layout angle), so
there its agreement with mu* is by construction and the watching runs are the check.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from frictiondisk.figures.footer import add_footer, data_footer
from frictiondisk.figures.shared import MU_LABEL
from frictiondisk.figures.style import styled
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.verdict import admissibility as ad

SERIES_STYLE = {
    "rest": {"color": "#1f4e79", "marker": "o", "label": "\u03bc* from rest (\u03c6\u03070 = 0)"},
    "corotating": {
        "color": "#c0504d",
        "marker": "s",
        "label": "\u03bc* from a co-rotating start (\u03c6\u03070 = \u03c9_m)",
    },
}


def bounds_for(results: xr.Dataset) -> dict[str, np.ndarray]:
    """Collapse and Melan shakedown demands on mu (mu F_n / F_n) at each point's orbit radius."""
    campaign = campaign_from_text(results.attrs["campaign_yaml"], "results.nc campaign_yaml")
    scene = campaign.points()[0].config
    par = scene.params
    points = scene.contact_positions()
    radius = np.where(
        np.isfinite(results["size_hi"].values), results["size_hi"].values, results["R1_hi"].values
    )
    out = {"collapse": [], "shakedown": [], "radius": radius}
    for beta_b, r in zip(results["beta_b"].values, radius, strict=True):
        if not math.isfinite(r):
            out["collapse"].append(math.nan)
            out["shakedown"].append(math.nan)
            continue
        case = ad.LoadCase.of(par, r, beta_b)
        out["collapse"].append(ad.collapse_demand(case, points) / par.F_n)
        out["shakedown"].append(ad.shakedown_demand(case, points) / par.F_n)
    return {key: np.asarray(values, dtype=float) for key, values in out.items()}


@styled
def plot_brake(series: dict[str, xr.Dataset]):
    """The figure: mu* with its bracket for every series, and both bounds of the first."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.0, 6.4), layout="constrained")
    ax, ax_gap = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1.3]})
    for name, results in series.items():
        style = SERIES_STYLE[name]
        beta_b = results["beta_b"].values
        lo, hi = results["mu_lo"].values, results["mu_hi"].values
        mid = 0.5 * (lo + hi)
        ax.errorbar(
            beta_b,
            mid,
            yerr=0.5 * (hi - lo),
            color=style["color"],
            marker=style["marker"],
            ms=4,
            lw=1.2,
            capsize=2,
            label=style["label"],
        )
        bounds = bounds_for(results)
        for key, ls in (("shakedown", "--"), ("collapse", ":")):
            ax.plot(
                beta_b,
                bounds[key],
                ls=ls,
                color=style["color"],
                lw=1.0,
                alpha=0.8,
                label=f"{key} bound at that run's radius ({name})",
            )
        ax_gap.plot(
            beta_b,
            mid - bounds["shakedown"],
            color=style["color"],
            marker=style["marker"],
            ms=4,
            lw=1.0,
            label=name,
        )
    ax.set_ylabel(MU_LABEL)
    ax.set_title("Fig 11: jump \u03bc* against the brake damping \u03b2_b (disk, x_ms = 0.1 m)")
    ax.legend(loc="upper left")
    ax_gap.axhline(0.0, color="0.3", lw=0.8)
    ax_gap.set_ylabel("\u03bc* \u2212 shakedown [-]")
    ax_gap.set_xlabel("brake damping \u03b2_b [N m s/rad]")
    names = ", ".join(str(r.attrs.get("campaign_name", "?")) for r in series.values())
    add_footer(fig, data_footer(f"Fig 11 with its bounds, campaigns {names}", series.values()))
    return fig


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("rest", type=Path, help="campaign DIR of the disk from rest")
    parser.add_argument("corotating", type=Path, nargs="?", help="DIR of the co-rotating start")
    parser.add_argument("-o", "--output", type=Path, required=True)
    args = parser.parse_args(argv)
    import matplotlib

    matplotlib.use("Agg")
    from frictiondisk.figures.plotting import save_figure

    series = {"rest": xr.load_dataset(args.rest / "results.nc")}
    if args.corotating is not None:
        series["corotating"] = xr.load_dataset(args.corotating / "results.nc")
    for name, results in series.items():
        bounds = bounds_for(results)
        gap = 0.5 * (results["mu_lo"].values + results["mu_hi"].values) - bounds["shakedown"]
        print(f"{name}: beta_b, mu_lo, mu_hi, collapse, shakedown, mu* - shakedown")
        for row in zip(
            results["beta_b"].values,
            results["mu_lo"].values,
            results["mu_hi"].values,
            bounds["collapse"],
            bounds["shakedown"],
            gap,
            strict=True,
        ):
            print("  " + "  ".join(f"{v:.5f}" for v in row))
    written = save_figure(plot_brake(series), args.output)
    print(f"figure: {written}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
