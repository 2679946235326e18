"""Identical results: run every shipped campaign and compare its files with a snapshot.

A refactor proves itself by identical results. This tool runs every campaign file under
campaigns/ (one by one, each into OUT/<name>/, resumable), writes a digest of every netCDF
file they leave (each variable's dtype, shape and SHA-256 of its values; timing variables
and the history attribute left out), and compares two such runs or a run with a digest::

    python -m frictiondisk.studies.identical run -o out/identical
    python -m frictiondisk.studies.identical digest out/identical -o digest.json
    python -m frictiondisk.studies.identical compare digest.json out/identical     # with a digest
    python -m frictiondisk.studies.identical compare out/before out/after   # run by run

Comparing two run folders names every run and variable that differs; comparing with a
digest names the variables (the digest keeps no values). Exit code 1 if anything differs.
`--allow VAR` leaves a variable out of the comparison (say what changed on purpose, e.g.
`--allow runs.nc:reason`).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

# variables that measure the machine, not the result
TIMING_VARIABLES = frozenset({"wall_s", "kernel_s", "elapsed_s", "run_wall_s"})
# attributes that carry a date, a host or a timing (a trajectory file's wall_s)
VOLATILE_ATTRIBUTES = frozenset({"history", "date_created", "date_modified"}) | TIMING_VARIABLES
# campaigns that only describe a scene (no task): `frictiondisk simulate` reads them
SCENE_FILES = frozenset({"demo_pin"})


def shipped_campaigns(folder: Path) -> list[Path]:
    """Every campaign file under `folder` (scene-only files left out), sorted by name."""
    return sorted(p for p in folder.glob("*.yaml") if p.stem not in SCENE_FILES)


def run_all(campaigns: Path, out: Path, python: str = sys.executable) -> int:
    """Run each shipped campaign into out/<name>/ (a finished one is resumed, which
    recomputes nothing). Returns the number of campaigns that exited non-zero."""
    out.mkdir(parents=True, exist_ok=True)
    failed = 0
    for path in shipped_campaigns(campaigns):
        target = out / path.stem
        start = time.perf_counter()
        with open(out / f"{path.stem}.log", "w") as log:
            rc = subprocess.call(
                [python, "-m", "frictiondisk.cli", "run", str(path), "-o", str(target)],
                stdout=log,
                stderr=subprocess.STDOUT,
            )
        failed += rc != 0
        print(f"{path.stem:40s} rc={rc} {time.perf_counter() - start:7.1f} s", flush=True)
    return failed


def _canonical(values: np.ndarray) -> bytes:
    """The bytes of an array with every NaN made the same NaN (so equal means equal)."""
    if values.dtype.kind == "f":
        values = np.where(np.isnan(values), np.nan, values)
    if values.dtype.kind in "OUS":
        return "\x1f".join(str(v) for v in values.ravel()).encode()
    return np.ascontiguousarray(values).tobytes()


def _open(path: Path):
    import xarray as xr

    return xr.open_dataset(path, decode_times=False, mask_and_scale=False).load()


def file_digest(path: Path) -> dict:
    """{variable: "dtype shape sha256"} and {attr: sha256} of one netCDF file."""
    ds = _open(path)
    variables = {}
    for name in sorted(list(ds.data_vars) + list(ds.coords)):
        if name in TIMING_VARIABLES:
            continue
        values = ds[name].values
        sha = hashlib.sha256(_canonical(values)).hexdigest()[:20]
        variables[str(name)] = f"{values.dtype.str} {values.shape} {sha}"
    attrs = {
        k: hashlib.sha256(str(v).encode()).hexdigest()[:20]
        for k, v in sorted(ds.attrs.items())
        if k not in VOLATILE_ATTRIBUTES
    }
    ds.close()
    return {"variables": variables, "attrs": attrs}


def digest(root: Path) -> dict:
    """{campaign: {file: file_digest}} for every netCDF file under root/<campaign>/."""
    found = {}
    for folder in sorted(p for p in root.iterdir() if p.is_dir()):
        files = sorted(folder.glob("*.nc"))
        if files:
            found[folder.name] = {f.name: file_digest(f) for f in files}
    return found


def _differences_in_values(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    if a.dtype.kind == "f" and b.dtype.kind == "f":
        return ~((a == b) | (np.isnan(a) & np.isnan(b)))
    return a != b


def compare_files(before: Path, after: Path, allow: set[str], limit: int = 5) -> list[str]:
    """Every difference between two netCDF files, run by run where they have a `run`
    dimension (`allow`: 'file:variable' or 'variable' names left out)."""
    a, b = _open(before), _open(after)
    lines = []
    names = sorted(set(a.variables) | set(b.variables))
    for name in names:
        if name in TIMING_VARIABLES or name in allow or f"{before.name}:{name}" in allow:
            continue
        if name not in a.variables or name not in b.variables:
            lines.append(f"{name}: only in {'after' if name in b.variables else 'before'}")
            continue
        va, vb = a[name].values, b[name].values
        if va.shape != vb.shape:
            lines.append(f"{name}: shape {va.shape} -> {vb.shape}")
            continue
        diff = _differences_in_values(va, vb)
        if np.any(diff):
            where = np.argwhere(diff)
            shown = ", ".join(
                f"{tuple(int(i) for i in idx)}: {va[tuple(idx)]!r} -> {vb[tuple(idx)]!r}"
                for idx in where[:limit]
            )
            more = f" (+{len(where) - limit} more)" if len(where) > limit else ""
            lines.append(f"{name}: {len(where)} differ: {shown}{more}")
    for key in sorted(set(a.attrs) | set(b.attrs)):
        if key in VOLATILE_ATTRIBUTES or f"attr:{key}" in allow:
            continue
        if str(a.attrs.get(key)) != str(b.attrs.get(key)):
            lines.append(f"attribute {key}: {a.attrs.get(key)!r} -> {b.attrs.get(key)!r}")
    return lines


def _compare_digests(before: dict, after: dict, allow: set[str]) -> list[str]:
    lines = []
    for campaign in sorted(set(before) | set(after)):
        if campaign not in after or campaign not in before:
            lines.append(f"{campaign}: only {'after' if campaign in after else 'before'}")
            continue
        for name in sorted(set(before[campaign]) | set(after[campaign])):
            fa, fb = before[campaign].get(name), after[campaign].get(name)
            if fa is None or fb is None:
                lines.append(f"{campaign}/{name}: only {'after' if fb else 'before'}")
                continue
            for var in sorted(set(fa["variables"]) | set(fb["variables"])):
                if var in allow or f"{name}:{var}" in allow:
                    continue
                if fa["variables"].get(var) != fb["variables"].get(var):
                    lines.append(f"{campaign}/{name}: {var} differs")
            for key in sorted(set(fa["attrs"]) | set(fb["attrs"])):
                if f"attr:{key}" not in allow and fa["attrs"].get(key) != fb["attrs"].get(key):
                    lines.append(f"{campaign}/{name}: attribute {key} differs")
    return lines


def campaign_folders(root: Path) -> list[Path]:
    """The run folders under `root`: root itself where it holds netCDF files (one
    campaign's folder), else each of its sub-folders that does."""
    if any(root.glob("*.nc")):
        return [root]
    return sorted(p for p in root.iterdir() if p.is_dir() and any(p.glob("*.nc")))


def compare(before: Path, after: Path, allow: set[str]) -> list[str]:
    """Differences between two run folders (run by run) or a digest and a run folder.
    Either folder is one campaign's folder or a folder of them; comparing no netCDF file
    at all is an error, never `identical`."""
    if before.is_file():
        return _compare_digests(json.loads(before.read_text()), digest(after), allow)
    folders = campaign_folders(before)
    if not folders:
        raise SystemExit(f"error: no netCDF file under {before}: nothing to compare")
    single = folders == [before]
    lines = []
    for folder in folders:
        other = after if single else after / folder.name
        for nc in sorted(folder.glob("*.nc")):
            if not (other / nc.name).exists():
                lines.append(f"{folder.name}/{nc.name}: missing after")
                continue
            lines += [
                f"{folder.name}/{nc.name}: {d}" for d in compare_files(nc, other / nc.name, allow)
            ]
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run every shipped campaign into OUT/<name>/")
    run.add_argument("-o", "--out", type=Path, required=True)
    run.add_argument("--campaigns", type=Path, default=Path("campaigns"))
    dig = sub.add_parser("digest", help="write the digest of a run folder")
    dig.add_argument("folder", type=Path)
    dig.add_argument("-o", "--out", type=Path, required=True)
    cmp = sub.add_parser("compare", help="compare a digest or run folder with a run folder")
    cmp.add_argument("before", type=Path)
    cmp.add_argument("after", type=Path)
    cmp.add_argument("--allow", action="append", default=[], help="variable left out")
    args = parser.parse_args(argv)
    if args.command == "run":
        return 1 if run_all(args.campaigns, args.out) else 0
    if args.command == "digest":
        args.out.write_text(json.dumps(digest(args.folder), indent=1, sort_keys=True) + "\n")
        return 0
    lines = compare(args.before, args.after, set(args.allow))
    for line in lines:
        print(line)
    print(f"{len(lines)} differences" if lines else "identical")
    return 1 if lines else 0


if __name__ == "__main__":
    raise SystemExit(main())
