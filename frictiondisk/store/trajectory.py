"""Recorded trajectory of one run as an xarray Dataset, and its atomic netCDF file.

`trajectory_dataset` turns the `Trajectory` of a `SimulationResult` into a self-describing
Dataset (dims `time` and `contact`, SI units and long names on every variable, the full scene
configuration and the run summary in the attributes). `write_trajectory` writes it as netCDF4,
atomically: a reader never sees a half-written file.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.model.headline import scene_headline
from frictiondisk.simulation.result import SimulationResult
from frictiondisk.store import cf
from frictiondisk.store.files import atomic_write_netcdf
from frictiondisk.version import __version__

# name -> (units, long_name) of the per-sample variables (dim `time`).
_BODY_VARIABLES: dict[str, tuple[str, str]] = {
    "x": ("m", "slave position x (pin or disk centre), fixed frame"),
    "y": ("m", "slave position y (pin or disk centre), fixed frame"),
    "vx": ("m s-1", "slave velocity x, fixed frame"),
    "vy": ("m s-1", "slave velocity y, fixed frame"),
    "phi": ("rad", "slave disk rotation angle"),
    "phidot": ("rad s-1", "slave disk angular velocity"),
}

# name -> (units, long_name) of the per-contact variables (dims `time`, `contact`).
_CONTACT_VARIABLES: dict[str, tuple[str, str]] = {
    "Zx": ("N", "elastic contact force Z = c z, x component, fixed frame"),
    "Zy": ("N", "elastic contact force Z = c z, y component, fixed frame"),
}

MODE_SLIDE = 0
MODE_STICK = 1


def _attr_value(value: Any) -> Any:
    """A netCDF-storable attribute value: None (a measure the run does not have) -> NaN,
    bool -> int, numpy scalar -> Python."""
    if isinstance(value, np.generic):
        value = value.item()
    if value is None:
        return math.nan
    if isinstance(value, bool):
        return int(value)
    return value


def trajectory_dataset(result: SimulationResult, config: Any) -> xr.Dataset:
    """Build the Dataset of the trajectory recorded in `result`.

    Parameters
    ----------
    result:
        A run made with recording on (`result.trajectory` is not None).
    config:
        The validated scene configuration the run was made from; it must provide
        `to_yaml()` and `content_hash()`.

    Returns
    -------
    xarray.Dataset with coordinates `time` [s] (strictly increasing), `contact` (index of
    the contact point) and `event_time` [s] (dim `event`: the stick/slide switches),
    variables x, y, vx, vy (time), phi, phidot (time; only for scenes with rotation),
    Zx, Zy (time, contact), mode (time, contact; int8, 1 = stick, 0 = slide; after a
    switch at its time) and mode_before_event (event, contact).
    Attributes: `scene_yaml` (the full configuration), `config_hash`, `frictiondisk_version`
    and every scalar of `result.summary()` (None stored as NaN, booleans as 0/1), the
    resolved physical parameters (`param_*`) and the CF attributes (frictiondisk.store.cf).
    """
    traj = result.trajectory
    if traj is None:
        raise ValueError(
            "the result holds no trajectory: run the simulation with recording on "
            "(simulate(config, record=True, ...))"
        )

    t = np.asarray(traj.t, dtype=float)
    n_time = t.shape[0]
    mode = np.asarray(traj.mode)
    if mode.ndim != 2 or mode.shape[0] != n_time:
        raise ValueError(f"trajectory mode has shape {mode.shape}, expected ({n_time}, N)")
    n_contact = mode.shape[1]
    # At a mode switch the recorder keeps the sample just before and just after it, at the
    # same time; the state is continuous there and only the mode differs. The time axis
    # keeps the sample after the switch (strictly increasing: `sel(time=..., method=...)`
    # works), and the mode before it goes to the `event` dimension.
    before = np.flatnonzero(np.diff(t) <= 0)
    keep = np.setdiff1d(np.arange(n_time), before)

    data_vars = _state_variables(traj, mode, keep, before)

    coords = {
        "time": ("time", t[keep], {"units": "s", "long_name": "simulated time", "axis": "T"}),
        "event_time": (
            "event",
            t[before],
            {"units": "s", "long_name": "time of a stick/slide switch (one per switch)"},
        ),
        "contact": (
            "contact",
            np.arange(n_contact, dtype=np.int32),
            {"units": "1", "long_name": "index of the contact point"},
        ),
    }

    attrs: dict[str, Any] = {
        "frictiondisk_version": __version__,
        "config_hash": str(config.content_hash()),
        **cf.scene_attrs(config),
        "truncated": int(bool(traj.truncated)),
    }
    for key, value in result.summary().items():
        attrs[key] = _attr_value(value)

    head = scene_headline(config)
    return cf.complete(
        xr.Dataset(data_vars=data_vars, coords=coords, attrs=attrs),
        title=f"frictiondisk trajectory: {head['scene']}, mu = {head['mu']:g}, "
        f"x_ms = {head['x_ms']:g} m",
        what="frictiondisk simulate (one recorded run)",
    )


def _state_variables(traj, mode: np.ndarray, keep: np.ndarray, before: np.ndarray) -> dict:
    """The recorded state at the kept samples (dim `time`; the contacts' dim `contact`),
    and the contact mode before each switch (dim `event`)."""
    data_vars: dict[str, xr.Variable] = {}
    for name, (units, long_name) in _BODY_VARIABLES.items():
        values = getattr(traj, name)
        if values is None:  # phi and phidot exist only for the disk
            continue
        data_vars[name] = xr.Variable(
            ("time",),
            np.asarray(values, dtype=float)[keep],
            {"units": units, "long_name": long_name},
        )
    for name, (units, long_name) in _CONTACT_VARIABLES.items():
        data_vars[name] = xr.Variable(
            ("time", "contact"),
            np.asarray(getattr(traj, name), dtype=float)[keep],
            {"units": units, "long_name": long_name},
        )
    flags = {
        "units": "1",
        "flag_values": np.array([MODE_SLIDE, MODE_STICK], dtype=np.int8),
        "flag_meanings": "slide stick",
    }
    data_vars["mode"] = xr.Variable(
        ("time", "contact"), mode.astype(np.int8)[keep], {"long_name": "contact mode", **flags}
    )
    data_vars["mode_before_event"] = xr.Variable(
        ("event", "contact"),
        mode.astype(np.int8)[before],
        {"long_name": "contact mode just before the switch at event_time", **flags},
    )
    return data_vars


def write_trajectory(path: str | os.PathLike[str], result: SimulationResult, config: Any) -> Path:
    """Write the trajectory of `result` to `path` as compressed netCDF4, atomically
    (frictiondisk.store.files: a temporary file renamed over `path`). Returns the path."""
    ds = trajectory_dataset(result, config)
    encoding = {name: {"zlib": True, "complevel": 4} for name in ds.data_vars}
    return atomic_write_netcdf(ds, path, encoding=encoding)
