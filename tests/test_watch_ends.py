"""studies/watch_ends: the not-stick end of each certified bracket is the one watched."""

from __future__ import annotations

import numpy as np
import xarray as xr

from frictiondisk.studies.watch_ends import not_stick_ends


def _results(certification, stick_high, bisected):
    n = len(certification)
    return xr.Dataset(
        {
            "certification": ("point", np.array(certification, dtype=np.int8)),
            "stick_high": ("point", np.array(stick_high, dtype=np.int8)),
            "bisected": ("point", np.array(bisected, dtype=np.int8)),
            "r": ("point", np.full(n, 0.8)),
            "r_lo": ("point", np.full(n, 0.79)),
            "r_hi": ("point", np.full(n, 0.81)),
            "mu_lo": ("point", np.full(n, 0.11)),
            "mu_hi": ("point", np.full(n, 0.12)),
        }
    ).assign(bisected=lambda d: d["bisected"].assign_attrs(flag_meanings="mu key"))


def test_the_end_that_does_not_stick_is_watched_and_uncertified_points_are_not():
    results = _results(
        certification=[1, 2, 3, 1, 1],
        stick_high=[1, 0, 1, 1, 0],
        bisected=[0, 0, 0, 1, 1],
    )
    assert not_stick_ends(results) == [
        (0.8, 0.11),  # sticks above: mu_lo does not stick
        (0.8, 0.12),  # recertified, sticks below: mu_hi
        (0.79, 0.11),  # bisected in the key, sticking at its high end: r_lo
        (0.81, 0.11),  # ... at its low end: r_hi
    ]
