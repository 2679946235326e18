"""Several campaigns in one run: the six find_jump figure campaigns one by one (six
`frictiondisk run` processes) against one `frictiondisk run` of all six (issue 32).

Per repetition, alternately (the order flips every repetition), each into fresh output
folders, so no journal is reused:

* sequential: six `frictiondisk run X.yaml -o DIR` processes, one after the other, 2 workers;
* together:   one `frictiondisk run A.yaml ... F.yaml -o DIR`, 2 workers;
* and the machine's own limit for each (unless --no-limit): two 1-worker copies of the
  same work side by side (two chains of six processes; two runs of all six), which keep
  both cores busy with no tail and no second worker to wait for. Half their wall time is
  what 2 workers could reach; efficiency = that / the 2-worker wall time.

It prints every time, the ratio together / sequential (target: <= 0.8) and the
efficiencies, and, to say where the time goes, each mode's utilization: the kernel time
of its runs (sum of runs.nc wall_s) over 2 x its wall time, the share of the two
workers' time spent inside runs rather than starting processes, scheduling or waiting
in a tail. Both terms are measured in the same run, so a machine shared with other jobs
slows them alike; their ratio (sequential over together) predicts the wall-time ratio on
an idle machine, where the kernel time is the same in both modes.

    python benchmarks/bench_together.py [--repeat 2] [--quick] [--no-limit]

--quick keeps 2 points of each campaign's line (its ends): a smoke check, not the number.
On a shared machine, run it when little else runs; the ratios come from the same minutes.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import xarray as xr
import yaml
from harness import Record

ROOT = Path(__file__).resolve().parent.parent
CLI = [sys.executable, "-m", "frictiondisk.cli", "run"]
CAMPAIGNS = (
    "fig07_pin_xms",
    "fig08_pin_x0",
    "fig09_disk_xms",
    "fig10_disk_x0",
    "fig11_betab_mu",
    "fig11_betab_mu_corotating",
)
TARGET = 0.8  # together / sequential (issue 32)


def campaign_files(folder: Path, quick: bool, certify: bool = True) -> list[Path]:
    """The six campaign files, copied into folder; with quick, each line cut to its ends;
    without certify, `find_jump.certify: false` (bench_certify_cost.py)."""
    files = []
    for name in CAMPAIGNS:
        data = yaml.safe_load((ROOT / "campaigns" / f"{name}.yaml").read_text())
        if not certify:
            data["find_jump"]["certify"] = False
        if quick:
            along = data["find_jump"]["along"]
            for key, values in along.items():
                along[key] = (
                    {**values, "num": 2} if isinstance(values, dict) else [values[0], values[-1]]
                )
        path = folder / f"{name}.yaml"
        path.write_text(yaml.safe_dump(data, sort_keys=False))
        files.append(path)
    return files


def sequential(files: list[Path], out: Path, workers: int) -> list[list[str]]:
    """Argument lists of the six runs of one chain, one after the other."""
    return [[*CLI, str(f), "-o", str(out / f.stem), "--workers", str(workers)] for f in files]


def together(files: list[Path], out: Path, workers: int) -> list[list[str]]:
    return [[*CLI, *map(str, files), "-o", str(out), "--workers", str(workers)]]


def timed(chains: list[list[list[str]]]) -> float:
    """Wall time [s] of the chains run side by side, the commands of each in turn."""

    def chain(commands):
        for cmd in commands:
            done = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
            if done.returncode != 0:
                raise SystemExit(f"{' '.join(cmd)} failed ({done.returncode}):\n{done.stderr}")

    t0 = time.perf_counter()
    threads = [threading.Thread(target=chain, args=(commands,)) for commands in chains]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return time.perf_counter() - t0


def kernel_seconds(out: Path) -> float:
    """Sum of the runs' kernel wall times [s] in every runs.nc under out."""
    total = 0.0
    for runs_file in out.rglob("runs.nc"):
        with xr.open_dataset(runs_file) as runs:
            total += float(runs["wall_s"].sum())
    return total


def one_round(files: list[Path], tmp: Path, k: int, order: list[str], limit: bool) -> dict:
    """The times of one repetition [s], its modes in `order`."""
    times = {}
    for mode in order:
        out = tmp / f"{mode}-{k}"
        build = sequential if mode == "sequential" else together
        times[mode] = timed([build(files, out, 2)])
        times[f"{mode} use"] = kernel_seconds(out) / (2 * times[mode])
        if limit:
            pair = [build(files, tmp / f"{mode}-limit-{k}-{copy}", 1) for copy in (0, 1)]
            times[f"{mode} limit"] = timed(pair) / 2
    return times


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--quick", action="store_true", help="2 points per campaign")
    parser.add_argument("--no-limit", action="store_true", help="skip the 1-worker pairs")
    args = parser.parse_args(argv)
    subprocess.run(  # compile or load the kernel once, outside the timings
        [sys.executable, "-c", "from frictiondisk.engine.worker import warm_up; warm_up()"],
        check=True,
        cwd=ROOT,
    )
    rounds = []
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        files = campaign_files(tmp, args.quick)
        for k in range(args.repeat):
            order = ["sequential", "together"] if k % 2 == 0 else ["together", "sequential"]
            times = one_round(files, tmp, k, order, not args.no_limit)
            rounds.append(times)
            shown = "   ".join(
                f"{mode} {value:.0%}" if mode.endswith("use") else f"{mode} {value:.1f} s"
                for mode, value in times.items()
            )
            print(f"round {k + 1}: {shown}", flush=True)
    median = {mode: statistics.median(r[mode] for r in rounds) for mode in rounds[0]}
    ratios = [r["together"] / r["sequential"] for r in rounds]
    use = {mode: median[f"{mode} use"] for mode in ("sequential", "together")}
    print(f"\nsix find_jump figure campaigns{' (--quick)' if args.quick else ''}, medians:")
    print(
        f"  one by one, 2 workers     {median['sequential']:7.1f} s   utilization {use['sequential']:.0%}"
    )
    print(
        f"  together, 2 workers       {median['together']:7.1f} s   utilization {use['together']:.0%}"
    )
    print(
        f"  predicted on an idle machine (utilization one by one / together): "
        f"{use['sequential'] / use['together']:.2f}"
    )
    print(
        f"  together / one by one     {statistics.median(ratios):7.2f}    per round: "
        f"{', '.join(f'{r:.2f}' for r in ratios)}   target <= {TARGET}: "
        f"{'met' if statistics.median(ratios) <= TARGET else 'not met'}"
    )
    for mode in ("sequential", "together"):
        if f"{mode} limit" in median:
            limit = median[f"{mode} limit"]
            print(
                f"  {mode:<10} 2 workers at {limit / median[mode]:.0%} of the machine's limit "
                f"(two 1-worker copies side by side: {limit:.1f} s each half)"
            )
    record = Record("together")
    record.ratio(
        "wall, together over one by one", median["together"], median["sequential"], f"<= {TARGET}"
    )
    record.ratio("utilization, one by one over together", use["sequential"], use["together"])
    record.write()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
