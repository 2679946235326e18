"""python -m frictiondisk.studies.wellposed: the well-posedness study's command line.

    python -m frictiondisk.studies.wellposed -o out/wellposed            # seeds 1-10, 50 scenes each
    python -m frictiondisk.studies.wellposed -o out/wp --seeds 1 --scenes 4
    python -m frictiondisk.studies.wellposed -o out/wp --scene 1/43 --scene 2/0
    python -m frictiondisk.studies.wellposed -o out/wellposed2 --generator 2 --seeds 1-4
    # a change to the default's rules against the references an earlier run located:
    python -m frictiondisk.studies.wellposed -o out/d --reference-from out/wellposed
    # the exact Coulomb watches to 1 500 s, not 12 000 s:
    python -m frictiondisk.studies.wellposed -o out/wellposed --exact-horizon 1500

Prints the report (also written to OUT/report.txt); exit 1 if any default verdict is
settled against a certified default, or a certified bracket end contradicted by its
watch (a silent error).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from frictiondisk.studies.wellposed.judge import silent_errors
from frictiondisk.studies.wellposed.report import report
from frictiondisk.studies.wellposed.scenes import (
    GENERATORS,
    braked,
    draw,
    parse_scene,
    parse_seeds,
)
from frictiondisk.studies.wellposed.settings import DEFAULT_STEP
from frictiondisk.studies.wellposed.study import Options, run_study


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="python -m frictiondisk.studies.wellposed",
        description="Well-posedness study: is the certified headline mu* true, checked "
        "against a dense reference and settled run by run? (docs/wellposed.md)",
    )
    p.add_argument("-o", "--out", type=Path, required=True, help="output folder (resumable)")
    p.add_argument("--seeds", default="1-10", help="e.g. 1-10 or 1,3")
    p.add_argument("--scenes", type=int, default=50, help="scenes per seed")
    p.add_argument(
        "--scene",
        action="append",
        default=[],
        metavar="SEED/INDEX",
        help="these scenes only, e.g. --scene 1/43 --scene 2/0 (repeatable)",
    )
    p.add_argument(
        "--generator",
        type=int,
        choices=sorted(GENERATORS),
        default=1,
        help="scene generator: 1 the study's own (the rules were tuned on it), 2 an "
        "independent one with wider ranges (scenes.draw_scene2)",
    )
    p.add_argument("--workers", type=int, default=2, help="engine workers")
    p.add_argument(
        "--default-step",
        type=float,
        default=DEFAULT_STEP,
        help=f"prescan step of the default and uncertified settings (default {DEFAULT_STEP})",
    )
    p.add_argument(
        "--cost-only", action="store_true", help="no reference: the cost of certification only"
    )
    p.add_argument(
        "--observe", action="store_true", help="the default certifies watching (certify.observe)"
    )
    p.add_argument(
        "--reference-from",
        type=Path,
        default=None,
        help="take each scene's reference from an earlier study (its folder or rows file, "
        "or the JSON lines of the former benchmarks/study_wellposed.py --cache)",
    )
    subset = p.add_mutually_exclusive_group()
    subset.add_argument(
        "--braked-only",
        action="store_true",
        help="only the disks with a brake (beta_b > 0): a change to the co-rotation verdict",
    )
    subset.add_argument(
        "--unbraked-only", action="store_true", help="only the scenes without a brake"
    )
    p.add_argument(
        "--settled-from",
        type=Path,
        action="append",
        default=[],
        help="take settling runs at a disputed scene and mu from an earlier study (folder or "
        "rows file; repeatable): they watch, so a change to the rules leaves them as they were",
    )
    p.add_argument(
        "--exact-horizon",
        type=float,
        default=None,
        metavar="SECONDS",
        help="every exact Coulomb watch runs to this horizon [s] (default: the whole watch "
        "budget, 12 000 s; it costs about 0.06 s of wall time a simulated second)",
    )
    p.add_argument(
        "--recheck-confirmed",
        action="store_true",
        help="watch the confirmed bracket ends again at rtol / 100 too, not only the "
        "contradicted ones (the control of that check)",
    )
    return p


def jobs_of(args: argparse.Namespace) -> list[tuple[int, int]]:
    """The (seed, index) to run: --scene, else every scene of --seeds, then the subset."""
    if args.scene:
        jobs = [parse_scene(text) for text in args.scene]
    else:
        jobs = [(seed, k) for seed in parse_seeds(args.seeds) for k in range(args.scenes)]
    if args.braked_only or args.unbraked_only:
        jobs = [job for job in jobs if braked(draw(args.generator, *job)) == args.braked_only]
    return jobs


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    options = Options(
        workers=args.workers,
        reference=not args.cost_only,
        observe=args.observe,
        step=args.default_step,
        reference_from=args.reference_from,
        settled_from=tuple(args.settled_from),
        generator=args.generator,
        exact_horizon=args.exact_horizon,
        recheck_confirmed=args.recheck_confirmed,
    )
    t0 = time.perf_counter()
    rows = run_study(jobs_of(args), args.out, options)
    text = "\n".join(report(rows, time.perf_counter() - t0))
    print(text)
    (args.out / "report.txt").write_text(text + "\n")
    return 1 if silent_errors(rows) else 0


if __name__ == "__main__":
    sys.exit(main())
