"""Two source trees side by side: the kernel's speed and its cold compile (issue 47).

A refactor of the kernel must keep its speed and its compile time within 5 % of the tree
before it. This benchmark runs both trees in alternating child processes (A B, B A, ...,
so a load that drifts on a shared machine hits both alike), each with PYTHONPATH set to
its tree:

* cold compile: a fresh NUMBA_CACHE_DIR, then the first pin and the first disk run, in CPU
  seconds of the child (compiling is single-threaded; CPU time moves less with the load
  of other processes than wall time);
* kernel speed: with that cache warm, the least CPU time of `repeats` runs of each case.

    python benchmarks/bench_trees.py /work/baseline .          # before, after
    python benchmarks/bench_trees.py A B --rounds 3 --repeats 10

It prints each number of B against A's from the same run, and writes them with
benchmarks/harness.py (out/bench/bench_trees.json, BENCH_OUT=DIR).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from bench_kernel import CASES as KERNEL_CASES
from harness import Record

CASES = {  # bench_kernel's two pin runs, and two disks
    **KERNEL_CASES,
    "disk from rest, 12 contacts (mu 0.2, x_ms 0.1)": {
        "scene": "disk",
        "params": {"mu": 0.2, "x_ms": 0.1},
        "numerics": {"mode": "decide"},
    },
    "pin decision run, rodas5 at rtol 1e-8 (certification's runs)": {
        "scene": "pin",
        "params": {"mu": 0.13},
        "numerics": {"method": "rodas5", "rtol": 1e-8},
    },
    "braked co-rotating disk (mu 0.3, beta_b 0.005)": {
        "scene": "disk",
        "params": {"mu": 0.3, "x_ms": 0.1, "beta_b": 0.005, "phidot0": 1.1},
        "numerics": {"mode": "decide"},
    },
}

# The child: imports only the public scene_from_dict and simulate, which both trees have.
CHILD = """
import json, sys, time
cases, repeats = json.loads(sys.argv[1]), int(sys.argv[2])
t0 = time.process_time()
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
configs = {}
for name, spec in cases.items():
    try:  # a case the older tree cannot run (a method it lacks) is left out of both
        configs[name] = scene_from_dict(spec)
    except Exception:
        pass
out = {"outcomes": {}}
c0 = time.process_time()
simulate(scene_from_dict({"scene": "pin", "params": {"mu": 0.13}}))
simulate(scene_from_dict({"scene": "disk", "params": {"mu": 0.2}}))
out["first_runs_cpu_s"] = time.process_time() - c0
out["import_cpu_s"] = c0 - t0
out["cases_cpu_s"] = {}
for name, config in configs.items():
    best = float("inf")
    for _ in range(repeats):
        c = time.process_time()
        result = simulate(config)
        best = min(best, time.process_time() - c)
    out["cases_cpu_s"][name] = best
    out["outcomes"][name] = [result.outcome, result.n_steps]
config = configs[AROUND_CASE]
around = []
for _ in range(AROUND_CALLS):
    t = time.perf_counter()
    result = simulate(config)
    around.append(time.perf_counter() - t - result.wall_s)
out["around_s"] = min(around)
print(json.dumps(out))
"""


# simulate()'s Python around its kernel call (wall time less the result's wall_s, the
# least of AROUND_CALLS calls) of this case
AROUND_CASE = "pin decision run (mu 0.13, x_ms 0.1)"
AROUND_CALLS = 400


def run_child(tree: Path, cache: str, repeats: int) -> dict:
    env = {**os.environ, "PYTHONPATH": str(tree), "NUMBA_CACHE_DIR": cache}
    child = CHILD.replace("AROUND_CASE", repr(AROUND_CASE)).replace(
        "AROUND_CALLS", str(AROUND_CALLS)
    )
    done = subprocess.run(
        [sys.executable, "-c", child, json.dumps(CASES), str(repeats)],
        env=env,
        cwd=tree,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("before", type=Path, help="the tree measured against (A)")
    parser.add_argument("after", type=Path, help="the tree measured (B)")
    parser.add_argument("--rounds", type=int, default=2, help="cold compiles per tree")
    parser.add_argument("--repeats", type=int, default=8, help="runs per case and round")
    args = parser.parse_args()
    trees = {"A": args.before.resolve(), "B": args.after.resolve()}
    samples: dict[str, list[dict]] = {"A": [], "B": []}
    for round_no in range(args.rounds):
        order = ("A", "B") if round_no % 2 == 0 else ("B", "A")
        for side in order:
            with tempfile.TemporaryDirectory(prefix="numba-cache-") as cache:
                cold = run_child(trees[side], cache, 1)
                warm = run_child(trees[side], cache, args.repeats)
            samples[side].append({"cold": cold, "warm": warm})
            print(
                f"round {round_no + 1} {side}: first runs {cold['first_runs_cpu_s']:.1f} s CPU "
                f"cold, {warm['first_runs_cpu_s']:.2f} s warm",
                flush=True,
            )

    record = Record("bench_trees")

    def median(side: str, pick) -> float:
        return statistics.median(pick(s) for s in samples[side])

    def compare(label: str, pick, unit: str) -> None:
        a, b = median("A", pick), median("B", pick)
        record.number(f"{label} A", a, unit)
        record.number(f"{label} B", b, unit)
        record.ratio(f"{label} B/A", b, a, target="<= 1.05")
        print(f"{label:<52} A {a:9.3f} {unit}   B {b:9.3f} {unit}   B/A {b / a:6.3f}")

    print(f"\nmedians over {args.rounds} rounds; A = {trees['A']}, B = {trees['B']}")
    compare("cold compile (first pin + disk run)", lambda s: s["cold"]["first_runs_cpu_s"], "s")
    compare("first pin + disk run, warm cache", lambda s: s["warm"]["first_runs_cpu_s"], "s")
    shared = [n for n in CASES if all(n in s["warm"]["cases_cpu_s"] for s in samples["A"])]
    for name in shared:
        compare(name, lambda s, n=name: s["warm"]["cases_cpu_s"][n], "s")
    for name in sorted(set(CASES) - set(shared)):
        print(f"{name}: not run (tree A cannot run it)")
    compare(
        "Python around the kernel (pin decision run)", lambda s: 1e3 * s["warm"]["around_s"], "ms"
    )
    same = all(
        samples["A"][0]["warm"]["outcomes"][n] == samples["B"][0]["warm"]["outcomes"][n]
        for n in shared
    )
    print(f"same outcome and step count in every case: {same}")
    record.write()
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
