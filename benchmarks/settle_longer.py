"""Settle the well-posedness study's unsettled disagreements with longer watches.

A disagreement stays *unsettled* (benchmarks/study_wellposed.py, `verdict`) where a
settling run at a disputed mu ends `undetermined`: it ran out of its horizon budget
(SETTLE_HORIZON x SETTLE_BUDGET = 12 000 s) or of its 2 000 000 steps before it stuck or
its section repeated. This script runs each such watch again with both budgets multiplied
by --longer (the same numerics otherwise: rtol, atol and eps / 100, evidence observe) and
prints every unsettled row's verdict before and after. The new runs go to --out (JSON
lines), so an interrupted call loses no finished watch and a second call reuses them.
--longer 1 asks a changed judge (the exact Coulomb watch of a Coulomb pin) on the same
budgets; the regularized watch, deterministic, is then taken from the row.

    python benchmarks/settle_longer.py out/wellposed.jsonl --out out/longer.jsonl --longer 8
"""

from __future__ import annotations

import argparse
import json
import math
import multiprocessing
import sys
from pathlib import Path

import study_wellposed as study


def load_rows(paths: list[Path]) -> list[dict]:
    """Every row of the study's JSON lines (any code)."""
    rows = []
    for path in paths:
        for line in path.read_text().splitlines():
            rows.append(study._from_json(json.loads(line)["row"]))
    return rows


def unsettled(rows: list[dict]) -> list[dict]:
    return [
        r
        for r in rows
        if study.disagrees(r["default"], r["reference"]) and study.verdict(r) == "unsettled"
    ]


def undecided_watches(row: dict) -> dict[float, dict]:
    """mu -> the row's settling or persistence run there that ended undetermined."""
    runs = [*row["settled"], *row.get("persisted", [])]
    return {run["mu"]: run for run in runs if run["sticks"] is None}


def _watch(job: tuple[int, int, float, int, dict]) -> dict:
    """A watch again; at --longer 1 (a new judge on the same budgets) its regularized run,
    deterministic, is taken from the study's row instead of run again."""
    seed, index, mu, longer, earlier = job
    known = earlier.get("regularized", earlier) if longer == 1 else None
    run = study.settle(study.draw_scene(seed, index), mu, longer, regularized=known)
    return {"seed": seed, "index": index, "longer": longer, "run": run}


def with_longer(row: dict, longer: dict[float, dict]) -> dict:
    """The row with its undetermined watches replaced by the longer ones at the same mu."""

    def swap(runs):
        return [longer.get(run["mu"], run) if run["sticks"] is None else run for run in runs]

    return {**row, "settled": swap(row["settled"]), "persisted": swap(row.get("persisted", []))}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("rows", type=Path, nargs="+", help="the study's JSON lines (--cache)")
    parser.add_argument("--out", type=Path, required=True, help="JSON lines of longer watches")
    parser.add_argument("--longer", type=int, default=8, help="factor on both budgets")
    parser.add_argument("--processes", type=int, default=2)
    args = parser.parse_args(argv)

    every = load_rows(args.rows)
    rows = unsettled(every)
    done: dict[tuple[int, int], dict[float, dict]] = {}  # (seed, index) -> mu -> watch

    def keep(entry):
        done.setdefault((entry["seed"], entry["index"]), {})[entry["run"]["mu"]] = entry["run"]

    if args.out.is_file():
        for line in args.out.read_text().splitlines():
            entry = json.loads(line)
            if entry["longer"] == args.longer:
                keep(entry)
    jobs = [
        (r["seed"], r["index"], mu, args.longer, run)
        for r in rows
        for mu, run in sorted(undecided_watches(r).items())
        if mu not in done.get((r["seed"], r["index"]), {})
    ]
    print(f"{len(rows)} unsettled disagreements, {len(jobs)} watches to run x {args.longer}")
    with multiprocessing.get_context("spawn").Pool(args.processes) as pool:
        for entry in pool.imap_unordered(_watch, jobs):
            run = entry["run"]
            keep(entry)
            with args.out.open("a") as f:
                f.write(json.dumps(entry) + "\n")
            print(
                f"  {entry['seed']}/{entry['index']} mu {run['mu']:.6f}: {run['outcome']} at "
                f"{run['t_end']:.0f} s",
                flush=True,
            )

    def mine(r):
        return done.get((r["seed"], r["index"]), {})

    for r in rows:
        after = with_longer(r, mine(r))
        text = "; ".join(
            f"{run['mu']:.6f} {run['outcome']} at {run['t_end']:.0f} s"
            for run in [*after["settled"], *after["persisted"]]
        )
        right = study.verdict(after)
        silent = right in ("reference", "neither") and r["default"].certified
        print(
            f"{r['seed']}/{r['index']}: unsettled -> {right}{' (SILENT)' if silent else ''}; {text}"
        )
    print("\nthe study's report with these watches (kernel times as the rows hold them):")
    print("\n".join(study.report([with_longer(r, mine(r)) for r in every], math.nan)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
