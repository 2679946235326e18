"""python -m frictiondisk.studies.brake: the brake study's command line (see the package)."""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from frictiondisk.studies.brake.figures import figure_admissibility, figure_rotation
from frictiondisk.studies.brake.micro_slip import part2
from frictiondisk.studies.brake.mu_star import part1
from frictiondisk.studies.brake.rotation_term import part3


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m frictiondisk.studies.brake",
        description="The braked disk: mu*(beta_b) against the admissibility bounds, "
        "micro-slip, and the rotation term (docs/brake.md)",
    )
    parser.add_argument("-o", "--out", type=Path, default=Path("out/brake"))
    parser.add_argument("--figures", type=Path, default=Path("figures"))
    parser.add_argument("--quick", action="store_true", help="fewer points and revolutions")
    parser.add_argument(
        "--no-radau", action="store_true", help="skip the scipy-radau mu* bisections"
    )
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    args.figures.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    rows = part1(args.quick, args.out, args.workers)
    micro = part2(args.quick)
    runs, mustar = part3(args.no_radau, args.quick)
    figure_admissibility(rows, micro, args.figures / "brake_admissibility.png")
    figure_rotation(runs, mustar, args.figures / "brake_rotation_term.png")
    summary = {
        "mu_star": rows,
        "micro_slip": micro,
        "rotation_term": {
            k: {
                "per_rev": v["per_rev"],
                "lag_rate_rad_per_rev": v["lag_rate"],
                "outcome": v["outcome"],
            }
            for k, v in runs.items()
        },
        "radau_mu_star": {k: list(v) for k, v in mustar.items()},
    }
    (args.out / "brake_study.json").write_text(json.dumps(summary, indent=1))
    print(
        f"\nfigures: {args.figures / 'brake_admissibility.png'}, "
        f"{args.figures / 'brake_rotation_term.png'}"
    )
    print(f"numbers: {args.out / 'brake_study.json'}  ({time.perf_counter() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
