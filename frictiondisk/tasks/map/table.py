"""The answer of a map campaign as text (`summary_lines`), printed by `run` and `status`:
the share of each motion, then one line per cell with its motion and measures."""

from __future__ import annotations

import numpy as np
import xarray as xr

from frictiondisk.store.measures import RUN_MEASURES
from frictiondisk.verdict.outcomes import OUTCOMES, is_stick

# bookkeeping of a run, not a measure of its motion: left out of a cell's line
BOOKKEEPING = {"t_end", "n_steps", "n_refused", "energy_residual", "n_revolutions", "n_transitions"}
HOW = {1: "run", 0: "inferred", -1: "pending"}
SETTLED = {1: ", settled", 0: ", not settled", -1: ""}


def settled_flags(results: xr.Dataset) -> np.ndarray:
    """Per cell 1 settled, 0 not settled, -1 unknown (not run, or its starts disagree), as
    the log says it: the cell's cycle_converged, except that a sticking cell is settled by
    its own rule (co-rotation for good), whatever cycle_converged says. The figure marks
    the same cells."""
    flags = np.asarray(results["cycle_converged"].values).astype(int)
    motion = np.asarray(results["motion"].values).astype(str)
    sticks = np.isin(motion, [o for o in OUTCOMES if is_stick(o)])
    return np.where(sticks & (flags >= 0), 1, flags)


def summary_lines(results: xr.Dataset) -> list[str]:
    """The shares of the motions over the map's cells, then a line per cell."""
    outcomes = [str(o) for o in results["outcome"].values]
    shares = ", ".join(
        f"{o} {float(f):.3f}"
        for o, f in zip(outcomes, results["cell_fraction"].values, strict=True)
        if np.isfinite(f) and f > 0
    )
    dims = list(results["motion"].dims)
    results = results.assign(settled=(dims, settled_flags(results)))
    stacked = results.stack(cell=dims)
    ran = int((results["ran"] == 1).sum())
    lines = [f"map, {stacked.sizes['cell']} cells ({ran} run): {shares or 'nothing yet'}"]
    shown = [name for name in RUN_MEASURES if name not in BOOKKEEPING and name in results]
    for k in range(stacked.sizes["cell"]):
        lines.append(cell_line(stacked.isel(cell=k), dims, shown))
    return lines


def cell_line(row: xr.Dataset, dims: list[str], shown: list[str]) -> str:
    """`omega_m = 1.2, mu = 0.1: slide_cycle (run, settled), size = 0.31 m, ...`."""
    where = ", ".join(f"{d} = {float(row[d]):.6g}" for d in dims)
    ran = int(row["ran"])
    motion = str(row["motion"].values.item()) or "pending"
    settled = int(row["settled"]) if "settled" in row else int(row["cycle_converged"])
    text = f"{where}: {motion} ({HOW[ran]}{SETTLED[settled]})"
    if int(row["n_runs"]) > 1:
        parts = [
            f"{str(o)} {float(f):.2f}"
            for o, f in zip(row["outcome"].values, row["fraction"].values, strict=True)
            if f > 0
        ]
        text += f" of {int(row['n_runs'])} starts: " + ", ".join(parts)
    for name in shown:
        value = float(row[name])
        if np.isfinite(value):
            unit = row[name].attrs.get("units", "1")
            text += f", {name} = {value:.4g}" + ("" if unit == "1" else f" {unit}")
    return text
