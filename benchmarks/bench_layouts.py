"""Cost per step against the number of contacts N: the O(N) arrow solver and the dense LU.

Scene: the braked disk (beta_b = 0.005 N m s/rad, co-rotating start phidot0 = omega_m,
mu = 0.2, which slides with many switches) on a ring of N points, a 5 s decision run
(stop_on_stick as usual). Each cost is the best of a few repeats after a JIT warm-up, so
the ratios, all measured in this process, mean something on a shared, noisy machine.

Targets (issue 11):
  cost(768) / cost(12) <= 100   (linear would be 64; the dense N^3 about 260 000)
  dense / arrow at N = 192 >= 20 on the same run (a 1 s run: the dense path is slow).
Also: events (contact switches) per run and the wall time per event.

    python benchmarks/bench_layouts.py [--quick]
"""

from __future__ import annotations

import sys

from harness import Record

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate

NS = (12, 24, 48, 96, 192, 384, 768)
T_DECIDE = 5.0  # [s] decision horizon of the scaling runs
T_COMPARE = 1.0  # [s] horizon of the dense-vs-arrow run
N_COMPARE = 192


def scene(n: int, t_decide: float, layout: str = "ring"):
    contact = {"points": n}
    if layout == "annulus":
        contact.update(layout="annulus", inner_radius=0.063, outer_radius=0.087)
    return scene_from_dict(
        {
            "scene": "disk",
            "params": {"beta_b": 0.005, "phidot0": 1.1, "mu": 0.2},
            "contact": contact,
            "numerics": {"t_decide": t_decide},
        }
    )


def best_run(config, repeats: int, dense_lu: bool = False):
    """(smallest wall time [s], that run's result) over repeats."""
    best = None
    for _ in range(repeats):
        res = simulate(config, dense_lu=dense_lu)
        if best is None or res.wall_s < best.wall_s:
            best = res
    return best.wall_s, best


def bench_scaling(ns, repeats, layout, record):
    print(f"== cost per step, {layout} of N points (arrow solver, {T_DECIDE:g} s run) ==")
    print("     N   steps  events  outcome      wall [s]  per step [us]  per event [ms]")
    per_step = {}
    for n in ns:
        wall, res = best_run(scene(n, T_DECIDE, layout), repeats)
        per_step[n] = wall / res.n_steps
        per_event = wall / res.n_transitions * 1e3 if res.n_transitions else float("nan")
        print(
            f"  {n:4d}  {res.n_steps:6d}  {res.n_transitions:6d}  {res.outcome:<11}"
            f"  {wall:8.3f}  {per_step[n] * 1e6:13.1f}  {per_event:14.3f}"
        )
    lo, hi = min(ns), max(ns)
    ratio = record.ratio(
        f"{layout}: cost per step, N = {hi} over N = {lo}", per_step[hi], per_step[lo], "<= 100"
    )
    print(
        f"  cost({hi}) / cost({lo}) = {ratio:.1f}   (target <= 100; linear {hi / lo:.0f})",
        flush=True,
    )
    return ratio


def bench_dense(n, repeats, record):
    print(f"== dense LU vs arrow solver, ring of N = {n} points, same {T_COMPARE:g} s run ==")
    config = scene(n, T_COMPARE)
    wall_a, arrow = best_run(config, repeats)
    wall_d, dense = best_run(config, 1, dense_lu=True)
    same = (arrow.outcome, arrow.n_transitions) == (dense.outcome, dense.n_transitions)
    print(f"  arrow : {wall_a / arrow.n_steps * 1e6:10.1f} us/step  steps {arrow.n_steps}")
    print(f"  dense : {wall_d / dense.n_steps * 1e6:10.1f} us/step  steps {dense.n_steps}")
    speedup = record.ratio(
        f"dense LU over arrow, N = {n}, per step",
        wall_d / dense.n_steps,
        wall_a / arrow.n_steps,
        ">= 20",
    )
    d_r1 = abs(arrow.R1 - dense.R1)
    shown = f"{d_r1:.1e} m" if d_r1 == d_r1 else "n/a (no sticking in the run)"
    print(
        f"  dense / arrow = {speedup:.1f} x   (target >= 20)   same outcome and events: {same}"
        f"   |dR1| = {shown}",
        flush=True,
    )
    return speedup


if __name__ == "__main__":
    quick = "--quick" in sys.argv
    ns = NS[:4] if quick else NS
    simulate(scene(12, 0.5))  # JIT warm-up (compiles or loads the cache)
    record = Record("layouts")
    bench_scaling(ns, 2 if quick else 3, "ring", record)
    bench_scaling(ns, 1, "annulus", record)
    bench_dense(48 if quick else N_COMPARE, 2, record)
    record.write()
