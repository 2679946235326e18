"""The Python around a short run, piece by piece: what one run of a scan costs outside the
kernel on its worker (the scene, packing, the result and its summary) and in the driver
(a point's scene, its canonical form and journal key, the planner), each the least of
many calls [us], so that a shared machine moves the numbers little.

The runs are the pin's decide runs of bench_engine.py's scans (x_ms 0.1, mu 0.13 to 0.30).
Only public functions are timed, so the same script measures an older tree:

    python benchmarks/bench_python_pieces.py            # 2 000 calls of each piece
    python benchmarks/bench_python_pieces.py --calls 400
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable

from harness import Record, best_of

from frictiondisk.engine.worker import run_scene, warm_up
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation import pack
from frictiondisk.simulation.buffers import RunBuffers
from frictiondisk.simulation.result_builder import build_result, run_facts
from frictiondisk.simulation.rodas_method import energy_balance
from frictiondisk.simulation.simulate import DEFAULT_VERDICT, simulate
from frictiondisk.store.journal_entry import encode, run_key
from frictiondisk.tasks.campaign import campaign_from_text
from frictiondisk.verdict.label import label

SCAN = """\
name: pieces
scene: pin
params: {{x_ms: 0.1}}
scan:
  mu: {{start: 0.13, stop: 0.30, num: {num}}}
  mode: decide
"""


def least(piece: Callable[[], object], calls: int) -> float:
    """The least wall time [us] of `calls` calls of piece()."""
    best = float("inf")
    for _ in range(calls):
        t0 = time.perf_counter()
        piece()
        best = min(best, time.perf_counter() - t0)
    return 1e6 * best


def least_around(call: Callable[[], object], calls: int) -> float:
    """The least wall time [us] of call() less its result's kernel time (a summary's or a
    result's wall_s)."""
    best = float("inf")
    for _ in range(calls):
        t0 = time.perf_counter()
        out = call()
        wall = time.perf_counter() - t0
        kernel = out["wall_s"] if isinstance(out, dict) else out.wall_s
        best = min(best, wall - kernel)
    return 1e6 * best


def packed(config) -> RunBuffers:
    """The step loop's inputs of `config`, as simulate_rodas packs them (no recording)."""
    p, pts = pack.pack_parameters(config)
    y0 = pack.initial_state(config)
    modes = pack.initial_modes(p, pts, y0)
    if not hasattr(pack, "new_options"):  # an older tree: records filled in place
        run = RunBuffers.allocate(y0, modes, 1, p, pts, thresholds=DEFAULT_VERDICT)
        pack.fill_options(run.options, config.numerics, False, 0.0, False)
        pack.fill_rules(run.rules, config)
        return run
    options = pack.new_options(config.numerics, False, 0.0, False)
    rules = pack.new_rules(config)
    return RunBuffers.allocate(
        y0, modes, 1, p, pts, thresholds=DEFAULT_VERDICT, options=options, rules=rules
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=2_000, help="calls of each piece")
    parser.add_argument("--points", type=int, default=4_000, help="points of the timed scan")
    args = parser.parse_args(argv)
    warm_up()
    calls = args.calls
    campaign = campaign_from_text(SCAN.format(num=args.points), "<bench_python_pieces>")
    points_s, points = best_of(campaign.points, 3)
    planner_s, _ = best_of(lambda: campaign.entry.planner(campaign), 3)
    config = points[len(points) // 2].config
    canonical = config.canonical()
    result = simulate(config)
    summary = result.summary()
    run = packed(config).run()
    energy = energy_balance(1.0, 1.0, 0.0, 0.0)
    facts = run_facts(config, run, DEFAULT_VERDICT)
    key = run_key(config)
    base = campaign.base
    fixed = campaign.task.point_overrides()
    mu = config.params.mu

    pieces = {
        "worker: run_scene, Python around the kernel": lambda: least_around(
            lambda: run_scene(canonical), calls
        ),
        "worker: simulate, Python around the kernel": lambda: least_around(
            lambda: simulate(config), calls
        ),
        "worker: scene_from_dict(canonical)": lambda: least(
            lambda: scene_from_dict(canonical), calls
        ),
        "worker: pack (parameters, state, modes, buffers, options, rules)": lambda: least(
            lambda: packed(config), calls
        ),
        "worker: build_result": lambda: least(
            lambda: build_result(config, run, 0.0, None, energy, verdict=DEFAULT_VERDICT), calls
        ),
        "worker: run_facts": lambda: least(lambda: run_facts(config, run, DEFAULT_VERDICT), calls),
        "worker: label": lambda: least(lambda: label(facts, config, DEFAULT_VERDICT), calls),
        "worker: summary()": lambda: least(result.summary, calls),
        "driver: config.canonical()": lambda: least(config.canonical, calls),
        "driver: run_key(config)": lambda: least(lambda: run_key(config), calls),
        "driver: with_overrides (one point)": lambda: least(
            lambda: base.with_overrides({"params.mu": mu, **fixed}), calls
        ),
        "driver: journal encode": lambda: least(lambda: encode(key, canonical, summary), calls),
    }
    record = Record("python_pieces")
    for name, measure in pieces.items():
        value = measure()
        record.number(f"{name}, least", value, "us")
        print(f"{name:<66} {value:8.1f} us", flush=True)
    per_point = 1e6 * points_s / len(points)
    n = len(points)
    print(f"{f'driver: campaign.points(), per point of {n} (least of 3)':<66} {per_point:8.1f} us")
    print(f"{f'driver: the planner made, {n} points (least of 3)':<66} {1e3 * planner_s:8.1f} ms")
    record.number("driver: campaign.points(), per point", per_point, "us")
    record.number("driver: planner made", 1e3 * planner_s, "ms")
    record.write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
