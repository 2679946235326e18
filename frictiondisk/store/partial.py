"""Partial results: a campaign that is stopped (Ctrl-C, SIGTERM) or still running writes
results.nc from what it has, every unfinished point `pending` (status "pending", NaN
values, no runs; each task's datasets say how its pending point reads). The file says so
in its attributes: `partial` = 1, `points_done` and `points_total` (`mark_partial`)."""

from __future__ import annotations

import xarray as xr

PENDING = "pending"
PENDING_REASON = "not finished yet: partial results (frictiondisk resume DIR continues)"


def mark_partial(ds: xr.Dataset, done: int, total: int) -> xr.Dataset:
    """`ds` marked as partial results: `done` of `total` points finished."""
    ds.attrs.update(partial=1, points_done=done, points_total=total)
    return ds
