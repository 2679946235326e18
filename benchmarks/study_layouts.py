"""Convergence of mu* in the number of contacts N: the braked disk on a ring and on an annulus.

Scene: disk, beta_b = 0.005 N m s/rad, co-rotating start (phidot0 = omega_m), x_ms = 0.1 m,
default numerics (rodas4, rtol 1e-6: integrator error on mu* below 1e-6, frictiondisk/model/scene.py
NUMERICS_PRESETS), t_decide = 30 s; the layouts are the ring of radius 0.05 m (the
paper's) and the clutch-like annulus 0.063 ... 0.087 m (campaigns/clutch_annulus.yaml).
mu* is the LOWEST rising jump: the sticking set in mu need not be an interval (annulus,
N = 768: stick at 0.46-0.47, stick_slip at 0.475, stick from 0.48), so a bisection from a
bracket may meet a higher jump. Each (layout, N) is therefore scanned upwards in steps of
SCAN_STEP from a start that does not stick (the previous N's mu* - SCAN_MARGIN, lowered
until it does not stick) to the first stick, and that bracket is bisected with the
campaigns' rules (frictiondisk/tasks/jump_search/bisection.py, horizon retries included) to `--tol`
(default 1e-4). A stick island narrower than SCAN_STEP below it could be missed.

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
FIRST_START = 0.30  # scan start of the first N
SCAN_STEP = 0.005  # upward scan step in mu
SCAN_MARGIN = 0.02  # the next N's scan starts this far below the previous mu*


def scene(layout: str, n: int):
    from frictiondisk.model.scene import scene_from_dict

    return scene_from_dict(
        {
            "scene": "disk",
            "params": {"beta_b": 0.005, "phidot0": 1.1, "x_ms": 0.1},
            "contact": {**LAYOUTS[layout], "points": n},
            "numerics": {"mode": "decide", "t_decide": 30.0},
        }
    )


def locate(layout: str, n: int, start: float, tol: float) -> dict:
    """Lowest rising jump mu* of one (layout, N): upward scan, then bisection."""
    from frictiondisk.engine.worker import run_bisection
    from frictiondisk.simulation.simulate import simulate
    from frictiondisk.tasks.jump_search.bisection import Bisection

    t0 = time.perf_counter()
    base = scene(layout, n)
    scanned = []

    def sticks(mu):
        res = simulate(base.with_overrides({"params.mu": round(mu, 6)})).summary()
        scanned.append((round(mu, 6), res["outcome"], res["n_steps"], res["n_transitions"]))
        return res["outcome"] == "stick"

    mu = start
    while sticks(mu) and mu > 2 * SCAN_STEP:
        mu -= SCAN_STEP
    while not sticks(mu + SCAN_STEP):
        mu += SCAN_STEP
        if mu > 2.0:
            raise RuntimeError(f"{layout} N={n}: no stick up to mu = 2")
    bracket = (round(mu, 6), round(mu + SCAN_STEP, 6))
    bisection = Bisection(bracket, tol, (1e-6, 10.0), 2)
    bisection, _ = run_bisection(bisection, base.canonical(), 2.0, "/nonexistent")
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
        "scan": scanned,
        "runs": len(runs) + len(scanned),
        "steps": sum(r["n_steps"] for r in runs) + sum(x[2] for x in scanned),
        "events": sum(r["n_transitions"] for r in runs) + sum(x[3] for x in scanned),
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
            start = FIRST_START
            if prev:  # on the scan grid, SCAN_MARGIN below the previous mu*
                start = SCAN_STEP * math.floor((prev[-1]["mu_star"] - SCAN_MARGIN) / SCAN_STEP)
            row = locate(layout, n, start, tol)
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
        unc = max(unc, tol / 2)
        # the smallest N from which every mu*(N) is within 1e-4 of the limit; only
        # meaningful if the limit itself is known to better than 1e-4
        within = [abs(m - limit) <= 1e-4 for m in mus]
        needed = next((n for k, n in enumerate(ns) if all(within[k:])), None)
        if unc > 1e-4 or needed == ns[-1]:
            needed = f"not established (limit known to +- {unc:.5f} only)"
        print(
            f"{layout}: limit mu* = {limit:.5f} +- {unc:.5f} "
            f"(Richardson on N = {ns[-3:]}; +- the last change or the bisection half-width); "
            f"N for |mu*(N) - limit| <= 1e-4: {needed}"
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
