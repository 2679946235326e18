"""The study's rows on disk: OUT/rows.jsonl, one JSON line per scene.

A row is derived from its campaigns (the journals are the record); the file is what a
later study reads an earlier one's references and watches from (--reference-from,
--settled-from) and what `wellposed.longer` reads. It has the line format of the former
benchmarks/study_wellposed.py --cache files ({"seed", "index", "row"}; their "code" is
ignored), so those are read too.
"""

from __future__ import annotations

import json
from pathlib import Path

from frictiondisk.studies.wellposed.found import Found
from frictiondisk.studies.wellposed.settings import SETTINGS

ROWS_FILE = "rows.jsonl"


def to_json(row: dict) -> dict:
    return {k: v.to_json() if isinstance(v, Found) else v for k, v in row.items()}


def from_json(row: dict) -> dict:
    out = dict(row)
    for setting in (s for s in SETTINGS if s in row):
        out[setting] = Found.from_json(row[setting])
    return out


def rows_path(path: Path) -> Path:
    """A rows file, or the rows file of a study folder."""
    path = Path(path)
    return path / ROWS_FILE if path.is_dir() else path


def read_rows(path: Path) -> dict[tuple[int, int], dict]:
    """(seed, index) -> row, of a rows file or a study folder (the last line of a scene wins)."""
    rows = {}
    for line in rows_path(path).read_text().splitlines():
        entry = json.loads(line)
        rows[(entry["seed"], entry["index"])] = from_json(entry["row"])
    return rows


def write_rows(out: Path, rows: list[dict]) -> Path:
    """OUT/rows.jsonl, rewritten whole (written beside, then moved over the old one)."""
    path = Path(out) / ROWS_FILE
    temporary = path.with_suffix(".tmp")
    with temporary.open("w") as file:
        for row in rows:
            entry = {"seed": row["seed"], "index": row["index"], "row": to_json(row)}
            file.write(json.dumps(entry) + "\n")
    temporary.replace(path)
    return path


def known_watches(paths: list[Path]) -> dict[tuple[int, int], dict[float, dict]]:
    """(seed, index) -> mu -> every settling run in the rows of `paths`. A settling run
    watches (numerics.evidence observe): it reads neither the default's rules nor the
    bound, so a change to those leaves it as it was. A change to the watches' numerics
    (settings.SETTLE_*) or to the integration makes these stale: then run afresh."""
    known: dict[tuple[int, int], dict[float, dict]] = {}
    for path in paths:
        for key, row in read_rows(path).items():
            runs = row.get("settled", []) + row.get("persisted", []) + row.get("ends", [])
            scene = known.setdefault(key, {})
            for run in runs:
                scene[float(run["mu"])] = {k: v for k, v in run.items() if k != "reused"}
    return known
