"""Work-precision of numerics auto: what a certified mu* costs at each find_jump.tol.

Two lines, each run with nothing but the tol set (the numerics chosen from it,
frictiondisk/model/auto_numerics.py), at tol 1e-3 ... 1e-9, 2 workers:

* pin: the default pin along x_ms = 0.06 ... 0.14 (5 points), bracket [0.05, 0.5];
* brake: the braked disk from rest (beta_b = 0.005) along x_ms = 0.08 ... 0.12 (3 points),
  bracket [0.15, 0.3].

Per tol it prints the numerics chosen and their expected mu* error, runs per point (of
them certification), accepted kernel steps and kernel time per point, how many points
certified and how many of those are right (|mu* - mu*_ref| <= tol against a reference:
the same line at tol 1e-11, two orders below the tightest tol, with its own auto
numerics), the cost per right certified mu* (kernel time of all runs / those points)
and the largest |mu* - mu*_ref| over the certified points. `baseline` rows run the
same lines with today's default numerics fixed (numerics.preset: default: rtol 1e-6,
atol 1e-9, t_decide 30 s), for comparison. `--figure PATH` draws the cost per right
certified mu* and runs per point against tol (docs/accuracy.md).

    python benchmarks/bench_work_precision.py --figure out/bench/work_precision_tol.png
    python benchmarks/bench_work_precision.py --lines pin --tols 1e-4,1e-8 --no-baseline
"""

from __future__ import annotations

import argparse
import copy
import math
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr
import yaml
from harness import Record

from frictiondisk.engine.runner import run_campaign
from frictiondisk.engine.worker import warm_up
from frictiondisk.store.cf import flag_meanings
from frictiondisk.tasks.campaign import campaign_from_text

TOLS = tuple(10.0**-k for k in range(3, 10))
REFERENCE_TOL = 1.0e-11
LINES = {
    "pin": {
        "name": "wp_pin",
        "scene": "pin",
        "params": {"x0": 0.0},
        "find_jump": {
            "bracket": [0.05, 0.5],
            "along": {"params.x_ms": {"start": 0.06, "stop": 0.14, "num": 5}},
        },
    },
    "brake": {
        "name": "wp_brake",
        "scene": "disk",
        "params": {"x0": 0.0, "phidot0": 0.0, "beta_b": 0.005},
        "find_jump": {
            "bracket": [0.15, 0.3],
            "along": {"params.x_ms": {"start": 0.08, "stop": 0.12, "num": 3}},
        },
    },
}
GOOD = ("certified", "recertified")


def variant(line: str, tol: float, baseline: bool) -> dict:
    spec = copy.deepcopy(LINES[line])
    spec["find_jump"]["tol"] = tol
    if baseline:
        spec["numerics"] = {"preset": "default", "t_decide": 30.0}
    return spec


def measure(spec: dict, reference: np.ndarray | None = None) -> dict:
    """Run a fresh campaign; what it chose, cost and found. A certified point is `right`
    if its mu* lies within tol of the reference's (all certified ones without one)."""
    campaign = campaign_from_text(yaml.safe_dump(spec), "<bench>")
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        run_campaign(campaign, Path(tmp), workers=2, progress=False)
        wall = time.perf_counter() - t0
        with xr.open_dataset(Path(tmp) / "runs.nc") as runs:
            roles = runs["role"].values.astype(str)
            kernel_s = float(runs["wall_s"].sum())
            steps = int(runs["n_steps"].sum())
        with xr.open_dataset(Path(tmp) / "results.nc") as results:
            mu_star = results["mu_star"].values.ravel().copy()
            meanings = flag_meanings(results["certification"])
            flags = [meanings[int(v)] for v in results["certification"].values.ravel()]
    points = mu_star.size
    good = np.isin(flags, GOOD)
    gaps = np.abs(mu_star - reference) if reference is not None else np.zeros(points)
    right = good & (gaps <= campaign.task.tol)
    return {
        "choice": campaign.numerics_choice,
        "points": points,
        "runs": len(roles) / points,
        "certification_runs": float((roles == "certification").sum()) / points,
        "steps": steps / points,
        "kernel_s": kernel_s / points,
        "cost": kernel_s / int(right.sum()) if right.any() else math.inf,
        "certified": int(good.sum()),
        "right": int(right.sum()),
        "error": float(np.nanmax(gaps[good])) if good.any() else math.nan,
        "flags": flags,
        "mu_star": mu_star,
        "wall": wall,
    }


def row(label: str, tol: float, m: dict) -> str:
    choice, error = m["choice"], m["error"]
    expected = "?" if choice.expected is None else f"{choice.expected:.1e}"
    recert = sum(flag == "recertified" for flag in m["flags"])
    return (
        f"{label:10s} {tol:6.0e}  rtol {choice.rtol:6.0e} atol {choice.atol:6.0e} "
        f"t {choice.t_decide:4g} s  exp {expected:>7s}  {m['runs']:5.1f} "
        f"({m['certification_runs']:4.1f})  {m['steps']:9.0f}  {m['kernel_s']:7.3f} s  "
        f"{m['certified']}/{m['points']}"
        + (f" ({recert} re)" if recert else "     ")
        + f"  {m['right']}/{m['points']}  {m['cost']:8.3f} s  {error:8.1e} ({error / tol:5.2f} tol)"
    )


def figure(results: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from frictiondisk.figures.footer import add_footer, code_footer
    from frictiondisk.figures.plotting import save_figure

    fig, (cost_ax, runs_ax) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    for (line, baseline), per_tol in sorted(results.items()):
        tols = sorted(per_tol)
        label = f"{line}, {'default numerics' if baseline else 'auto numerics'}"
        style = {"marker": "o", "linestyle": "--" if baseline else "-", "label": label}
        cost = [per_tol[t]["cost"] for t in tols]
        cost_ax.loglog(tols, [c if math.isfinite(c) else np.nan for c in cost], **style)
        runs_ax.semilogx(tols, [per_tol[t]["runs"] for t in tols], **style)
        for t in tols:
            if not baseline:
                choice = per_tol[t]["choice"]
                cost_ax.annotate(
                    f"{choice.rtol:.0e}", (t, per_tol[t]["cost"]), fontsize=7, alpha=0.7
                )
    cost_ax.set(
        xlabel="find_jump.tol",
        ylabel="kernel time per right certified mu* [s]",
        title="cost per certified mu* within tol (labels: rtol)",
    )
    runs_ax.set(xlabel="find_jump.tol", ylabel="runs per point", title="runs per point")
    for ax in (cost_ax, runs_ax):
        ax.invert_xaxis()
        ax.grid(True, which="both", alpha=0.3)
    runs_ax.legend(fontsize=8)
    # the footer (also in the PNG's metadata): the lines ran just now with this numerics
    add_footer(fig, code_footer("benchmarks/bench_work_precision.py"))
    save_figure(fig, path)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", default=",".join(LINES), help="comma-separated: pin, brake")
    parser.add_argument("--tols", default=",".join(f"{t:g}" for t in TOLS))
    parser.add_argument("--no-baseline", action="store_true", help="skip the default numerics")
    parser.add_argument("--figure", type=Path, help="draw the work-precision figure here")
    args = parser.parse_args(argv)
    tols = [float(t) for t in args.tols.split(",")]
    warm_up()
    import distributed  # noqa: F401  (import time is not campaign time)

    results: dict[tuple[str, bool], dict[float, dict]] = {}
    record = Record("work_precision")
    print(
        "line       tol     numerics chosen                     expected  runs/pt (cert)  "
        "steps/pt  kernel/pt  certified  right  cost/right  |mu* - ref| (certified)"
    )
    for line in args.lines.split(","):
        reference = measure(variant(line, REFERENCE_TOL, False))
        print(
            f"{line}: reference at tol {REFERENCE_TOL:g}: {reference['choice'].describe()}; "
            f"{reference['certified']}/{reference['points']} certified",
            flush=True,
        )
        for baseline in (False, True)[: 1 if args.no_baseline else 2]:
            for tol in tols:
                m = measure(variant(line, tol, baseline), reference["mu_star"])
                results.setdefault((line, baseline), {})[tol] = m
                label = f"{line}{'/def' if baseline else ''}"
                print(row(label, tol, m), flush=True)
                record.number(f"{label}, tol {tol:g}: kernel per right mu*", m["cost"], "s")
                record.number(f"{label}, tol {tol:g}: right of certified", m["right"], "1")
        if not args.no_baseline:  # both passes done: auto against default numerics
            for tol in tols:
                auto, default = results[(line, False)][tol], results[(line, True)][tol]
                key = f"{line}, tol {tol:g}: kernel per right mu*, auto over default numerics"
                record.ratio(key, auto["cost"], default["cost"])
    if args.figure:
        figure(results, args.figure)
        print(f"figure: {args.figure}")
    record.write()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
