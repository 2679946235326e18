"""The accuracy study's answer as text (`summary_table`): one line per row of accuracy.nc,
printed by `frictiondisk accuracy`."""

from __future__ import annotations

import math

from frictiondisk.store.tables import mu_decimals


def summary_table(ds) -> str:
    """One line per row: knob, setting, mu*, error, steps, wall time, status; mu* to two
    decimals below the study's tol (tol 1e-9 -> 11)."""
    places = mu_decimals(float(ds.attrs["tol"]) if "tol" in ds.attrs else None)
    width = max(14, places + 4)
    head = f"{'knob':10s} {'setting':42s} {'mu*':>{width}s} {'error':>9s} {'steps':>9s} "
    head += f"{'wall_s':>8s}"
    lines = [head]
    for i in range(ds.sizes["setting"]):
        row = {name: ds[name].values[i] for name in ds.data_vars}
        mark = " (ref)" if row["is_reference"] else ""
        error = f"{row['error']:9.2e}" if math.isfinite(row["error"]) else f"{'-':>9s}"
        finite = math.isfinite(row["mu_star"])
        mu = f"{row['mu_star']:{width}.{places}f}" if finite else f"{'-':>{width}s}"
        status = "" if row["status"] == "converged" else f"  {row['status']}: {row['reason']}"
        lines.append(
            f"{str(row['knob']):10s} {(str(row['label']) + mark)[:42]:42s} {mu} {error} "
            f"{int(row['n_steps']):9d} {row['wall_s']:8.3f}{status}"
        )
    return "\n".join(lines)
