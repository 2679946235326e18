"""The braked disk from ratcheting to shakedown: master-frame drift per revolution against mu.

    python -m frictiondisk.studies.corotation [-o out/corotation] [--figure figures/brake_drift.png]
        [--beta-b 0.005] [--mu 0.18,0.26,0.0025]

Runs the disk (12 points on 0.05 m, x_ms = 0.1 m) from rest and from a co-rotating start
over a mu grid around the Melan shakedown bound, each run to its verdict under stick_rule
corotation: one scan campaign per start (mode decide), run on the engine into OUT/<name>/
(resumable). Plots the slip, centre drift and spin-phase drift of each run's last
revolution (log scale) with the outcome as marker, the collapse and shakedown bounds at
each run's radius, and the located boundary; prints the decision time of every run: near
the boundary the slip decays or settles slowly and the verdict takes longer.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from frictiondisk.studies import campaigns
from frictiondisk.verdict import admissibility as ad
from frictiondisk.verdict import outcomes

STARTS = {"rest": 0.0, "corotating": 1.1}  # phidot0 [rad/s]
RING = (12, 0.05)  # contact points, ring radius [m] (the default layout)


def sweep_campaign(beta_b: float, mus: np.ndarray, start: str) -> dict:
    """The scan of one start: the default disk with beta_b and phidot0 over `mus`."""
    return {
        "name": f"corotation-{start}-beta{campaigns.name_part(beta_b)}",
        "scene": "disk",
        "params": {"beta_b": beta_b, "phidot0": STARTS[start]},
        "scan": {"mu": [float(mu) for mu in mus], "mode": "decide"},
    }


def sweep_rows(folder: Path, beta_b: float) -> list[dict]:
    """One dict per run of a finished scan: outcome, decision time, the last revolution's
    rates and the bounds at the run's first sticking radius."""
    runs = campaigns.results(folder, "runs")
    points = ad.ring_points(*RING)
    rows = []
    for k in range(runs.sizes["run"]):
        radius = float(runs.R1.values[k])
        case = ad.LoadCase(R=radius, beta_b=beta_b) if math.isfinite(radius) else None
        rows.append(
            {
                "mu": float(runs.mu.values[k]),
                "outcome": str(runs.outcome.values[k]),
                "t_end": float(runs.t_end.values[k]),
                "wall": float(runs.wall_s.values[k]),
                "slip": float(runs.slip_per_rev.values[k]),
                "drift": float(runs.drift_per_rev.values[k]),
                "spin": abs(float(runs.spin_drift_per_rev.values[k])) * RING[1],
                "shakedown": ad.shakedown_demand(case, points) if case else math.nan,
                "collapse": ad.collapse_demand(case, points) if case else math.nan,
            }
        )
    return sorted(rows, key=lambda r: r["mu"])


def boundary(rows: list[dict]) -> tuple[float, float]:
    """(largest not-stick mu below the first stick, first stick mu) of a sweep."""
    sticks = [r["mu"] for r in rows if outcomes.is_stick(r["outcome"])]
    if not sticks:
        return math.nan, math.nan
    first = min(sticks)
    below = [
        r["mu"]
        for r in rows
        if r["mu"] < first and outcomes.outcome_class(r["outcome"]) != outcomes.UNDETERMINED
    ]
    return (max(below) if below else math.nan), first


def plot(results: dict[str, list[dict]], beta_b: float, out: Path) -> Path:
    """The drift figure: one panel per start."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from frictiondisk.figures.footer import add_footer, code_footer
    from frictiondisk.figures.plotting import save_figure

    fig, axes = plt.subplots(1, len(results), figsize=(6.2 * len(results), 4.6), sharey=True)
    for ax, (name, rows) in zip(np.atleast_1d(axes), results.items(), strict=True):
        draw_sweep(ax, rows)
        ax.set_title(f"braked disk \u03b2_b = {beta_b} N m s/rad, start: {name}")
    np.atleast_1d(axes)[0].set_ylabel("per master revolution, last revolution [m]")
    np.atleast_1d(axes)[0].legend(fontsize=6.5, loc="lower left")
    # this code's numerics: the scans resume only runs journaled under them
    add_footer(fig, code_footer("python -m frictiondisk.studies.corotation"))
    return save_figure(fig, out)


def _outcome_look(outcome: outcomes.Outcome, rate_color: str) -> dict:
    """A run's marker: its outcome's marker and face colour (the outcome records), edged in
    the colour of the rate it marks (an unfilled marker such as x: in the outcome's)."""
    if outcome.marker in ("x", "+", "|", "_"):
        return {"marker": outcome.marker, "color": outcome.color}
    return {"marker": outcome.marker, "facecolors": outcome.color, "edgecolors": rate_color}


def draw_sweep(ax, rows: list[dict]) -> None:
    """The three rates against mu, markers by outcome (every outcome of the records), the
    bounds and the jump."""
    mu = np.array([r["mu"] for r in rows])
    for key, color, label in (
        ("slip", "#1f4e79", "net slip per revolution [m]"),
        ("drift", "#c0504d", "centre drift per revolution [m]"),
        ("spin", "#70ad47", "spin-phase drift per revolution \u00d7 \u03c1 [m]"),
    ):
        values = np.array([r[key] for r in rows])
        ax.plot(mu, np.where(values > 0, values, np.nan), color=color, lw=0.8, label=label)
        for outcome in outcomes.RECORDS:
            sel = np.array([r["outcome"] == outcome.name for r in rows]) & (values > 0)
            look = _outcome_look(outcome, color)
            ax.scatter(mu[sel], values[sel], s=16, linewidths=0.8, **look)
    for outcome in outcomes.RECORDS:
        if any(r["outcome"] == outcome.name for r in rows):
            look = _outcome_look(outcome, "0.3")
            ax.scatter([], [], linewidths=0.8, label=outcome.legend, **look)
    shake = np.nanmedian([r["shakedown"] for r in rows])
    coll = np.nanmedian([r["collapse"] for r in rows])
    ax.axvline(shake, color="0.2", ls="--", lw=1, label=f"Melan shakedown bound {shake:.4f}")
    ax.axvline(coll, color="0.2", ls=":", lw=1, label=f"collapse bound {coll:.4f}")
    lo, hi = boundary(rows)
    ax.axvspan(lo, hi, color="#ffd966", alpha=0.5, label=f"jump: [{lo:.4f}, {hi:.4f}]")
    ax.set_yscale("log")
    ax.set_xlabel("friction coefficient \u03bc [1]")
    ax.grid(alpha=0.3, which="both")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m frictiondisk.studies.corotation", description=__doc__.splitlines()[0]
    )
    parser.add_argument("-o", "--out", type=Path, default=Path("out/corotation"))
    parser.add_argument("--figure", type=Path, default=Path("figures/brake_drift.png"))
    parser.add_argument("--beta-b", type=float, default=0.005)
    parser.add_argument("--mu", type=str, default="0.18,0.26,0.0025", help="start,stop,step")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    start, stop, step = (float(v) for v in args.mu.split(","))
    mus = np.arange(start, stop + 0.5 * step, step)
    scans = {name: sweep_campaign(args.beta_b, mus, name) for name in STARTS}
    campaigns.run(scans.values(), args.out, args.workers)
    results = {}
    for name, scan in scans.items():
        results[name] = sweep_rows(args.out / scan["name"], args.beta_b)
        print(f"start: {name}")
        for r in results[name]:
            print(
                f"  mu = {r['mu']:.4f}  {r['outcome']:<12} decided at t = {r['t_end']:7.1f} s "
                f"({r['wall']:.2f} s wall)  slip {r['slip']:.2e} m/rev  "
                f"shakedown {r['shakedown']:.4f}"
            )
        lo, hi = boundary(results[name])
        print(f"  jump between mu = {lo:.4f} (not stick) and {hi:.4f} (stick)")
    print(f"figure: {plot(results, args.beta_b, args.figure)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
