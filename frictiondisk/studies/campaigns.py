"""How a study runs its work: campaigns on the engine and the journal, nothing of its own.

A study writes each piece of its work as a campaign (a dict, as a campaign file would
hold it), runs them together into one output folder, each into OUT/<name>/, and reads
their results.nc and runs.nc back. Every finished run is journaled the moment it comes
back, so a study stopped at any point resumes where it stopped: run the same command
again (a campaign already finished is replayed from its journal, computing nothing).

This module is the studies' one door to the engine (`run_campaigns` and
`campaign_from_dict` or `load_campaign`, the functions behind `frictiondisk.run_campaigns`
and `frictiondisk.load_campaign`; the package root ranks above studies in the layers, so a
study imports them from where they live).
"""

from __future__ import annotations

import argparse
import json
import time
from collections.abc import Iterable
from pathlib import Path
from typing import Any

CHUNK = 60  # campaigns handed to the engine at once (one Dask client, one driver loop)


def name_part(value: float) -> str:
    """A number as a campaign name may hold it (letters, digits, _ and -): 0.005 -> 0p005."""
    return f"{value:g}".replace(".", "p").replace("+", "")


def campaign(data: dict[str, Any]):
    """The validated campaign of a dict (a ConfigError names every bad key)."""
    from frictiondisk.tasks.campaign import campaign_from_dict

    return campaign_from_dict(data, source=f"<study campaign {data.get('name', '?')}>")


def campaign_file(path: Path):
    """The validated campaign of a campaign YAML file."""
    from frictiondisk.tasks.campaign import load_campaign

    return load_campaign(path)


def run(campaigns: Iterable, out: Path, workers: int = 2, chunk: int = CHUNK) -> int:
    """Run (or resume) `campaigns` (validated, or dicts) into out/<name>/, `chunk` of
    them per engine call; returns the runs computed now."""
    from frictiondisk.engine.runner import run_campaigns

    todo = [c if hasattr(c, "task") else campaign(c) for c in campaigns]
    computed = 0
    for start in range(0, len(todo), chunk):
        summaries = run_campaigns(todo[start : start + chunk], Path(out), workers, progress=False)
        computed += sum(summary.runs_computed for summary in summaries)
    return computed


def results(folder: Path, name: str = "results"):
    """A campaign folder's results.nc or runs.nc as an xarray Dataset, read into memory
    (what `frictiondisk.open_results` gives)."""
    import xarray as xr

    with xr.open_dataset(Path(folder) / f"{name}.nc") as ds:
        return ds.load()


def finished(folder: Path) -> bool:
    """Whether the campaign in `folder` ran to its end (its status.json says so)."""
    path = Path(folder) / "status.json"
    if not path.is_file():
        return False
    status = json.loads(path.read_text())
    return status.get("state") == "complete" and status["points_done"] == status["points_total"]


def figure_study_parser(prog: str, description: str, out: str) -> argparse.ArgumentParser:
    """The options of a study that runs shipped campaigns and draws their figures:
    --campaigns (the campaign files' folder), -o (the run folders), --figures, --workers."""
    parser = argparse.ArgumentParser(prog=prog, description=description)
    parser.add_argument("--campaigns", type=Path, default=Path("campaigns"))
    parser.add_argument("-o", "--out", type=Path, default=Path(out))
    parser.add_argument("--figures", type=Path, default=Path("figures"))
    parser.add_argument("--workers", type=int, default=2)
    return parser


def run_shipped(names: Iterable[str], folder: Path, out: Path, workers: int) -> int:
    """Run (or resume) the campaign files folder/<name>.yaml into out/<name>/, printing
    how many and how long; returns the runs computed now."""
    t0 = time.perf_counter()
    files = [campaign_file(folder / f"{name}.yaml") for name in names]
    computed = run(files, out, workers)
    print(f"{len(files)} campaigns, {computed} runs computed now, {time.perf_counter() - t0:.1f} s")
    return computed
