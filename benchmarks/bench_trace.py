"""Traced planes against the line campaigns of the same figures (issue 31).

For each figure both campaigns run here, 2 workers, into fresh directories: the line
campaign (campaigns/figNN_*.yaml: a prescan and a certified bisection of mu at each of its
points) and its trace (campaigns/trace_figNN_*.yaml: a first look, then the curve followed
through the plane). Printed for each:

* runs and wall time of both, and their ratios (trace / line);
* how far the traced curve lies from the line's mu* at the line's keys, in units of tol
  (mu interpolated linearly along the traced curve between its two points around the key);
* where the traced points are: per interval between two of the line's keys, how much
  the curve turns over it (the angle between the traced curve's directions at the
  interval's two ends, in coordinates scaled by the plane's ranges) and how many traced
  points lie in it: the trace places more points where the curve bends.

    python benchmarks/bench_trace.py            # Fig 11 from rest (about 7 minutes)
    python benchmarks/bench_trace.py --all      # Figs 9, 10, 11 and 11 co-rotating
"""

from __future__ import annotations

import argparse
import math
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr
from harness import Record

from frictiondisk.engine.runner import run_campaign
from frictiondisk.engine.worker import warm_up
from frictiondisk.tasks.campaign import load_campaign

ROOT = Path(__file__).resolve().parent.parent
PAIRS = {  # figure -> (line campaign, trace campaign)
    "fig11": ("fig11_betab_mu", "trace_fig11_betab_mu"),
    "fig11_corotating": ("fig11_betab_mu_corotating", "trace_fig11_betab_mu_corotating"),
    "fig09": ("fig09_disk_xms", "trace_fig09_disk_xms"),
    "fig10": ("fig10_disk_x0", "trace_fig10_disk_x0"),
}


def run(name: str, out: Path) -> tuple[xr.Dataset, int, float]:
    """Run campaigns/<name>.yaml into out/<name>: (results, runs, wall time [s])."""
    campaign = load_campaign(ROOT / "campaigns" / f"{name}.yaml")
    t0 = time.perf_counter()
    summary = run_campaign(campaign, out / name, workers=2, progress=False)
    wall = time.perf_counter() - t0
    with xr.open_dataset(summary.results) as ds:
        return ds.load(), summary.runs_total, wall


def directions(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Unit directions of the segments of a polyline."""
    d = np.column_stack([np.diff(x), np.diff(y)])
    return d / np.hypot(d[:, 0], d[:, 1])[:, None]


def compare(figure: str, out: Path, record: Record) -> None:
    line_name, trace_name = PAIRS[figure]
    line, line_runs, line_wall = run(line_name, out)
    trace, trace_runs, trace_wall = run(trace_name, out)
    tol = float(trace.attrs["tol"])
    name = str(trace.attrs["trace_key_var"])
    key_lo, key_hi = (float(v) for v in trace.attrs["key_range"])
    mu_lo, mu_hi = (float(v) for v in trace.attrs["mu_range"])
    if trace.sizes["curve"] != 1:
        print(f"{figure}: the trace has {trace.sizes['curve']} curves; compared: its first")
    start = int(trace["curve_first_point"][0])
    stop = start + int(trace["curve_points"][0])
    key = trace[name].values[start:stop]
    mu = trace["mu_star"].values[start:stop]
    order = np.argsort(key)
    key, mu = key[order], mu[order]
    line_key = line[name].values
    line_mu = line["mu_star"].values
    traced = np.interp(line_key, key, mu)
    off = np.abs(traced - line_mu) / tol
    # where the line's bracket is wider than tol (it straddles mu that stayed undecided),
    # its midpoint is known only to half its width: the distance to the bracket says more
    below, above = line["mu_lo"].values - traced, traced - line["mu_hi"].values
    outside = np.maximum(0.0, np.maximum(below, above)) / tol
    wide = (line["mu_hi"].values - line["mu_lo"].values) > tol * (1 + 1e-6)

    print(f"\n{figure}: {line_name} ({line.sizes[name]} points) against {trace_name}, tol {tol:g}")
    print(f"  {'':22s} {'line':>10s} {'trace':>10s} {'trace/line':>11s}")
    print(f"  {'runs':22s} {line_runs:10d} {trace_runs:10d} {trace_runs / line_runs:11.2f}")
    print(f"  {'wall [s]':22s} {line_wall:10.1f} {trace_wall:10.1f} {trace_wall / line_wall:11.2f}")
    print(f"  {'points':22s} {line.sizes[name]:10d} {len(key):10d}")
    record.ratio(f"{figure}: runs, trace over line", trace_runs, line_runs)
    record.ratio(f"{figure}: wall, trace over line", trace_wall, line_wall)
    record.number(f"{figure}: traced mu* off the line's, at most", off.max(), "tol", "<= 2")
    print(
        f"  traced mu* at the line's keys: max {off.max():.2f} tol, mean {off.mean():.2f} tol "
        f"off the line's mu* ({int((off <= 2).sum())} of {off.size} within 2 tol)"
    )
    if wide.any():
        print(
            f"  {int(wide.sum())} line brackets are wider than tol (straddling undecided mu, "
            f"up to {(line['mu_hi'] - line['mu_lo']).values.max() / tol:.1f} tol); the traced "
            f"curve lies at most {outside.max():.2f} tol outside the line's brackets"
        )
    x = (key - key_lo) / (key_hi - key_lo)
    y = (mu - mu_lo) / (mu_hi - mu_lo)
    d = directions(x, y)
    mids = 0.5 * (x[1:] + x[:-1])
    edges = (line_key - key_lo) / (key_hi - key_lo)
    print(f"  {'interval of ' + name:28s} {'turn [deg]':>10s} {'traced points':>14s}")
    turns, counts = [], []
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        t0 = d[np.argmin(np.abs(mids - a))]
        t1 = d[np.argmin(np.abs(mids - b))]
        turn = math.degrees(math.acos(max(-1.0, min(1.0, float(t0 @ t1)))))
        inside = int(((x > a) & (x <= b)).sum())
        turns.append(turn)
        counts.append(inside)
        k0, k1 = key_lo + a * (key_hi - key_lo), key_lo + b * (key_hi - key_lo)
        print(
            f"  [{k0:.5g}, {k1:.5g}]{'':{max(0, 12 - len(f'{k0:.5g}{k1:.5g}'))}s} {turn:10.2f} {inside:14d}"
        )
    turns, counts = np.asarray(turns), np.asarray(counts)
    bent = turns >= np.median(turns)
    print(
        f"  traced points per interval: {counts[bent].mean():.2f} where the curve turns most "
        f"(half of the intervals, turn >= {np.median(turns):.2f} deg), {counts[~bent].mean():.2f} "
        "elsewhere; the line: 1 everywhere"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--all", action="store_true", help="all four figures, not only Fig 11")
    parser.add_argument("--out", type=Path, default=None, help="keep the campaigns here")
    args = parser.parse_args(argv)
    warm_up()
    figures = list(PAIRS) if args.all else ["fig11"]
    with tempfile.TemporaryDirectory() as tmp:
        out = args.out or Path(tmp)
        record = Record("trace")
        for figure in figures:
            compare(figure, out, record)
    record.write()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
