"""Part 1: mu*(beta_b) of the `stick` rule from both initial spins (find_jump campaigns on
the engine), of a co-rotation rule (a bisection on recorded runs), and the four bounds at
the sticking radius."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from frictiondisk.studies import campaigns
from frictiondisk.studies.brake.common import OMEGA, bisect, bounds, corotation

BETA_B = np.linspace(0.0, 0.03, 13)  # as campaigns/fig11_betab_mu.yaml [N m s/rad]
STARTS = {"stick_corot_start": OMEGA, "stick_rest_start": 0.0}  # row key -> phidot0
# mu: its low end below c_s x_ms / F_n = 0.1, where an unbraked disk creeps onto the rim of
# its sticking disc and a run there never decides (the former plain bisection from 0.1 took
# that undetermined run for not stick)
BRACKET = (0.09, 1.2)
TOL = 1e-4
COROTATION_BRACKET = (0.1, 1.2)  # the co-rotation rule's plain bisection: each step a recorded run
COROTATION_TOL = 2e-3


def stick_campaign(key: str, betas: np.ndarray) -> dict:
    """mu* of the `stick` rule along beta_b from one initial spin: the default numerics
    (rtol 1e-6, atol 1e-9, t_decide 30 s), no certification; at each beta_b both ends of
    BRACKET run first and the change between them is halved to TOL (root_finder bisect),
    as a plain bisection would, but an undetermined run is retried with a longer horizon
    where a plain bisection took it for not stick."""
    return {
        "name": f"brake-{key.replace('_', '-')}-{len(betas)}",
        "scene": "disk",
        "params": {"phidot0": STARTS[key]},
        "numerics": {"rtol": 1e-6, "atol": 1e-9, "t_decide": 30.0},
        "find_jump": {
            "prescan": {"mu": list(BRACKET), "stride": 1},
            "tol": TOL,
            "along": {"params.beta_b": [float(b) for b in betas]},
            "certify": False,
            "root_finder": "bisect",
        },
    }


def stick_rule(betas: np.ndarray, out: Path, workers: int) -> dict[str, tuple]:
    """Row key -> (mu* per beta_b, R1 at mu_hi per beta_b), from the engine."""
    plan = {key: stick_campaign(key, betas) for key in STARTS}
    campaigns.run(plan.values(), out, workers)
    found = {}
    for key, data in plan.items():
        res = campaigns.results(out / data["name"])
        found[key] = (res.mu_star.values, res.R1_hi.values)
    return found


def part1(quick: bool, out: Path, workers: int) -> list[dict]:
    betas = BETA_B[::3] if quick else BETA_B
    stick = stick_rule(betas, out, workers)
    rows = []
    print("\n1. mu*(beta_b): `stick` rule (both spins), co-rotation rule, bounds at R1(mu_hi)")
    print(
        "  beta_b  mu*_stick(w) mu*_stick(0)  mu*_corot  R1[m]    collapse shakedown"
        "  elastic additive  mu*/additive"
    )
    for k, bb in enumerate(betas):
        row = {"beta_b": float(bb), **{key: float(stick[key][0][k]) for key in STARTS}}
        row["R1"] = float(stick["stick_corot_start"][1][k])
        lo, hi = bisect(
            lambda m, b=bb: corotation(m, b, OMEGA)["corotates"],
            *COROTATION_BRACKET,
            COROTATION_TOL,
        )
        row["corotation_rule"] = 0.5 * (lo + hi)
        row["R_corot"] = corotation(hi, bb, OMEGA)["R"]
        row["bounds"] = bounds(bb, row["R1"])
        row["bounds_at_corot"] = bounds(bb, row["R_corot"])
        b = row["bounds"]
        print(
            f"  {bb:.4f}  {row['stick_corot_start']:.4f}       {row['stick_rest_start']:.4f}"
            f"       {row['corotation_rule']:.4f}     {row['R1']:.4f}   {b['collapse']:.4f}"
            f"   {b['shakedown']:.4f}    {b['elastic']:.4f}   {b['additive']:.4f}"
            f"   {row['stick_corot_start'] / b['additive']:.2f}",
            flush=True,
        )
        rows.append(row)
    return rows
