"""Watch the not-stick end of every certified bracket of a finished trace campaign: does
it stick after all?

A certified bracket promises that its one end sticks and its other does not. This study
runs each certified point's not-stick end again with `numerics.evidence: observe` (only
what a run shows counts: it sticks, or its section repeats) to a long horizon, at the
campaign's own numerics, and counts the ends that stick (each one a certified end the
watch contradicts)::

    frictiondisk run campaigns/trace_stribeck_pin.yaml -o out/trace_stribeck_pin
    python -m frictiondisk.studies.watch_ends out/trace_stribeck_pin --horizon 600

Prints one line per end (key, mu, the watch's outcome, its time and rule) and the count;
exit 1 if any watched end sticks.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import xarray as xr
import yaml

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.model.search_settings import CERTIFICATION_FLAGS
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict.outcomes import STICK

# certification flags (results.nc) of a certified or recertified point
CERTIFIED = tuple(CERTIFICATION_FLAGS.index(name) for name in ("certified", "recertified"))


def not_stick_ends(results: xr.Dataset) -> list[tuple[float | None, float]]:
    """(key value or None, mu) of the not-stick end of every certified point: the end of
    the bisected coordinate that `stick_high` does not name."""
    ends = []
    bisects_key = "bisected" in results and "key" in str(results["bisected"].attrs)
    for i in range(results.sizes["point"]):
        if int(results["certification"][i]) not in CERTIFIED:
            continue
        high_sticks = bool(results["stick_high"][i])
        key = float(results["r"][i]) if "r" in results else None
        mu = float(results["mu_hi"][i] if not high_sticks else results["mu_lo"][i])
        if bisects_key and int(results["bisected"][i]) == 1:
            mu = float(results["mu_lo"][i])
            key = float(results["r_hi"][i] if not high_sticks else results["r_lo"][i])
        ends.append((key, mu))
    return ends


def watch_scene(results: xr.Dataset, key: float | None, mu: float, horizon: float) -> dict:
    """The campaign's scene at (key, mu), at its own numerics, watching to `horizon` [s]."""
    campaign = yaml.safe_load(results.attrs["campaign_yaml"])
    numerics = yaml.safe_load(results.attrs["numerics_yaml"])
    scene = {k: v for k, v in campaign.items() if k in ("scene", "params", "contact")}
    scene["numerics"] = {
        **numerics,
        "mode": "decide",
        "t_decide": horizon,
        "horizon_budget": 1.0,
        "evidence": "observe",
    }
    config = scene_from_dict(scene).with_overrides({"params.mu": mu})
    if key is not None:
        config = config.with_overrides({campaign["trace"]["key"]: key})
    return config


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m frictiondisk.studies.watch_ends")
    p.add_argument("campaign", type=Path, help="a finished campaign folder (results.nc)")
    p.add_argument("--horizon", type=float, default=600.0, help="watch to this time [s]")
    args = p.parse_args(argv)
    with xr.open_dataset(args.campaign / "results.nc") as results:
        results = results.load()
    ends = not_stick_ends(results)
    stuck = 0
    for key, mu in ends:
        res = simulate(watch_scene(results, key, mu, args.horizon))
        stuck += res.outcome == STICK
        where = "" if key is None else f"key {key:.10g}  "
        print(f"{where}mu {mu:.10g}: {res.outcome} at t = {res.t_end:.6g} s ({res.decided_by})")
    print(
        f"{len(ends)} certified not-stick ends watched (observe, {args.horizon:g} s): {stuck} stick"
    )
    return 1 if stuck else 0


if __name__ == "__main__":
    sys.exit(main())
