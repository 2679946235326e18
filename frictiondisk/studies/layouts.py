"""Convergence of mu* in the number of contacts N: the braked disk on a ring and on an annulus.

Scene: disk, beta_b = 0.005 N m s/rad, co-rotating start (phidot0 = omega_m), x_ms = 0.1 m,
default numerics (rodas4, rtol 1e-6: integrator error on mu* below 1e-6, frictiondisk/model/
scene.py NUMERICS_PRESETS), t_decide = 30 s; the layouts are the ring of radius 0.05 m (the
paper's) and the clutch-like annulus 0.063 ... 0.087 m (campaigns/clutch_annulus.yaml).
mu* is the LOWEST rising jump: the sticking set in mu need not be an interval (annulus,
N = 768 under the old contacts rule: stick at 0.46-0.47, stick_slip at 0.475, stick from
0.48), so each (layout, N) is a find_jump campaign with a prescan of mu = PRESCAN (step
0.005, adaptive), every change bisected to `--tol` (default 1e-4) without certification,
and its headline, the lowest rising jump that persists, is mu*(N). All of them run on the
engine together into OUT/<name>/ (resumable). A sticking island narrower than the prescan
step could be missed where the adaptive prescan skips it above the headline.

Reported per layout: mu*(N) with its bracket, the change from the previous N, the
extrapolated limit (Richardson on the last three N, which double: mu*(N) = mu_inf + C N^-p,
p fitted, so mu_inf = m3 - (m3 - m2)^2 / ((m3 - m2) - (m2 - m1))) with the last change as
its uncertainty, and the smallest N whose mu* is within 1e-4 of the limit.

    python -m frictiondisk.studies.layouts [--ns 12,24,...] [--layouts ring,annulus]
        [--tol 1e-4] [-o out/study_layouts]
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from frictiondisk.studies import campaigns

NS = (12, 24, 48, 96, 192, 384, 768)
LAYOUTS = {
    "ring": {"layout": "ring", "ring_radius": 0.05},
    "annulus": {"layout": "annulus", "inner_radius": 0.063, "outer_radius": 0.087},
}
PRESCAN = tuple(round(0.10 + 0.005 * k, 4) for k in range(61))  # mu = 0.10 ... 0.40
NUMERICS = {"mode": "decide", "t_decide": 30.0, "rtol": 1e-6, "atol": 1e-9}


def layout_campaign(layout: str, n: int, tol: float) -> dict:
    """The find_jump campaign of one (layout, N)."""
    return {
        "name": f"{layout}-N{n}-tol{campaigns.name_part(tol)}",
        "scene": "disk",
        "params": {"beta_b": 0.005, "phidot0": 1.1},
        "contact": {**LAYOUTS[layout], "points": n},
        "numerics": NUMERICS,
        "find_jump": {
            "tol": tol,
            "along": {"params.x_ms": [0.1]},
            "prescan": {"mu": list(PRESCAN)},
            "certify": False,
        },
    }


def located(folder: Path, layout: str, n: int) -> dict:
    """mu*(N) of a finished campaign, its bracket and what it cost."""
    res, runs = campaigns.results(folder), campaigns.results(folder, "runs")
    mu_lo, mu_hi = float(res.mu_lo.values[0]), float(res.mu_hi.values[0])
    return {
        "layout": layout,
        "N": n,
        "status": str(res.status.values[0]),
        "reason": str(res.reason.values[0]),
        "mu_lo": mu_lo,
        "mu_hi": mu_hi,
        "mu_star": 0.5 * (mu_lo + mu_hi),
        "runs": int(runs.sizes["run"]),
        "steps": int(np.nansum(runs.n_steps.values)),
        "wall_s": float(np.nansum(runs.wall_s.values)),
    }


def extrapolate(mus: list[float]) -> tuple[float, float]:
    """(limit, uncertainty) from the last three of a doubling sequence (module docstring)."""
    if len(mus) < 3:
        return math.nan, math.nan
    m1, m2, m3 = mus[-3:]
    d1, d2 = m2 - m1, m3 - m2
    if d1 == d2 or d2 == 0.0 or d1 * d2 < 0.0 or abs(d2) > abs(d1):
        return m3, abs(d2)  # not in the asymptotic range: the last value, the last change
    return m3 - d2 * d2 / (d2 - d1), abs(d2)


def report(rows_by_layout: dict[str, list[dict]], tol: float) -> list[str]:
    """The mu*(N) table and each layout's limit."""
    lines = ["| layout | N | mu* | bracket | change from N/2 |", "|---|---|---|---|---|"]
    for layout, rows in rows_by_layout.items():
        prev = None
        for r in rows:
            change = "" if prev is None else f"{r['mu_star'] - prev:+.5f}"
            lines.append(
                f"| {layout} | {r['N']} | {r['mu_star']:.5f} | [{r['mu_lo']:.5f}, "
                f"{r['mu_hi']:.5f}] | {change} |"
            )
            prev = r["mu_star"]
    for layout, rows in rows_by_layout.items():
        good = [r for r in rows if r["status"] == "converged"]
        ns = [r["N"] for r in good]
        mus = [r["mu_star"] for r in good]
        limit, unc = extrapolate(mus)
        unc = max(unc, tol / 2)
        # the smallest N from which every mu*(N) is within 1e-4 of the limit; only
        # meaningful if the limit itself is known to better than 1e-4
        within = [abs(m - limit) <= 1e-4 for m in mus]
        needed = next((n for k, n in enumerate(ns) if all(within[k:])), None)
        if unc > 1e-4 or needed == ns[-1]:
            needed = f"not established (limit known to +- {unc:.5f} only)"
        lines.append(
            f"{layout}: limit mu* = {limit:.5f} +- {unc:.5f} "
            f"(Richardson on N = {ns[-3:]}; +- the last change or the bisection half-width); "
            f"N for |mu*(N) - limit| <= 1e-4: {needed}"
        )
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m frictiondisk.studies.layouts", description=__doc__.splitlines()[0]
    )
    parser.add_argument("--ns", default=",".join(map(str, NS)))
    parser.add_argument("--layouts", default=",".join(LAYOUTS))
    parser.add_argument("--tol", type=float, default=1e-4)
    parser.add_argument("-o", "--out", type=Path, default=Path("out/study_layouts"))
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    ns = [int(x) for x in args.ns.split(",")]
    layouts = args.layouts.split(",")
    plan = {(lay, n): layout_campaign(lay, n, args.tol) for lay in layouts for n in ns}
    campaigns.run(plan.values(), args.out, args.workers)
    rows = {
        lay: [located(args.out / plan[(lay, n)]["name"], lay, n) for n in ns] for lay in layouts
    }
    for row in (r for by in rows.values() for r in by):
        print(
            f"{row['layout']:8s} N={row['N']:4d} mu*={row['mu_star']:.5f} [{row['mu_lo']:.5f}, "
            f"{row['mu_hi']:.5f}] {row['status']} runs={row['runs']} kernel={row['wall_s']:.0f}s"
        )
    print("\n".join(report(rows, args.tol)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
