"""Searches run in this process, on a small thread pool (the kernel releases the GIL),
without Dask or a journal: what a study that measures cost runs on (`run_study`; the
accuracy study, frictiondisk.studies.accuracy.study)."""

from __future__ import annotations

import concurrent.futures
import os
import time
from typing import Any

from frictiondisk.engine.progress import progress_bar
from frictiondisk.engine.worker import run_search, warm_up
from frictiondisk.tasks.jobs import RunSearch

# A directory no journal can live in: Journal.peek finds nothing there, so every run is
# computed (a cost study must not read cached runs).
NO_JOURNAL = os.devnull


def run_searches(
    searches: dict[Any, RunSearch],
    workers: int = 1,
    labels: dict[Any, str] | None = None,
    progress: bool = True,
    name: str = "searches",
    unit: str = "search",
) -> dict[Any, Any]:
    """Run every search to its end on `workers` threads; {key: the finished search}. A
    progress bar (stderr) shows each one's label as it finishes."""
    finished: dict[Any, Any] = {}
    bar = progress_bar(len(searches), name, unit, disable=not progress)
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        futures = {
            pool.submit(run_search, job.search, job.scene_of, NO_JOURNAL, job.budget_s): key
            for key, job in searches.items()
        }
        for future in concurrent.futures.as_completed(futures):
            key = futures[future]
            finished[key], _ = future.result()
            if bar is not None:
                bar.set_postfix_str((labels or {}).get(key, str(key))[:40])
                bar.update()
    if bar is not None:
        bar.close()
    return finished


def run_study(study, workers: int = 1, progress: bool = True):
    """Run a study's searches here (`study.searches()`, `labels()`, `name`, `unit`,
    `to_dataset(finished, wall, workers)`: the accuracy study) after compiling the kernel,
    timed; its Dataset."""
    warm_up()  # compile (or load) the kernel before anything is timed
    wall0 = time.perf_counter()
    searches = study.searches()
    finished = run_searches(searches, workers, study.labels(), progress, study.name, study.unit)
    return study.to_dataset(finished, time.perf_counter() - wall0, workers)
