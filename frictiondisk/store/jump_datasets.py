"""The variables of a find_jump with a prescan (frictiondisk.search.jumps): every jump of
every point (dim `jump`), its sticking windows (dim `window`), how much of the prescan
grid below mu* is decided, and the prescan runs (dim `scan_mu`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from frictiondisk.search.certify import CERTIFICATION_FLAGS
from frictiondisk.store.measures import RUN_MEASURES, num

CERTIFICATION_FILL = -1  # a padded jump slot (a point with fewer jumps than the most)


def all_jumps(campaign, planner, dims: tuple[str, ...]) -> dict[str, Any]:
    """Every jump of every point (dim `jump`, NaN-padded) and the prescan runs (dim
    `scan_mu`) of a find_jump with a prescan (frictiondisk.search.jumps)."""
    shape = campaign.shape
    results = [planner.results[i] for i in range(len(planner.points))]
    n_jump = max([1, *(len(r.jumps) for r in results)])
    n_window = max([1, *(len(r.windows) for r in results)])
    scan_mu = campaign.task.prescan.mu
    lo = np.full((len(results), n_jump), np.nan)
    hi = np.full((len(results), n_jump), np.nan)
    rising = np.full((len(results), n_jump), -1, np.int8)
    status = np.full((len(results), n_jump), "", dtype=object)
    certified = np.full((len(results), n_jump), CERTIFICATION_FILL, np.int8)
    outcome = np.full((len(results), len(scan_mu)), "", dtype=object)
    measures = {name: np.full((len(results), len(scan_mu)), np.nan) for name in ("size", "a")}
    win_lo = np.full((len(results), n_window), np.nan)
    win_hi = np.full((len(results), n_window), np.nan)
    win_narrow = np.full((len(results), n_window), -1, np.int8)
    grid = np.full((len(results), 3), np.nan)  # decided, total, resolution
    for i, res in enumerate(results):
        for j, jump in enumerate(res.jumps):
            lo[i, j], hi[i, j] = jump.mu_lo, jump.mu_hi
            rising[i, j] = int(jump.rising)
            status[i, j] = jump.status
            certified[i, j] = CERTIFICATION_FLAGS.index(jump.certification)
        for j, window in enumerate(res.windows):
            win_lo[i, j], win_hi[i, j] = window.lo, window.hi
            win_narrow[i, j] = int(window.narrow)
        if res.grid_below is not None:
            below = res.grid_below
            grid[i] = below.decided, below.total, below.resolution
        # the prescan's runs, and the grid values run later below the headline
        for run in [*res.scan, *(r for r in res.checks if r.request.mu in scan_mu)]:
            k = scan_mu.index(run.request.mu)
            outcome[i, k] = run.outcome
            for name in measures:
                measures[name][i, k] = num(run.result.get(name))
    jdims = (*dims, "jump")
    sdims = (*dims, "scan_mu")
    wdims = (*dims, "window")

    def shaped(values, last):
        return np.asarray(values).reshape((*shape, last))

    return {
        "n_jumps": (
            dims,
            np.asarray([len(r.jumps) for r in results], np.int64).reshape(shape),
            {"units": "1", "long_name": "jumps found by the prescan and bisected"},
        ),
        "jump_mu_lo": (jdims, shaped(lo, n_jump), {"units": "1", "long_name": "jump bracket low"}),
        "jump_mu_hi": (jdims, shaped(hi, n_jump), {"units": "1", "long_name": "jump bracket high"}),
        "jump_mu_star": (
            jdims,
            shaped(0.5 * (lo + hi), n_jump),
            {"units": "1", "long_name": "jump mu* (bracket midpoint)"},
        ),
        "jump_rising": (
            jdims,
            shaped(rising, n_jump),
            {"long_name": "1: not stick below, stick above; 0: the reverse; -1: no jump"},
        ),
        "jump_status": (
            jdims,
            shaped(status.astype(str), n_jump),
            {"long_name": "converged or failed"},
        ),
        "jump_certification": (
            jdims,
            shaped(certified, n_jump),
            {"long_name": "certification of the jump (frictiondisk.search.certify)"},
        ),
        "n_windows": (
            dims,
            np.asarray([len(r.windows) for r in results], np.int64).reshape(shape),
            {"units": "1", "long_name": "sticking windows (a rising jump, then a falling one)"},
        ),
        "window_mu_lo": (
            wdims,
            shaped(win_lo, n_window),
            {"units": "1", "long_name": "sticking window: mu* of its rising jump"},
        ),
        "window_mu_hi": (
            wdims,
            shaped(win_hi, n_window),
            {"units": "1", "long_name": "sticking window: mu* of its falling jump"},
        ),
        "window_narrow": (
            wdims,
            shaped(win_narrow, n_window),
            {
                "long_name": "1: narrower than the persistence width (never the headline); "
                "0: wider; -1: no window"
            },
        ),
        "grid_below_decided": (
            dims,
            grid[:, 0].reshape(shape),
            {"units": "1", "long_name": "prescan values below mu* with a decided verdict"},
        ),
        "grid_below_total": (
            dims,
            grid[:, 1].reshape(shape),
            {"units": "1", "long_name": "prescan values below mu*"},
        ),
        "grid_below_share": (
            dims,
            (grid[:, 0] / np.where(grid[:, 1] > 0, grid[:, 1], np.nan)).reshape(shape),
            {
                "units": "1",
                "long_name": "share of the prescan values below mu* with a decided verdict "
                "(certified grid)",
            },
        ),
        "window_resolution": (
            dims,
            grid[:, 2].reshape(shape),
            {
                "units": "1",
                "long_name": "largest gap between decided mu below mu*: a sticking window "
                "narrower than this could still hide there",
            },
        ),
        "scan_outcome": (
            sdims,
            shaped(outcome.astype(str), len(scan_mu)),
            {"long_name": "outcome of the prescan run"},
        ),
        "scan_size": (
            sdims,
            shaped(measures["size"], len(scan_mu)),
            {"units": "m", "long_name": RUN_MEASURES["size"][1] + " (prescan)"},
        ),
        "scan_a": (
            sdims,
            shaped(measures["a"], len(scan_mu)),
            {"units": "m", "long_name": RUN_MEASURES["a"][1] + " (prescan)"},
        ),
    }
