"""The jump curves of a trace results.nc as point lists, for any figure that draws them
(the trace figure, a motion map's traced boundary). A curve's points are stored one after
the other: `curve_first_point` and `curve_points` say where each curve starts and how many
points it has."""

from __future__ import annotations

import numpy as np
import xarray as xr


def curve_points(results: xr.Dataset, name: str) -> list[tuple[np.ndarray, np.ndarray]]:
    """(key values, mu*) of each curve of a trace results.nc, in curve order (`name`: the
    key's variable)."""
    key = np.asarray(results[name].values, float)
    mu = np.asarray(results["mu_star"].values, float)
    curves = []
    for c in range(results.sizes["curve"]):
        start = int(results["curve_first_point"][c])
        stop = start + int(results["curve_points"][c])
        curves.append((key[start:stop], mu[start:stop]))
    return curves
