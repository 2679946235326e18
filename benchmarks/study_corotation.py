"""The braked disk from ratcheting to shakedown: master-frame drift per revolution against mu.

    python benchmarks/study_corotation.py [--out figures/brake_drift.png] [--beta-b 0.005]

Runs the disk (12 points on 0.05 m, x_ms = 0.1 m) from rest and from a co-rotating start
over a mu grid around the Melan shakedown bound, each run to its verdict under stick_rule
corotation, and plots the slip, centre drift and spin-phase drift of its last revolution
(log scale) with the outcome as marker, the collapse and shakedown bounds at each run's
radius, and the located boundary. It also prints the decision time of every run: near the
boundary the slip decays or settles slowly and the verdict takes longer.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict import admissibility as ad

STARTS = {"rest": 0.0, "corotating": 1.1}  # phidot0 [rad/s]


def sweep(beta_b: float, mus: np.ndarray, phidot0: float) -> list[dict]:
    rows = []
    for mu in mus:
        scene = {"scene": "disk", "params": {"mu": float(mu), "beta_b": beta_b, "phidot0": phidot0}}
        t0 = time.perf_counter()
        run = simulate(scene_from_dict(scene))
        radius = run.R1 if math.isfinite(run.R1) else math.nan
        case = ad.LoadCase(R=radius, beta_b=beta_b) if math.isfinite(radius) else None
        points = ad.ring_points(12, 0.05)
        rows.append(
            {
                "mu": float(mu),
                "outcome": run.outcome,
                "t_end": run.t_end,
                "wall": time.perf_counter() - t0,
                "slip": run.slip_per_rev,
                "drift": run.drift_per_rev,
                "spin": abs(run.spin_drift_per_rev) * 0.05,
                "shakedown": ad.shakedown_demand(case, points) if case else math.nan,
                "collapse": ad.collapse_demand(case, points) if case else math.nan,
            }
        )
        r = rows[-1]
        print(
            f"  mu = {r['mu']:.4f}  {r['outcome']:<12} decided at t = {r['t_end']:7.1f} s "
            f"({r['wall']:.2f} s wall)  slip {r['slip']:.2e} m/rev  shakedown {r['shakedown']:.4f}",
            flush=True,
        )
    return rows


def boundary(rows: list[dict]) -> tuple[float, float]:
    """(largest not-stick mu below the first stick, first stick mu) of a sweep."""
    sticks = [r["mu"] for r in rows if r["outcome"] == "stick"]
    if not sticks:
        return math.nan, math.nan
    first = min(sticks)
    below = [r["mu"] for r in rows if r["mu"] < first and r["outcome"] != "undetermined"]
    return (max(below) if below else math.nan), first


def plot(results: dict[str, list[dict]], beta_b: float, out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from frictiondisk.figures.plotting import save_figure

    fig, axes = plt.subplots(1, len(results), figsize=(6.2 * len(results), 4.6), sharey=True)
    markers = {"stick": "o", "creep": "D", "stick_slip": "s", "slide": "v", "undetermined": "x"}
    for ax, (name, rows) in zip(np.atleast_1d(axes), results.items(), strict=True):
        mu = np.array([r["mu"] for r in rows])
        for key, color, label in (
            ("slip", "#1f4e79", "net slip per revolution [m]"),
            ("drift", "#c0504d", "centre drift per revolution [m]"),
            ("spin", "#70ad47", "spin-phase drift per revolution \u00d7 \u03c1 [m]"),
        ):
            values = np.array([r[key] for r in rows])
            ax.plot(mu, np.where(values > 0, values, np.nan), color=color, lw=0.8, label=label)
            for outcome, marker in markers.items():
                sel = np.array([r["outcome"] == outcome for r in rows]) & (values > 0)
                ax.scatter(mu[sel], values[sel], marker=marker, s=14, color=color)
        for outcome, marker in markers.items():
            if any(r["outcome"] == outcome for r in rows):
                ax.scatter([], [], marker=marker, color="0.3", label=outcome)
        shake = np.nanmedian([r["shakedown"] for r in rows])
        coll = np.nanmedian([r["collapse"] for r in rows])
        ax.axvline(shake, color="0.2", ls="--", lw=1, label=f"Melan shakedown bound {shake:.4f}")
        ax.axvline(coll, color="0.2", ls=":", lw=1, label=f"collapse bound {coll:.4f}")
        lo, hi = boundary(rows)
        ax.axvspan(lo, hi, color="#ffd966", alpha=0.5, label=f"jump: [{lo:.4f}, {hi:.4f}]")
        ax.set_yscale("log")
        ax.set_xlabel("friction coefficient \u03bc [1]")
        ax.set_title(f"braked disk \u03b2_b = {beta_b} N m s/rad, start: {name}")
        ax.grid(alpha=0.3, which="both")
    np.atleast_1d(axes)[0].set_ylabel("per master revolution, last revolution [m]")
    np.atleast_1d(axes)[0].legend(fontsize=6.5, loc="lower left")
    fig.tight_layout()
    print(f"figure: {save_figure(fig, out)}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("figures/brake_drift.png"))
    parser.add_argument("--beta-b", type=float, default=0.005)
    parser.add_argument("--mu", type=str, default="0.18,0.26,0.0025", help="start,stop,step")
    args = parser.parse_args(argv)
    start, stop, step = (float(v) for v in args.mu.split(","))
    mus = np.arange(start, stop + 0.5 * step, step)
    results = {}
    for name, phidot0 in STARTS.items():
        print(f"start: {name}", flush=True)
        results[name] = sweep(args.beta_b, mus, phidot0)
        lo, hi = boundary(results[name])
        print(f"  jump between mu = {lo:.4f} (not stick) and {hi:.4f} (stick)")
    plot(results, args.beta_b, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
