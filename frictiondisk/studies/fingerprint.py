"""Run-level fingerprints: every field of a `SimulationResult` over a fixed list of scenes.

The proof, scene by scene and bit for bit, that a refactor of the kernel, the verdict or
the simulation layer leaves every run as it was. The scene list
(frictiondisk/studies/fingerprint_scenes.json) covers every path a run can take: pin and
disk, stick_rule contacts and corotation, modes decide and converge, evidence extrapolate
and observe, braked disks decided by the shakedown bound, Stribeck friction, recorded
trajectories, the methods rodas4, rodas4-fixed, scipy-radau and coulomb, the dense LU,
exhausted step and event budgets, a degenerate stick after 0 steps, and runs sampled from
the shipped campaigns' journals. A fingerprint holds, per scene, every scalar field (floats
as exact hex), the SHA-256 of every column of the revolution and section logs (by name) and
of every trajectory array; wall_s is kept apart (timing, never compared).

It runs as a plain script, importing only the public `simulate` and `scene_from_dict`, so
the same file fingerprints another tree (an older commit) with PYTHONPATH pointing there::

    PYTHONPATH=/work/baseline python frictiondisk/studies/fingerprint.py run -o base.json
    PYTHONPATH=$PWD python frictiondisk/studies/fingerprint.py run -o mine.json
    python frictiondisk/studies/fingerprint.py compare base.json mine.json

`--tier quick` runs the scenes that take a few seconds at most; `--tier all` (default)
adds the slow ones. Exit code 1 from `compare` if anything differs.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

SCENES = Path(__file__).resolve().with_name("fingerprint_scenes.json")
# Column names of the revolution log and the section log, in the order of the numbered
# columns they replace (older trees hold 2-D float arrays; newer ones structured arrays
# with these field names).
REVOLUTION_COLUMNS = (
    "t",
    "slip",
    "drift_r",
    "drift_phi",
    "switches",
    "all_stuck",
    "any_stuck",
    "ever_all",
    "still",
    "stick_t",
    "x",
    "y",
    "u",
    "v",
    "w",
    "reserve",
)
SECTION_COLUMNS = ("t0", "t1", "x", "y", "slip", "steps")
TRAJECTORY_FIELDS = ("t", "x", "y", "vx", "vy", "phi", "phidot", "Zx", "Zy", "mode")
TIMING = frozenset({"wall_s"})


def _digest(values: np.ndarray) -> str:
    """dtype-free SHA-256 of an array's values as float64 (every NaN the same NaN)."""
    values = np.asarray(values, dtype=np.float64)
    values = np.where(np.isnan(values), np.nan, values)
    return f"{values.shape} " + hashlib.sha256(np.ascontiguousarray(values).tobytes()).hexdigest()


def _scalar(value):
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        value = float(value)
        return "nan" if math.isnan(value) else value.hex()
    return value


def _columns(log, names: tuple[str, ...]) -> dict[str, str] | None:
    """{column name: digest} of a revolution or section log, 2-D or structured."""
    if log is None:
        return None
    log = np.asarray(log)
    if log.dtype.names:
        return {name: _digest(log[name]) for name in log.dtype.names}
    return {name: _digest(log[:, k]) for k, name in enumerate(names)}


def fingerprint(result) -> tuple[dict, float]:
    """(fingerprint, wall time [s]) of one SimulationResult."""
    out: dict = {}
    for name, value in vars(result).items():
        if name in TIMING:
            continue
        if name == "revolutions":
            out[name] = _columns(value, REVOLUTION_COLUMNS)
        elif name == "sections":
            out[name] = _columns(value, SECTION_COLUMNS)
        elif name == "own_section":  # the motion's own section (structured rows)
            out[name] = _columns(value, ())
        elif name == "trajectory":
            out[name] = (
                None
                if value is None
                else {
                    **{
                        f: (None if getattr(value, f) is None else _digest(getattr(value, f)))
                        for f in TRAJECTORY_FIELDS
                    },
                    "truncated": bool(value.truncated),
                }
            )
        else:
            out[name] = _scalar(value)
    return out, float(result.wall_s)


def load_scenes(tier: str, path: Path = SCENES) -> list[dict]:
    """The scene list, the quick tier only or all of it."""
    scenes = json.loads(path.read_text())["scenes"]
    return [s for s in scenes if tier == "all" or s["tier"] == "quick"]


def run_one(entry: dict):
    """simulate() the scene of one entry and return its SimulationResult."""
    from frictiondisk.model.scene import scene_from_dict
    from frictiondisk.simulation.simulate import simulate

    config = scene_from_dict(entry["scene"])
    if entry.get("unchecked_params"):  # past validation, as tests/test_hostile_inputs.py does
        params = config.params.model_copy(update=entry["unchecked_params"])
        config = config.model_copy(update={"params": params})
    kwargs = {"dense_lu": True} if entry.get("dense_lu") else {}
    return simulate(config, entry.get("record", False), entry.get("dt_out", 0.0), **kwargs)


def run(tier: str, out: Path, names: list[str] | None = None) -> int:
    from frictiondisk.simulation import simulate

    scenes = load_scenes(tier)
    if names:
        scenes = [s for s in scenes if s["name"] in names]
    versions = {}
    for lib in ("numba", "numpy", "scipy"):
        versions[lib] = __import__(lib).__version__
    tree = str(Path(simulate.__file__).parents[1])
    record = {"tree": tree, "versions": versions, "runs": {}}
    start = time.perf_counter()
    for k, entry in enumerate(scenes):
        result = run_one(entry)
        prints, wall = fingerprint(result)
        record["runs"][entry["name"]] = {"fingerprint": prints, "wall_s": wall}
        print(f"{k + 1:4d}/{len(scenes)} {wall:8.3f} s  {result.outcome:12s} {entry['name']}")
    out.write_text(json.dumps(record, indent=1, sort_keys=True))
    print(f"{len(scenes)} scenes in {time.perf_counter() - start:.1f} s -> {out}")
    return 0


def differences(a: dict, b: dict) -> list[str]:
    """Every scene and field where fingerprint record b differs from a (scenes only one of
    them ran are left out)."""
    found = []
    for name in sorted(set(a["runs"]) & set(b["runs"])):
        fa, fb = a["runs"][name]["fingerprint"], b["runs"][name]["fingerprint"]
        for field in sorted(set(fa) | set(fb)):
            va, vb = fa.get(field, "<absent>"), fb.get(field, "<absent>")
            if isinstance(va, dict) and isinstance(vb, dict):
                for sub in sorted(set(va) | set(vb)):
                    if va.get(sub, "<absent>") != vb.get(sub, "<absent>"):
                        found.append(f"{name}: {field}.{sub}")
            elif va != vb:
                found.append(f"{name}: {field}: {va!r} != {vb!r}")
    return found


def compare(path_a: Path, path_b: Path) -> int:
    a, b = json.loads(path_a.read_text()), json.loads(path_b.read_text())
    common = set(a["runs"]) & set(b["runs"])
    found = differences(a, b)
    for line in found:
        print(line)
    wall_a = sum(a["runs"][n]["wall_s"] for n in common)
    wall_b = sum(b["runs"][n]["wall_s"] for n in common)
    print(
        f"{len(common)} scenes compared: {len(found)} differences "
        f"(kernel time {wall_a:.1f} s vs {wall_b:.1f} s)"
    )
    return 1 if found else 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p_run = sub.add_parser("run", help="fingerprint every scene of the list")
    p_run.add_argument("-o", "--out", type=Path, required=True)
    p_run.add_argument("--tier", choices=("quick", "all"), default="all")
    p_run.add_argument("--only", nargs="*", help="scene names")
    p_cmp = sub.add_parser("compare", help="compare two fingerprint files")
    p_cmp.add_argument("a", type=Path)
    p_cmp.add_argument("b", type=Path)
    args = parser.parse_args(argv)
    if args.command == "run":
        return run(args.tier, args.out, args.only)
    return compare(args.a, args.b)


if __name__ == "__main__":
    sys.exit(main())
