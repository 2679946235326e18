"""The per-run measures written to runs.nc, with units and long names, and the number
conversion every dataset builder shares."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

RUN_MEASURES = {  # summary field -> (units, long name)
    "R1": ("m", "first sticking radius |r|"),
    "t_R1": ("s", "time of first sticking"),
    "size": ("m", "radius of the sticking circle or of the cycle's sticking segment"),
    "a": ("m", "largest excess |r| - R_stick while sliding on the cycle"),
    "n_transitions": ("1", "stick/slide switches, all contacts"),
    "stick_fraction": ("1", "fraction of the final window with every contact sticking"),
    "t_end": ("s", "simulated time reached"),
    "n_steps": ("1", "accepted integrator steps"),
    "n_refused": ("1", "refused slide->stick entries"),
    # integration quality of each run (kernel/energy.py); NaN for scipy-radau and coulomb
    "energy_residual": ("1", "relative residual of the energy balance over the run"),
    # co-rotation measures over the last whole master revolution (kernel/monitor.py);
    # NaN for scipy-radau and coulomb
    "n_revolutions": ("1", "whole master revolutions completed"),
    "slip_per_rev": ("m", "net plastic slip over the last revolution"),
    "drift_per_rev": ("m", "drift of the slave centre over the last revolution, master frame"),
    "spin_drift_per_rev": (
        "rad",
        "drift of the spin phase phi - omega_m t over the last revolution",
    ),
    "slip_decay": ("1", "mean log ratio of successive slips per revolution"),
    "slip_limit": ("m", "extrapolated limit of the slip per revolution"),
    # the search's continuous signal (frictiondisk/verdict/reserve.py); NaN if never stuck
    "reserve": ("1", "friction reserve mu - demand(R1) / F_n of the first sticking circle"),
    # the pure-sliding motion's measures from its own section (verdict/motion_evidence.py);
    # NaN where the run does not slide or its motion is not named
    "own_period": ("s", "the motion's own period: the velocity phase turning 2 pi"),
    "mean_radius": ("m", "time mean of |r| over the newest own period"),
    "amplitude": ("m", "half the range of |r| over the newest own period"),
    "spin_rate": ("rad s-1", "mean spin phidot over the newest own period"),
    "floquet_ratio": ("1", "contraction of the own section per own period"),
    "decay_rate": ("s-1", "-ln(floquet_ratio) / own_period"),
    "r_eq_x": ("m", "self-centring rest point, x"),
    "r_eq_y": ("m", "self-centring rest point, y"),
    "r_eq": ("m", "self-centring rest point, radius |r_eq|"),
    "r_eq_angle": ("rad", "self-centring rest point, angle from +x counter-clockwise"),
    "envelope_period": ("s", "modulated cycle: period of the envelope of |r|"),
    "envelope_depth": ("m", "modulated cycle: half the range of the step-mean |r|"),
}


def num(value) -> float:
    return math.nan if value is None else float(value)


def measure_columns(results: Sequence[Mapping[str, Any]]) -> dict[str, np.ndarray]:
    """Each of RUN_MEASURES as a float column over `results` (result summaries; NaN where
    a measure is missing or None, as `num` gives), read in one pass over the rows."""
    names = tuple(RUN_MEASURES)
    rows = [[result.get(name) for name in names] for result in results]
    table = np.array(rows, dtype=float).reshape(len(rows), len(names))
    return {name: table[:, k] for k, name in enumerate(names)}
