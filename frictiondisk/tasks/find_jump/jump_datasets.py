"""The variables of a find_jump with a prescan (frictiondisk.tasks.jump_search.jumps): every
jump of every point (dim `jump`), its sticking windows (dim `window`), how much of the
prescan grid below mu* is decided, and the prescan runs (dim `scan_mu`). A point not
finished yet (None) has none of them: its rows stay padded."""

from __future__ import annotations

from typing import Any

import numpy as np

from frictiondisk.model.search_settings import CERTIFICATION_FLAGS
from frictiondisk.store.measures import RUN_MEASURES, num

CERTIFICATION_FILL = -1  # a padded jump slot (a point with fewer jumps than the most)


def all_jumps(campaign, results, dims: tuple[str, ...]) -> dict[str, Any]:
    """Every jump of every point (dim `jump`, NaN-padded), its windows, the grid below mu*
    and the prescan runs (dim `scan_mu`) of a find_jump with a prescan; `results`: each
    point's JumpSearchResult, None if not finished."""
    shape = campaign.shape
    found = [(r.jumps, r.windows) if r is not None else ((), ()) for r in results]

    def shaped(values, last):
        return np.asarray(values).reshape((*shape, last))

    def counted(values, long_name):
        data = np.asarray(values, np.int64).reshape(shape)
        return (dims, data, {"units": "1", "long_name": long_name})

    n_jumps = [len(jumps) for jumps, _ in found]
    n_windows = [len(windows) for _, windows in found]
    return {
        "n_jumps": counted(n_jumps, "jumps found by the prescan and bisected"),
        **_jump_vars(found, max([1, *n_jumps]), (*dims, "jump"), shaped),
        "n_windows": counted(n_windows, "sticking windows (a rising jump, then a falling one)"),
        **_window_vars(found, max([1, *n_windows]), (*dims, "window"), shaped),
        **_grid_vars(results, dims, shape),
        **_scan_vars(results, campaign.task.prescan.mu, (*dims, "scan_mu"), shaped),
    }


def _jump_vars(found, n_jump: int, jdims, shaped) -> dict[str, Any]:
    n = len(found)
    lo, hi = np.full((n, n_jump), np.nan), np.full((n, n_jump), np.nan)
    rising = np.full((n, n_jump), -1, np.int8)
    status = np.full((n, n_jump), "", dtype=object)
    certified = np.full((n, n_jump), CERTIFICATION_FILL, np.int8)
    for i, (jumps, _) in enumerate(found):
        for j, jump in enumerate(jumps):
            lo[i, j], hi[i, j] = jump.mu_lo, jump.mu_hi
            rising[i, j] = int(jump.rising)
            status[i, j] = jump.status
            certified[i, j] = CERTIFICATION_FLAGS.index(jump.certification)
    return {
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
    }


def _window_vars(found, n_window: int, wdims, shaped) -> dict[str, Any]:
    n = len(found)
    win_lo, win_hi = np.full((n, n_window), np.nan), np.full((n, n_window), np.nan)
    win_narrow = np.full((n, n_window), -1, np.int8)
    for i, (_, windows) in enumerate(found):
        for j, window in enumerate(windows):
            win_lo[i, j], win_hi[i, j] = window.lo, window.hi
            win_narrow[i, j] = int(window.narrow)
    return {
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
    }


def _grid_vars(results, dims, shape) -> dict[str, Any]:
    grid = np.full((len(results), 3), np.nan)  # decided, total, resolution
    for i, result in enumerate(results):
        if result is not None and result.grid_below is not None:
            below = result.grid_below
            grid[i] = below.decided, below.total, below.resolution
    share = grid[:, 0] / np.where(grid[:, 1] > 0, grid[:, 1], np.nan)
    return {
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
            share.reshape(shape),
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
    }


def _scan_vars(results, scan_mu, sdims, shaped) -> dict[str, Any]:
    outcome = np.full((len(results), len(scan_mu)), "", dtype=object)
    measures = {name: np.full((len(results), len(scan_mu)), np.nan) for name in ("size", "a")}
    for i, result in enumerate(results):
        if result is None:
            continue
        # the prescan's runs, and the grid values run later below the headline
        for run in [*result.scan, *(r for r in result.checks if r.request.mu in scan_mu)]:
            k = scan_mu.index(run.request.mu)
            outcome[i, k] = run.outcome
            for name in measures:
                measures[name][i, k] = num(run.result.get(name))
    return {
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
