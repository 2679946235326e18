"""Strong scaling of campaigns: workers 1, 2, 4, ... up to the machine's cores.

First the machine's own limit: N independent loops of kernel runs on N threads, no
orchestration (speed-up = N x one loop's time / N loops' time). Then, for each campaign,
the wall time on 1, 2, ... workers, the speed-up, the parallel efficiency and the speed-up
as a fraction of the machine's limit:

  (a) the 10-point disk-from-rest prescan line (campaigns/disk_xms_at_rest.yaml);
  (b) the Fig 11 campaign (campaigns/fig11_betab_mu.yaml);
  (c) one point searched to tol 1e-8 (the co-rotating disk at x_ms 0.1; multisection split 3,
      with the runs and rounds of plain bisection for comparison);
  (d) one prescanned disk point (the disk from rest at x_ms = 0.1).

`--quick` (the default of `make bench`) uses reduced copies of (a) and (b) (coarser
prescan and tol 1e-3, (b) on fewer brake values) so the whole bench takes minutes on 2
cores; `--full` runs the campaign files as they are. Ratios are measured in this process
after JIT warm-up; on a shared machine the numbers are noisy: repeat with --repeats.

Targets (issue 10) on 2 cores: (a), (b) 2-worker speed-up >= 90 % of the machine's limit;
(c), (d) 2 workers >= 1.6x faster than 1.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import threading
import time
from pathlib import Path

import xarray as xr

from frictiondisk.campaign.plan import run_config
from frictiondisk.campaign.runner import run_campaign
from frictiondisk.campaign.spec import campaign_from_text, load_campaign
from frictiondisk.campaign.tasks import warm_up
from frictiondisk.simulate import simulate

ROOT = Path(__file__).resolve().parents[1]


def campaign_text(name: str, quick: bool) -> tuple[str, str]:
    """(YAML text, what it is) of bench campaign `name`."""
    if name == "a":
        text = (ROOT / "campaigns/disk_xms_at_rest.yaml").read_text()
        if quick:
            text = text.replace("num: 59}", "num: 20}").replace("tol: 1.0e-4", "tol: 1.0e-3")
            return text, "disk_xms_at_rest.yaml, quick: prescan of 20 mu, tol 1e-3"
        return text, "campaigns/disk_xms_at_rest.yaml as is"
    if name == "b":
        text = (ROOT / "campaigns/fig11_betab_mu.yaml").read_text()
        if quick:
            text = (
                text.replace("num: 91}", "num: 19}")
                .replace("tol: 1.0e-4", "tol: 1.0e-3")
                .replace("num: 13}", "num: 7}")
            )
            return text, "fig11_betab_mu.yaml, quick: 7 beta_b, prescan of 19 mu, tol 1e-3"
        return text, "campaigns/fig11_betab_mu.yaml as is"
    if name == "c":
        text = """name: bench_one_point_fine
scene: disk
params: {x_ms: 0.1, phidot0: 1.1}
numerics: {mode: decide, t_decide: 30.0}
find_jump:
  bracket: [0.1, 0.6]
  tol: 1.0e-8
  split: SPLIT
  along:
    params.x_ms: [0.1]
"""
        return text, "co-rotating disk, x_ms 0.1, bracket [0.1, 0.6], tol 1e-8, split SPLIT"
    if name == "d":
        text = (ROOT / "campaigns/disk_xms_at_rest.yaml").read_text()
        text = text.replace("params.x_ms: {start: 0.02, stop: 0.2, num: 10}", "params.x_ms: [0.1]")
        if quick:
            text = text.replace("num: 59}", "num: 30}")
            return text, "disk from rest at x_ms 0.1, quick: prescan of 30 mu, tol 1e-4"
        return text, "disk from rest at x_ms 0.1, prescan of 59 mu, tol 1e-4"
    raise ValueError(name)


def machine_limit(workers: list[int], loop_s: float) -> dict[int, float]:
    """Speed-up of N independent loops of kernel runs on N threads over one loop."""
    campaign = load_campaign(ROOT / "campaigns/disk_xms_at_rest.yaml")
    point = campaign.points()[4].config
    from frictiondisk.bisection import RunRequest

    configs = [run_config(point, RunRequest(mu, 0, "decide"), 2.0) for mu in (0.1, 0.2, 0.3)]
    t0 = time.perf_counter()
    n_loop = 0
    while time.perf_counter() - t0 < loop_s:  # one loop lasts about loop_s
        simulate(configs[n_loop % len(configs)])
        n_loop += 1
    todo = [configs[k % len(configs)] for k in range(n_loop)]

    def loop():
        for config in todo:
            simulate(config)

    walls = {}
    for n in workers:
        threads = [threading.Thread(target=loop) for _ in range(n)]
        t0 = time.perf_counter()
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        walls[n] = time.perf_counter() - t0
    return {n: n * walls[1] / walls[n] for n in workers}


def time_campaign(text: str, workers: int, repeats: int):
    """Best wall time [s] of a fresh run on `workers` local workers, runs used, the
    results (mu_lo, mu_hi) and the measured cost per task [s]."""
    best = None
    for _ in range(repeats):
        with tempfile.TemporaryDirectory() as tmp:
            campaign = campaign_from_text(text, "<bench>")
            t0 = time.perf_counter()
            summary = run_campaign(campaign, Path(tmp), workers=workers, progress=False)
            wall = time.perf_counter() - t0
            with xr.open_dataset(Path(tmp) / "results.nc") as ds:
                found = (ds.mu_lo.values.tolist(), ds.mu_hi.values.tolist())
        if best is None or wall < best[0]:
            best = (wall, summary.runs_total, found, summary.task_overhead_s)
    return best


def scaling_table(label, text, workers, repeats, limit) -> dict[int, float]:
    rows = {}
    found_1 = None
    print(f"  {'workers':>7} {'wall [s]':>9} {'speed-up':>9} {'efficiency':>10} {'of limit':>9}")
    for n in workers:
        wall, runs, found, overhead = time_campaign(text, n, repeats)
        rows[n] = wall
        found_1 = found_1 or found
        speedup = rows[workers[0]] / wall
        print(
            f"  {n:7d} {wall:9.2f} {speedup:8.2f}x {speedup / n:10.0%} "
            f"{speedup / limit[n]:9.0%}" + ("" if found == found_1 else "  RESULTS DIFFER")
        )
    print(f"  runs used: {runs}; cost per task measured by the driver: {overhead * 1e3:.1f} ms")
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="the campaign files as they are")
    parser.add_argument("--quick", action="store_true", help="reduced copies (default)")
    parser.add_argument("--repeats", type=int, default=1, help="best of this many runs")
    parser.add_argument("--workers", help="comma-separated worker counts (default 1, 2, 4, ...)")
    parser.add_argument("--only", default="abcd", help="which of a, b, c, d (default all)")
    parser.add_argument("--split", type=int, default=3, help="(c): parts per round (default 3)")
    args = parser.parse_args()
    quick = not args.full
    cores = os.cpu_count() or 1
    if args.workers:
        workers = sorted({int(w) for w in args.workers.split(",")} | {1})
    else:
        workers = sorted({1, cores} | {2**k for k in range(1, 8) if 2**k < cores})

    warm_up()
    import dask.array  # noqa: F401  (xarray imports it when writing results.nc: once per process)
    import distributed  # noqa: F401  (import time is not campaign time)

    print("== machine limit: independent kernel loops on N threads, no orchestration ==")
    limit = machine_limit(workers, loop_s=3.0)
    for n in workers:
        print(f"  {n:3d} threads: speed-up {limit[n]:5.2f}x ({limit[n] / n:.0%} of {n})")

    for name in args.only:
        text, what = campaign_text(name, quick)
        if name == "c":
            text = text.replace("SPLIT", str(args.split))
            what = what.replace("SPLIT", str(args.split))
        title = {
            "a": "(a) 10-point disk-from-rest prescan line",
            "b": "(b) Fig 11 campaign",
            "c": "(c) one point searched to tol 1e-8",
            "d": "(d) one prescanned disk point",
        }[name]
        print(f"== {title} [{what}] ==")
        rows = scaling_table(title, text, workers, args.repeats, limit)
        if name == "c" and args.split != 2:
            plain = text.replace(f"split: {args.split}", "split: 2")
            wall, runs, _, _ = time_campaign(plain, 1, args.repeats)
            best = min(rows.values())
            print(
                f"  plain bisection (split 2) on 1 worker: {wall:.2f} s, {runs} runs; "
                f"split {args.split} at its best ({best:.2f} s) is {wall / best:.2f}x faster"
            )


if __name__ == "__main__":
    main()
