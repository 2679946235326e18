"""Settle a well-posedness study's unsettled disagreements with longer watches.

A disagreement stays *unsettled* (judge.verdict) where a settling run at a disputed mu
ends `undetermined`: it ran out of its horizon budget (SETTLE_HORIZON x SETTLE_BUDGET =
12 000 s) or of its steps before it stuck or its section repeated. This runs each such
watch again with both budgets multiplied by --longer (the same numerics otherwise: rtol,
atol and eps / 100, evidence observe), as scan campaigns in the study's own folder (so an
interrupted call loses no finished watch and a second call computes nothing again), and
prints every unsettled row's verdict before and after, then the study's report with the
longer watches. --longer 1 asks the study's judge again on the same budgets: the watches
the rows hold are taken, and only a watch they lack (the exact Coulomb watch of rows from
before it) is run.

    python -m frictiondisk.studies.wellposed.longer out/wellposed --longer 8
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

from frictiondisk.studies import campaigns
from frictiondisk.studies.wellposed.judge import combine_watches, disagrees, verdict
from frictiondisk.studies.wellposed.report import report
from frictiondisk.studies.wellposed.rows import read_rows
from frictiondisk.studies.wellposed.settings import (
    locate_campaign,
    watch_campaign,
    watch_prefix,
    watch_scene,
)
from frictiondisk.studies.wellposed.study import earlier_watch, read_watches, watches_of


def unsettled(rows: list[dict]) -> list[dict]:
    return [
        r
        for r in rows
        if "reference" in r
        and disagrees(r["default"], r["reference"])
        and verdict(r) == "unsettled"
    ]


def undecided_watches(row: dict) -> dict[float, dict]:
    """mu -> the row's settling or persistence run there that ended undetermined."""
    runs = [*row["settled"], *row.get("persisted", [])]
    return {run["mu"]: run for run in runs if run["sticks"] is None}


def with_longer(row: dict, longer: dict[float, dict]) -> dict:
    """The row with its undetermined watches replaced by the longer ones at the same mu."""

    def swap(runs):
        return [longer.get(run["mu"], run) if run["sticks"] is None else run for run in runs]

    return {
        **row,
        "settled": swap(row["settled"]),
        "persisted": swap(row.get("persisted", [])),
        "ends": swap(row.get("ends", [])),
    }


def default_scene(scene: dict):
    """The default's point scene of a study scene dict (validated, nothing run)."""
    data = locate_campaign("longer", scene, "default")
    return campaigns.campaign(data).points()[0].config


def watch_longer(rows: list[dict], out: Path, longer: int, workers: int) -> dict:
    """(seed, index) -> mu -> the longer settling run at each undetermined mu of `rows`;
    at longer 1 a watch the row holds is taken, not run again."""
    scans = {}  # (seed, index, watch) -> the scan campaign of its longer watches
    for row in rows:
        key = (row["seed"], row["index"])
        for watch in watches_of(row["scene"]):
            todo = [
                mu
                for mu, run in sorted(undecided_watches(row).items())
                if longer != 1 or earlier_watch(run, watch) is None
            ]
            if todo:
                scene = watch_scene(default_scene(row["scene"]), longer, exact=watch == "coulomb")
                scans[(*key, watch)] = watch_campaign(watch_prefix(*key, watch, scene), scene, todo)
    campaigns.run(scans.values(), out, workers)
    shown = {where: read_watches(out / scan["name"]) for where, scan in scans.items()}
    found: dict[tuple[int, int], dict[float, dict]] = {}
    for row in rows:
        key = (row["seed"], row["index"])
        for mu, run in undecided_watches(row).items():
            watches = {
                watch: shown.get((*key, watch), {}).get(mu) or earlier_watch(run, watch)
                for watch in watches_of(row["scene"])
            }
            found.setdefault(key, {})[mu] = combine_watches(
                mu, watches["regularized"], watches.get("coulomb")
            )
    return found


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m frictiondisk.studies.wellposed.longer",
        description=__doc__.splitlines()[0],
    )
    parser.add_argument("study", type=Path, help="the study's output folder")
    parser.add_argument("--longer", type=int, default=8, help="factor on both budgets")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    every = list(read_rows(args.study).values())
    rows = unsettled(every)
    n_watches = sum(len(undecided_watches(r)) for r in rows)
    print(f"{len(rows)} unsettled disagreements, {n_watches} watches x {args.longer}")
    longer = watch_longer(rows, args.study, args.longer, args.workers)

    def mine(r):
        return longer.get((r["seed"], r["index"]), {})

    for r in rows:
        after = with_longer(r, mine(r))
        text = "; ".join(
            f"{run['mu']:.6f} {run['outcome']} at {run['t_end']:.0f} s"
            for run in [*after["settled"], *after["persisted"]]
        )
        right = verdict(after)
        silent = right in ("reference", "neither") and r["default"].certified
        print(
            f"{r['seed']}/{r['index']}: unsettled -> {right}{' (SILENT)' if silent else ''}; {text}"
        )
    print("\nthe study's report with these watches (kernel times as the rows hold them):")
    print("\n".join(report([with_longer(r, mine(r)) for r in every], math.nan)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
