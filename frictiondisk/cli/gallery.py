"""`make gallery`: draw every PNG under figures/ again from this code.

    python -m frictiondisk.cli.gallery [--runs DIR] [--out out/gallery] [--figures figures]
        [--only NAME ...] [--list]

`GALLERY` names every PNG of figures/ and the one command that draws it (a test holds the
two equal: tests/test_gallery.py). Each generator runs as its own process, from the
repository root, in the order below (the cheap ones first); its campaigns run or resume
into OUT/<campaign>/, and its PNGs are written into FIGURES.

`--runs DIR`: run folders made before, DIR/<campaign>/ as `frictiondisk run
campaigns/<campaign>.yaml -o DIR/<campaign>` leaves them (e.g. every shipped campaign run
once). A campaign folder that OUT does not hold yet is copied from DIR first (if DIR's
says `complete`), and the generator resumes the copy: a run is reused only if the journal
holds it under this code's numerics version (the version is part of every journal key),
so the figure is this code's either way, and a folder of older numerics is run again.
No figure needs campaigns/clutch_annulus.yaml.

Cost, measured 2026-11-28 one campaign or study at a time on the shared 2-core machine
(load 6-13; docs/user-guide.md, "The gallery"): the figure campaigns 15-21 min
(disk_xms_at_rest 5-7, each Fig 11 start 3-4), the basin campaigns 2-12, the accuracy
study of the pin 9 min, the brake study 11 min, the corotation
scans 30 s. Drawing from
finished run folders (--runs): about 2 min for the figure and basin campaigns.
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from frictiondisk.studies import atlas

PAPER = tuple(
    f"fig{name}"
    for name in (
        "04_trajectory",
        "05_limit_cycle",
        "06_a_mu",
        "07_pin_xms",
        "08_pin_x0",
        "09_disk_xms",
        "10_disk_x0",
        "11_betab_mu",
        "11_betab_mu_corotating",
    )
)
# campaigns drawn by `frictiondisk plot`'s figure: the paper's, the traced planes of
# docs/trace.md, the disk from rest of docs/brake.md and the pin line of `make demo` (README)
PLOTTED = (*PAPER, "trace_fig11_betab_mu", "trace_stribeck_pin", "disk_xms_at_rest", "demo_line")
BASIN = ("basin_pin_x0", "basin_pin_map", "basin_pin_boundary", "basin_disk_map")
# the motion maps (pin, braked disk) and the traced boundaries drawn on them
ATLAS = atlas.campaign_names()


@dataclass(frozen=True)
class Generator:
    """One command of the gallery and the PNGs it leaves in FIGURES.

    `command`: the arguments after `python`, where {out}, {figures} and {campaigns} stand
    for the folders of the call; `campaigns`: the run folders it resumes from OUT (copied
    from --runs); `copies`: (file under OUT, PNG name) pairs copied into FIGURES after it."""

    name: str
    outputs: tuple[str, ...]
    command: tuple[str, ...]
    campaigns: tuple[str, ...] = ()
    copies: tuple[tuple[str, str], ...] = ()


def _accuracy(name: str, figure: str, *options: str) -> Generator:
    """`frictiondisk accuracy` of campaigns/NAME.yaml, its work-precision figure as FIGURE."""
    command = ("-m", "frictiondisk.cli", "accuracy", f"{{campaigns}}/{name}.yaml")
    return Generator(
        name,
        (figure,),
        (*command, "-o", f"{{out}}/{name}", *options),
        copies=((f"{name}/work_precision.png", figure),),
    )


GALLERY: tuple[Generator, ...] = (
    Generator(
        "figures",
        (*(f"{name}.png" for name in PLOTTED), "fig11_bounds.png"),
        ("-m", "frictiondisk.cli.figure_campaigns", "--campaigns", "{campaigns}")
        + ("--out", "{out}", "--figures", "{figures}", "--formats", "png", "--only", *PLOTTED),
        campaigns=PLOTTED,
    ),
    Generator(
        "basin",
        tuple(f"{name}.png" for name in ("basin_pin_x0", "basin_pin_map", "basin_disk_map")),
        ("-m", "frictiondisk.studies.basin", "--campaigns", "{campaigns}")
        + ("-o", "{out}", "--figures", "{figures}"),
        campaigns=BASIN,
    ),
    Generator(
        "atlas",
        tuple(f"{name}.png" for name in atlas.FIGURES),
        ("-m", "frictiondisk.studies.atlas", "--campaigns", "{campaigns}")
        + ("-o", "{out}", "--figures", "{figures}"),
        campaigns=ATLAS,
    ),
    _accuracy("accuracy_pin", "work_precision_pin.png"),
    Generator(
        "corotation",
        ("brake_drift.png",),
        ("-m", "frictiondisk.studies.corotation", "-o", "{out}/corotation")
        + ("--figure", "{figures}/brake_drift.png"),
    ),
    Generator(
        "brake",
        ("brake_admissibility.png", "brake_rotation_term.png"),
        ("-m", "frictiondisk.studies.brake", "-o", "{out}/brake", "--figures", "{figures}"),
    ),
)


def outputs() -> list[str]:
    """Every PNG name the gallery writes into FIGURES."""
    return [name for generator in GALLERY for name in generator.outputs]


def seed(names: tuple[str, ...], runs: Path, out: Path) -> None:
    """Copy each finished run folder RUNS/<name> that OUT does not hold yet into OUT."""
    for name in names:
        source, target = runs / name, out / name
        if target.exists():
            print(f"  {name}: resuming {target}", flush=True)
            continue
        status = source / "status.json"
        state = json.loads(status.read_text()).get("state") if status.is_file() else None
        if state != "complete":
            print(f"  {name}: {source} is not a complete run folder ({state}): runs here")
            continue
        shutil.copytree(source, target, ignore=shutil.ignore_patterns("lock"))
        print(f"  {name}: copied from {source}", flush=True)


def run_generator(generator: Generator, args: argparse.Namespace) -> int:
    """Run one generator (seeded from --runs); its exit status."""
    folders = {"out": args.out, "figures": args.figures, "campaigns": args.campaigns}
    if args.runs is not None:
        seed(generator.campaigns, args.runs, args.out)
    command = [sys.executable, *(part.format(**folders) for part in generator.command)]
    print(f"== {generator.name}: {' '.join(command[1:])}", flush=True)
    start = time.perf_counter()
    status = subprocess.run(command, check=False).returncode
    for source, name in generator.copies:
        if status == 0:
            shutil.copyfile(args.out / source, args.figures / name)
    print(f"== {generator.name}: exit {status}, {time.perf_counter() - start:.0f} s", flush=True)
    return status


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=Path, help="finished run folders to start from")
    parser.add_argument("--out", type=Path, default=Path("out/gallery"))
    parser.add_argument("--figures", type=Path, default=Path("figures"))
    parser.add_argument("--campaigns", type=Path, default=Path("campaigns"))
    names = [generator.name for generator in GALLERY]
    parser.add_argument("--only", nargs="+", choices=names, help="these generators only")
    parser.add_argument("--list", action="store_true", help="print each generator's PNGs")
    args = parser.parse_args(argv)
    chosen = [g for g in GALLERY if args.only is None or g.name in args.only]
    if args.list:
        for generator in chosen:
            print(f"{generator.name}: {' '.join(generator.outputs)}")
        return 0
    args.out.mkdir(parents=True, exist_ok=True)
    args.figures.mkdir(parents=True, exist_ok=True)
    failed = [g.name for g in chosen if run_generator(g, args) != 0]
    if failed:
        print(f"failed: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
