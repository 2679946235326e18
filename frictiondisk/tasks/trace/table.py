"""The answer of a trace campaign as text: one line per curve and per fold (printed by
`frictiondisk status`), and the one-line summary of what is not certain (also at the end
of `run`)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from frictiondisk.store.tables import columns, flag_text, mu_decimals


def _meanings(results: xr.Dataset, name: str) -> list[str]:
    var = results[name]
    return [flag_text(var, v) for v in np.atleast_1d(var.values)]


def trace_lines(results: xr.Dataset) -> list[str]:
    """Lines of a trace results.nc: its curves and folds ([] without curve points)."""
    if "point_curve" not in results:
        return []
    name = str(results.attrs["trace_key_var"])
    key, mu = results[name].values, results["mu_star"].values
    places = mu_decimals(float(results.attrs["tol"]))  # two below the tol's place
    # today's look where it shows as much (tol 1e-4: 6 and 8 significant digits)
    curve_mu = ".6g" if places <= 6 else f".{places}f"
    fold_mu = ".8g" if places <= 8 else f".{places}f"
    flags = _meanings(results, "certification") if results.sizes["point"] else []
    rows = []
    for c in range(results.sizes["curve"]):
        start = int(results["curve_first_point"][c])
        stop = start + int(results["curve_points"][c])
        counts = {flag: flags[start:stop].count(flag) for flag in dict.fromkeys(flags[start:stop])}
        rows.append(
            [
                str(c),
                str(stop - start),
                f"{key[start]:.6g} -> {key[stop - 1]:.6g}",
                f"{mu[start]:{curve_mu}} -> {mu[stop - 1]:{curve_mu}}",
                "closed"
                if int(results["curve_closed"][c])
                else f"{results['curve_first_end'].values[c]} / {results['curve_last_end'].values[c]}",
                ", ".join(f"{n} {flag}" for flag, n in counts.items()),
            ]
        )
    lines = [
        f"curves of the plane ({results.attrs['trace_key']}, mu), points certified to tol "
        f"{float(results.attrs['tol']):g} in mu:"
    ]
    if rows:
        heads = ["curve", "points", f"{name} first -> last", "mu first -> last", "ends"]
        lines += columns([*heads, "certification"], rows)
    else:
        lines.append("  none found")
    if results.sizes["fold"]:
        kinds = _meanings(results, "fold_window")
        certs = _meanings(results, "fold_certification")
        fold_rows = []
        for f in range(results.sizes["fold"]):
            k_in, k_out = (float(results[f"fold_{name}_{s}"][f]) for s in ("in", "out"))
            lo, hi = float(results["fold_mu_lo"][f]), float(results["fold_mu_hi"][f])
            fold_rows.append(
                [
                    str(f),
                    str(int(results["fold_curve"][f])),
                    f"{float(results[f'fold_{name}'][f]):.8g} [{k_in:.8g}, {k_out:.8g}]",
                    f"{float(results['fold_mu'][f]):{fold_mu}} [{lo:{fold_mu}}, {hi:{fold_mu}}]",
                    "window" if kinds[f] == "sticking_window_closes" else "gap",
                    str(results["fold_status"].values[f]),
                    certs[f],
                ]
            )
        heads = ["fold", "curve", f"{name} [in, out]", "mu [lo, hi]", "closes", "status"]
        lines += ["folds (where two jumps meet):", *columns([*heads, "certification"], fold_rows)]
    return lines


def trace_closing(results: xr.Dataset) -> list[str]:
    """The uncertain points and what failed, one line each ([] without curve points)."""
    if "point_curve" not in results:
        return []
    lines = []
    flags = _meanings(results, "certification") if results.sizes["point"] else []
    uncertain = flags.count("uncertain")
    if uncertain:
        lines.append(f"{uncertain} of {len(flags)} curve points uncertain (kept, flagged)")
    if results.attrs.get("status") == "failed":
        lines.append(f"trace incomplete: {results.attrs.get('reason')}")
    elif results.sizes.get("fold"):
        missed = [str(r) for r in results["fold_reason"].values if str(r)]
        if missed:
            lines.append(f"{len(missed)} fold(s) not located: " + "; ".join(missed))
    return lines
