"""Watch both ends of every certified bracket of a finished find_jump campaign, to a longer
horizon: does each end still name the side its bracket claims?

A certified bracket [lo, hi] of a boundary `between: [A, B]` (stick / not stick by default)
claims that its lo end's motion lies on side A and its hi end's on side B. This study runs
each end again with the campaign's own scene and numerics, its horizon (t_max in converge
mode, t_decide in decide mode) times `--factor`, and sorts the ends:

* confirmed: the longer run names the claimed side;
* contradicted: it names the other side (a certified end the watch contradicts);
* open: it names neither side (undetermined, or a third motion).

    frictiondisk run campaigns/torus_disk_js_fold.yaml -o out/torus_disk_js_fold
    python -m frictiondisk.studies.watch_boundary_ends out/torus_disk_js_fold --factor 3

Prints one line per end and the counts; exit 1 if any end is contradicted.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from frictiondisk.model.search_settings import CERTIFICATION_FLAGS
from frictiondisk.simulation import simulate as simulate_module
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.tasks.jump_search.sides import HIGH, LOW

# certification flags (results.nc): certified or recertified, and a bracket its
# certification could not confirm (watched with --uncertain)
CERTIFIED = tuple(CERTIFICATION_FLAGS.index(name) for name in ("certified", "recertified"))
UNCERTAIN = CERTIFICATION_FLAGS.index("uncertain")


def watched_config(point_config, numerics: dict, key: str, value: float, factor: float):
    """The point's scene at `key` = `value`, at the campaign's numerics with its horizon
    times `factor` [1]."""
    horizon = "t_max" if numerics.get("mode") == "converge" else "t_decide"
    overrides = {f"numerics.{k}": v for k, v in numerics.items() if v is not None}
    overrides[f"numerics.{horizon}"] = factor * float(numerics[horizon])
    overrides[key] = value
    return point_config.with_overrides(overrides)


def ends_of(results: xr.Dataset, uncertain: bool = False) -> list[tuple[int, float, float]]:
    """(point, lo, hi) of every certified or recertified bracket (and `uncertain` ones too),
    in point order."""
    flags = np.asarray(results["certification"].values).ravel()
    lo = np.asarray(results["mu_lo"].values).ravel()
    hi = np.asarray(results["mu_hi"].values).ravel()
    wanted = (*CERTIFIED, UNCERTAIN) if uncertain else CERTIFIED
    return [(i, float(lo[i]), float(hi[i])) for i in range(flags.size) if flags[i] in wanted]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m frictiondisk.studies.watch_boundary_ends")
    p.add_argument("campaign", type=Path, help="a finished find_jump campaign folder")
    p.add_argument("--factor", type=float, default=3.0, help="horizon x this [1]")
    p.add_argument("--uncertain", action="store_true", help="watch uncertain brackets too")
    args = p.parse_args(argv)
    with xr.open_dataset(args.campaign / "results.nc") as results:
        results = results.load()
    campaign = campaign_from_text(results.attrs["campaign_yaml"])
    numerics = yaml.safe_load(results.attrs["numerics_yaml"])
    task = campaign.task
    sides, key = task.sides, task.parameter_key
    points = campaign.points()
    counts = {"confirmed": 0, "contradicted": 0, "open": 0}
    for i, lo, hi in ends_of(results, args.uncertain):
        for value, claim in ((lo, LOW), (hi, HIGH)):
            config = watched_config(points[i].config, numerics, key, value, args.factor)
            res = simulate_module.simulate(config)
            side = sides.side(res.outcome)
            verdict = "open" if side is None else "confirmed" if side == claim else "contradicted"
            counts[verdict] += 1
            print(
                f"point {i} {key} = {value:.10g} (claims {sides.low if claim == LOW else sides.high}): "
                f"{res.outcome} at t = {res.t_end:.6g} s ({res.decided_by}): {verdict}",
                flush=True,
            )
    total = sum(counts.values())
    print(
        f"{total} {'certified or uncertain' if args.uncertain else 'certified'} ends watched to {args.factor:g} x the horizon: "
        + ", ".join(f"{n} {name}" for name, n in counts.items())
    )
    return 1 if counts["contradicted"] else 0


if __name__ == "__main__":
    sys.exit(main())
