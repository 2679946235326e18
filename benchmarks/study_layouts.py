"""Convergence of mu* in the number of contacts N: the braked disk on a ring and on an annulus.

Scene: disk, beta_b = 0.005 N m s/rad, co-rotating start (phidot0 = omega_m), x_ms = 0.1 m,
default numerics (rodas4, rtol 1e-6: integrator error on mu* below 1e-6, config.py
NUMERICS_PRESETS), t_decide = 30 s; the layouts are the ring of radius 0.05 m (the
paper's) and the clutch-like annulus 0.063 ... 0.087 m (campaigns/clutch_annulus.yaml).
mu* is the rising jump located by the campaigns' bisection (frictiondisk/bisection.py,
horizon retries included) to `--tol` (default 1e-4); each N after the first starts from a
narrow bracket around the previous N's mu* (the bisection widens it if it is wrong).

Reported per layout: mu*(N) with its bracket, the change from the previous N, the
extrapolated limit (Richardson on the last three N, which double: mu*(N) = mu_inf + C N^-p,
p fitted, so mu_inf = m3 - (m3 - m2)^2 / ((m3 - m2) - (m2 - m1))) with the last change as
its uncertainty, and the smallest N whose mu* is within 1e-4 of the limit.

    python benchmarks/study_layouts.py [--ns 12,24,...] [--layouts ring,annulus]
        [--tol 1e-4] [-o out/study_layouts]       (layouts run in parallel processes)

Results are cached per (layout, N) in the output folder as JSON; rerunning continues.
The disk's `stick` rule is what the branch has (issue 9 changes it): rerun after merging.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

NS = (12, 24, 48, 96, 192, 384, 768)
LAYOUTS = {
    "ring": {"layout": "ring", "ring_radius": 0.05},
    "annulus": {"layout": "annulus", "inner_radius": 0.063, "outer_radius": 0.087},
}
FIRST_BRACKET = (0.1, 0.6)
HALF_BRACKET = 0.004  # half-width of the bracket around the previous N's mu*


def scene(layout: str, n: int):
    from frictiondisk.config import scene_from_dict

    return scene_from_dict(
        {
            "scene": "disk",
            "params": {"beta_b": 0.005, "phidot0": 1.1, "x_ms": 0.1},
            "contact": {**LAYOUTS[layout], "points": n},
            "numerics": {"mode": "decide", "t_decide": 30.0},
        }
    )


def locate(layout: str, n: int, bracket, tol: float) -> dict:
    """mu* of one (layout, N) by the campaigns' bisection rules."""
    from frictiondisk.bisection import Bisection
    from frictiondisk.campaign.tasks import run_bisection

    t0 = time.perf_counter()
    bisection = Bisection(tuple(bracket), tol, (1e-6, 10.0), 2)
    bisection, _ = run_bisection(bisection, scene(layout, n).canonical(), 2.0, "/nonexistent")
    res = bisection.result()
    runs = [run.result for run in res.runs]
    return {
        "layout": layout,
        "N": n,
        "status": res.status,
        "reason": res.reason,
        "mu_lo": res.mu_lo,
        "mu_hi": res.mu_hi,
        "mu_star": res.mu_star,
        "monotone": res.monotone,
        "runs": len(runs),
        "steps": sum(r["n_steps"] for r in runs),
        "events": sum(r["n_transitions"] for r in runs),
        "wall_s": time.perf_counter() - t0,
    }


def sweep(layout: str, ns, tol: float, out: Path) -> list[dict]:
    """mu*(N) for one layout, N in increasing order, cached in out/<layout>_<N>.json."""
    rows = []
    for n in ns:
        path = out / f"{layout}_{n}.json"
        if path.exists():
            row = json.loads(path.read_text())
        else:
            prev = [r for r in rows if r["status"] == "converged"]
            if prev:
                mu = prev[-1]["mu_star"]
                bracket = (mu - HALF_BRACKET, mu + HALF_BRACKET)
            else:
                bracket = FIRST_BRACKET
            row = locate(layout, n, bracket, tol)
            path.write_text(json.dumps(row, indent=1))
        print(
            f"{layout:8s} N={n:4d} mu*={row['mu_star']:.5f} [{row['mu_lo']:.5f}, "
            f"{row['mu_hi']:.5f}] {row['status']} runs={row['runs']} wall={row['wall_s']:.0f}s",
            flush=True,
        )
        rows.append(row)
    return rows


def extrapolate(ns, mus):
    """(limit, uncertainty) from the last three of a doubling sequence (module docstring)."""
    if len(mus) < 3:
        return math.nan, math.nan
    m1, m2, m3 = mus[-3:]
    d1, d2 = m2 - m1, m3 - m2
    if d1 == d2 or d2 == 0.0 or d1 * d2 < 0.0 or abs(d2) > abs(d1):
        return m3, abs(d2)  # not in the asymptotic range: the last value, the last change
    return m3 - d2 * d2 / (d2 - d1), abs(d2)


def report(rows_by_layout, tol):
    print("\n| layout | N | mu* | bracket | change from N/2 |")
    print("|---|---|---|---|---|")
    for layout, rows in rows_by_layout.items():
        prev = None
        for r in rows:
            change = "" if prev is None else f"{r['mu_star'] - prev:+.5f}"
            print(
                f"| {layout} | {r['N']} | {r['mu_star']:.5f} | [{r['mu_lo']:.5f}, "
                f"{r['mu_hi']:.5f}] | {change} |"
            )
            prev = r["mu_star"]
    for layout, rows in rows_by_layout.items():
        good = [r for r in rows if r["status"] == "converged"]
        ns = [r["N"] for r in good]
        mus = [r["mu_star"] for r in good]
        limit, unc = extrapolate(ns, mus)
        within = [n for n, m in zip(ns, mus, strict=True) if abs(m - limit) <= 1e-4]
        needed = next(
            (n for k, n in enumerate(ns) if all(w in within for w in ns[k:])),
            None,
        )
        print(
            f"{layout}: limit mu* = {limit:.5f} +- {max(unc, tol / 2):.5f} "
            f"(Richardson on N = {ns[-3:]}; +- the last change or the bisection half-width); "
            f"N for |mu*(N) - limit| <= 1e-4: {needed if needed else 'not reached'}"
        )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ns", default=",".join(map(str, NS)))
    parser.add_argument("--layouts", default=",".join(LAYOUTS))
    parser.add_argument("--tol", type=float, default=1e-4)
    parser.add_argument("-o", "--out", type=Path, default=Path("out/study_layouts"))
    args = parser.parse_args()
    ns = [int(x) for x in args.ns.split(",")]
    layouts = args.layouts.split(",")
    args.out.mkdir(parents=True, exist_ok=True)
    with ProcessPoolExecutor(len(layouts)) as pool:
        futures = {lay: pool.submit(sweep, lay, ns, args.tol, args.out) for lay in layouts}
        rows = {lay: fut.result() for lay, fut in futures.items()}
    report(rows, args.tol)


if __name__ == "__main__":
    main()
