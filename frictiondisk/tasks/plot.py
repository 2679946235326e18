"""The figure of a campaign, drawn by its task (the entry in frictiondisk.tasks.registry):
`plot_campaign` from its Datasets, `figure_for_dir` from its directory alone (what
`frictiondisk plot DIR` and `frictiondisk.plot_results` draw). Never simulates. Like every
figure: a matplotlib Figure, no backend, no pyplot (save it with
frictiondisk.figures.plotting.save_figure)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from frictiondisk.store.campaign_files import CampaignFileError, load_dataset
from frictiondisk.store.layout import RESULTS_FILE, RUNS_FILE
from frictiondisk.tasks.entry import TaskEntry
from frictiondisk.tasks.registry import TASKS


def entry_of(results) -> TaskEntry:
    """The entry of the task whose results.nc `results` is; ValueError if it is none."""
    task = results.attrs.get("task")
    if task not in TASKS:
        raise ValueError(
            f"results attribute 'task' is {task!r}; expected one of {', '.join(TASKS)} "
            "(not a frictiondisk campaign result?)"
        )
    return TASKS[task]


def plot_campaign(results, runs=None, *, show_runs: bool = False, **inputs: Any):
    """The figure that fits a campaign's results.nc `results` (runs.nc `runs` for
    `show_runs`; `boundary`, `files`: see TaskEntry.figure)."""
    return entry_of(results).figure(results, runs, show_runs=show_runs, **inputs)


def figure_for_dir(
    out_dir: Path,
    show_runs: bool = False,
    note: Callable[[str], Any] | None = None,
    boundary: Path | Sequence[Path] | None = None,
):
    """The Figure of the campaign in `out_dir`, from its netCDF files alone.

    `show_runs` overlays the runs of a task that shows them (ignored for the others, with
    a message to `note`, a callable taking text, if given). `boundary`: campaign
    directories drawn on top, of the tasks the figure's task takes (TaskEntry.
    boundary_tasks: a find_jump's mu* grid on a basin map, trace curves on a motion map).
    Raises CampaignFileError naming the file if one is missing, damaged or cannot be
    drawn."""
    out_dir = Path(out_dir)
    results = load_dataset(out_dir / RESULTS_FILE, out_dir)
    if results.attrs.get("partial") and not results.attrs.get("points_done"):
        raise CampaignFileError(
            f"{out_dir / RESULTS_FILE}: nothing to draw, no point is finished yet "
            f"(partial: 0 of {results.attrs.get('points_total', '?')} points)",
            [f"the campaign was stopped early; continue with: frictiondisk resume {out_dir}"],
        )
    try:
        entry = entry_of(results)
    except ValueError as exc:
        path = out_dir / RESULTS_FILE
        raise CampaignFileError(f"{path}: cannot draw this file", [str(exc)]) from None
    runs = _runs(entry, out_dir, show_runs, note)
    paths = (boundary,) if isinstance(boundary, str | Path) else tuple(boundary or ())
    drawn = _boundaries(entry, out_dir, paths, note)
    files = {name: load_dataset(out_dir / name, out_dir) for name in entry.figure_files}
    try:
        return entry.figure(results, runs, show_runs=runs is not None, boundary=drawn, files=files)
    except ValueError as exc:
        text = str(exc)
        if text.startswith("boundary"):
            path = Path(paths[0]) / RESULTS_FILE if len(paths) == 1 else out_dir / RESULTS_FILE
        elif text.startswith("runs"):
            path = out_dir / RUNS_FILE
        else:
            path = out_dir / (entry.figure_files or (RESULTS_FILE,))[0]
        raise CampaignFileError(f"{path}: cannot draw this file", [text]) from None


def _runs(entry: TaskEntry, out_dir: Path, show_runs: bool, note):
    """runs.nc, if asked for and the task shows its runs (else a note why not)."""
    if show_runs and entry.shows_runs:
        return load_dataset(out_dir / RUNS_FILE, out_dir)
    if show_runs and note is not None:
        showing = " and ".join(name for name, e in TASKS.items() if e.shows_runs)
        note(
            f"note: --runs applies to {showing} campaigns; in a {entry.name} every "
            "run is a point already"
        )
    return None


def _boundaries(entry: TaskEntry, out_dir: Path, paths: tuple, note) -> tuple:
    """The results.nc of each campaign in `paths` to draw on the figure, if the task draws
    such campaigns (else a note why not); CampaignFileError naming a file of another task."""
    if not paths:
        return ()
    if not entry.boundary_tasks:
        if note is not None:
            takers = " and ".join(
                f"{name} ({', '.join(e.boundary_tasks)})"
                for name, e in TASKS.items()
                if e.boundary_tasks
            )
            note(f"note: --boundary applies to {takers} campaigns; {out_dir} holds a {entry.name}")
        return ()
    drawn = []
    for folder in map(Path, paths):
        path = folder / RESULTS_FILE
        results = load_dataset(path, folder)
        if results.attrs.get("task") not in entry.boundary_tasks or "mu_star" not in results:
            raise CampaignFileError(
                f"{path}: cannot draw this file",
                [
                    f"boundary: expected a {' or '.join(entry.boundary_tasks)} results.nc (with mu_star)"
                ],
            )
        drawn.append(results)
    return tuple(drawn)
