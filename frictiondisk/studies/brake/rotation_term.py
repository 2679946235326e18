"""Part 3: the rotation term of the contact rate (docs/model.md section 3): a stuck braked
disk integrated by scipy-radau with and without it. Without it is a model variant that no
scene file can ask for (simulate_radau with objective_rate=False), so these
runs call the simulation directly, not through a campaign."""

from __future__ import annotations

import math
import time

import numpy as np

from frictiondisk.simulation.radau import simulate_radau
from frictiondisk.studies.brake.common import (
    N_POINTS,
    OMEGA,
    POINTS,
    REV,
    bisect,
    scene,
    transitions_per_rev,
)
from frictiondisk.verdict import admissibility as ad
from frictiondisk.verdict.outcomes import STICK

VARIANTS = {"with rotation term (ours)": True, "without (u = v)": False}
# scipy-radau measures no slip per revolution, so a disk there takes the `contacts` rule
# (every contact stuck for a revolution), the rule of the numbers in docs/brake.md
RADAU = {"method": "scipy-radau", "stick_rule": "contacts"}


def self_stress(tr):
    """Largest contact force [N] not explained by the elastic sharing of the resultants
    (force and torque) of the pattern: the self-equilibrated part, in every sample."""
    out = np.empty(len(tr.t))
    for j in range(len(tr.t)):
        ang = tr.phi[j]
        a = POINTS @ np.array([[math.cos(ang), math.sin(ang)], [-math.sin(ang), math.cos(ang)]])
        z = np.column_stack((tr.Zx[j], tr.Zy[j]))
        torque = float((a[:, 0] * z[:, 1] - a[:, 1] * z[:, 0]).sum())
        elastic = ad.elastic_pattern(z.sum(axis=0), torque, a)
        out[j] = np.linalg.norm(z - elastic, axis=1).max()
    return out


def stuck_run(label: str, objective: bool, mu: float, bb: float, nrev: int) -> dict:
    """One stuck disk over nrev revolutions: transitions, spin creep, self-stress."""
    cfg = scene(mu, bb, OMEGA, stop_on_stick=False, t_decide=nrev * REV, **RADAU)
    t0 = time.perf_counter()
    res = simulate_radau(cfg, record=True, dt_out=REV / 50, objective_rate=objective)
    tr = res.trajectory
    per_rev = transitions_per_rev(tr, nrev)
    lag = tr.phi - OMEGA * tr.t
    late = tr.t > (nrev - 3) * REV
    lag_rate = float(np.polyfit(tr.t[late], lag[late], 1)[0] * REV)
    stress = self_stress(tr)
    print(
        f"  {label:26s}: {res.outcome}, transitions per revolution {per_rev}, spin creep"
        f" {lag_rate:+.2e} rad/rev, self-stress last rev {stress[late].max():.2e} N"
        f" (limit mu F_n/N = {mu / N_POINTS:.4f} N), wall {time.perf_counter() - t0:.1f} s",
        flush=True,
    )
    return {
        "trajectory": tr,
        "per_rev": per_rev,
        "lag": lag,
        "self_stress": stress,
        "lag_rate": lag_rate,
        "outcome": res.outcome,
    }


def part3(no_radau: bool, quick: bool):
    mu, bb = 0.5, 0.002
    nrev = 6 if quick else 10
    print(
        f"\n3. rotation term: stuck disk mu = {mu}, beta_b = {bb}, phidot0 = omega_m, "
        f"{nrev} revolutions (scipy-radau)"
    )
    runs = {label: stuck_run(label, obj, mu, bb, nrev) for label, obj in VARIANTS.items()}
    mustar = {}
    if not no_radau:
        for label, obj in (("ours", True), ("without", False)):
            t0 = time.perf_counter()

            def sticks(m, obj=obj):
                cfg = scene(m, bb, OMEGA, **RADAU)
                return simulate_radau(cfg, objective_rate=obj).outcome == STICK

            lo, hi = bisect(sticks, 0.15, 1.35 if obj else 2.55, 0.02)
            mustar[label] = (lo, hi)
            print(
                f"  mu* (`stick` rule, scipy-radau, tol 0.02), {label}: [{lo:.3f}, {hi:.3f}]"
                f" ({time.perf_counter() - t0:.0f} s)",
                flush=True,
            )
    return runs, mustar
