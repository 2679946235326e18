"""The accuracy study's answer as text (`summary_table`): one line per row of accuracy.nc,
printed by `frictiondisk accuracy`."""

from __future__ import annotations

import math


def summary_table(ds) -> str:
    """One line per row: knob, setting, mu*, error, steps, wall time, status."""
    head = f"{'knob':10s} {'setting':42s} {'mu*':>14s} {'error':>9s} {'steps':>9s} {'wall_s':>8s}"
    lines = [head]
    for i in range(ds.sizes["setting"]):
        row = {name: ds[name].values[i] for name in ds.data_vars}
        mark = " (ref)" if row["is_reference"] else ""
        error = f"{row['error']:9.2e}" if math.isfinite(row["error"]) else f"{'-':>9s}"
        mu = f"{row['mu_star']:14.10f}" if math.isfinite(row["mu_star"]) else f"{'-':>14s}"
        status = "" if row["status"] == "converged" else f"  {row['status']}: {row['reason']}"
        lines.append(
            f"{str(row['knob']):10s} {(str(row['label']) + mark)[:42]:42s} {mu} {error} "
            f"{int(row['n_steps']):9d} {row['wall_s']:8.3f}{status}"
        )
    return "\n".join(lines)
