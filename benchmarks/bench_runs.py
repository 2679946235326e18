"""Runs per mu*: the search with its friction-reserve root finder, adaptive prescan and
certification against plain bisection over a dense prescan without certification.

Six campaigns, each at tol 1e-4 and 1e-8, 2 workers:

* the demo pin line (campaigns/demo_line.yaml, 5 points);
* a co-rotating disk line, x_ms 0.06 ... 0.14 (5 points), bracket [0.05, 0.5];
* a prescan campaign (campaigns/fig10_disk_x0.yaml, 11 points, 36 prescan values);
* the accuracy campaigns (campaigns/accuracy_{pin,disk,brake}.yaml, one cold point each),
  for the agreement with plain bisection only.

`after` is the campaign as written (find_jump defaults: root_finder itp, certification
on, adaptive prescan). `before` is the same campaign with `root_finder: bisect`,
`certify: false` and `prescan.stride: 1` (dense): the search of the issue's baseline,
measured in the same run (warm starts are the current, coarse-to-fine ones in both). Both
set nothing but the tol: the numerics are chosen from it (numerics auto,
frictiondisk/model/auto_numerics.py), so both run the same numerics. Runs per point =
all runs of the campaign / its points, split into search, prescan and certification
(runs.nc `role`). mu* of every point is compared
between the two, and against a third run of the campaign as written but with
`root_finder: bisect` (same prescan, same certification): where both certify a point,
their mu* must agree to tol, which is the root finder's guarantee.

    python benchmarks/bench_runs.py                # all cases (about 5 minutes warm)
    python benchmarks/bench_runs.py --tol 1e-4     # one tolerance
    python benchmarks/bench_runs.py --only demo    # one campaign
"""

from __future__ import annotations

import argparse
import copy
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

ROOT = Path(__file__).resolve().parent.parent
DISK_LINE = {
    "name": "bench_disk_corotating",
    "scene": "disk",
    "params": {"phidot0": 1.1, "x0": 0.0},
    "find_jump": {
        "bracket": [0.05, 0.5],
        "along": {"params.x_ms": {"start": 0.06, "stop": 0.14, "num": 5}},
    },
}
CASES = {
    "demo": lambda: yaml.safe_load((ROOT / "campaigns/demo_line.yaml").read_text()),
    "disk": lambda: copy.deepcopy(DISK_LINE),
    "prescan": lambda: yaml.safe_load((ROOT / "campaigns/fig10_disk_x0.yaml").read_text()),
    # one cold point each: checked for agreement with plain bisection, not for runs/point
    **{
        name: (lambda name=name: yaml.safe_load((ROOT / f"campaigns/{name}.yaml").read_text()))
        for name in ("accuracy_pin", "accuracy_disk", "accuracy_brake")
    },
}
TARGETS = {1e-4: "<= 5 (lines)", 1e-8: "<= 10 (lines), all certified"}


def variant(spec: dict, tol: float, before: bool, bisect_only: bool = False) -> dict:
    """The campaign dict at `tol`, as the baseline (`before`) or as written;
    `bisect_only`: as written except `root_finder: bisect` (the same certification and
    prescan), the reference that mu* must agree with to tol."""
    spec = copy.deepcopy(spec)
    task = spec["find_jump"]
    task["tol"] = tol
    if before or bisect_only:
        task["root_finder"] = "bisect"
    if before:
        task["certify"] = False
        if "prescan" in task:
            task["prescan"]["stride"] = 1
    return spec


def agreement(a: dict, b: dict, tol: float) -> str:
    """max |mu* a - b| in units of tol over the points certified (or recertified) in both,
    and how many points that is."""
    good = ("certified", "recertified")
    both = np.isin(a["certification"], good) & np.isin(b["certification"], good)
    if not both.any():
        return "no point certified in both"
    gap = float(np.nanmax(np.abs(a["mu_star"][both] - b["mu_star"][both])))
    return f"{gap / tol:.2f} tol over {int(both.sum())} of {both.size} points certified in both"


def measure(spec: dict) -> dict:
    """Run a fresh campaign; its runs per point by role, wall time and mu* per point."""
    with tempfile.TemporaryDirectory() as tmp:
        campaign = campaign_from_text(yaml.safe_dump(spec), "<bench>")
        t0 = time.perf_counter()
        run_campaign(campaign, Path(tmp), workers=2, progress=False)
        wall = time.perf_counter() - t0
        with xr.open_dataset(Path(tmp) / "runs.nc") as runs:
            roles = runs["role"].values.astype(str)
        with xr.open_dataset(Path(tmp) / "results.nc") as results:
            mu_star = results["mu_star"].values.ravel().copy()
            meanings = flag_meanings(results["certification"])
            certification = np.array(
                [meanings[int(v)] for v in results["certification"].values.ravel()]
            )
    points = mu_star.size
    return {
        "numerics": campaign.numerics_choice.describe(),
        "wall": wall,
        "points": points,
        "per_point": len(roles) / points,
        "roles": {
            r: float((roles == r).sum()) / points for r in ("search", "prescan", "certification")
        },
        "mu_star": mu_star,
        "certification": certification,
    }


def row(label: str, m: dict) -> str:
    roles = m["roles"]
    flags = list(m["certification"])
    certified = ", ".join(f"{flags.count(f)} {f}" for f in sorted(set(flags)))
    return (
        f"  {label:<7} {m['per_point']:6.1f} runs/point (search {roles['search']:.1f}, "
        f"prescan {roles['prescan']:.1f}, certification {roles['certification']:.1f})  "
        f"wall {m['wall']:6.1f} s  [{certified}]"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tol", type=float, action="append", help="1e-4 and 1e-8 by default")
    parser.add_argument("--only", choices=sorted(CASES), action="append")
    args = parser.parse_args(argv)
    warm_up()
    import distributed  # noqa: F401  (import time is not campaign time)

    record = Record("runs")
    for name in args.only or list(CASES):
        for tol in args.tol or (1e-4, 1e-8):
            spec = CASES[name]()
            before = measure(variant(spec, tol, before=True))
            after = measure(variant(spec, tol, before=False))
            bisect = measure(variant(spec, tol, before=False, bisect_only=True))
            gap = np.nanmax(np.abs(before["mu_star"] - after["mu_star"]))
            print(f"== {name} ({spec['name']}, {after['points']} points), tol {tol:g} ==")
            print(f"  numerics: {after['numerics']}")
            print(row("before", before))
            print(row("after", after))
            target = {"prescan": "<= 1/3 of before"}.get(name, TARGETS[tol])
            if name.startswith("accuracy"):
                target = "none: one cold point, checked for agreement"
            print(
                f"  ratio   {after['per_point'] / before['per_point']:6.2f} runs, "
                f"{after['wall'] / before['wall']:5.2f} wall   (target runs/point {target}); "
                f"max |mu* after - before| = {gap:.2g} ({gap / tol:.2f} tol)",
                flush=True,
            )
            print(
                f"  agreement with plain bisection, both certified: max |mu* itp - bisect| = "
                f"{agreement(after, bisect, tol)} (must be <= 1 tol); bisect took "
                f"{bisect['per_point']:.1f} runs/point",
                flush=True,
            )
            key = f"{name}, tol {tol:g}"
            record.ratio(
                f"{key}: runs per point, after over before",
                after["per_point"],
                before["per_point"],
                target,
            )
            record.ratio(f"{key}: wall, after over before", after["wall"], before["wall"])
            record.number(f"{key}: max |mu* after - before|", gap, "1")
    record.write()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
