"""An exact Coulomb pin creeping onto the rim of its sticking disc (docs/model.md section 6).

The exact Coulomb pin sticks for good at an onset r_s inside its sticking disc,
g |r_s| + c_s |x_ms| <= mu F_n, of radius R* = (mu F_n - c_s |x_ms|) / g. Just above the
bound c_s |x_ms| / F_n it can approach that disc from outside without entering it: each
stick phase ends in a short slip that carries the next onset closer, the gaps
d_n = |r_s,n| - R* following the map of a tangent fixed point, d_{n+1} = d_n - c d_n^2, so
that d_n ~ 1 / (c n). The pin then sticks in the limit, although no run reaches the disc.
A stick-slip cycle instead has its onsets converge to a gap d_inf > 0.

The test: sqrt(d_n - d_{n+1}) = sqrt(c) (d_n - d_inf) is a line in d_n whose root is the
limit of the gaps. Fitted over the newest onsets, a root at or below zero says the onsets
go to the rim. Pure numerics, no orchestration; thresholds: VerdictParams rim_*.
"""

from __future__ import annotations

import numpy as np

from .params import VerdictParams


def rim_limit(gaps: np.ndarray, cycle_tol: float, vp: VerdictParams) -> tuple[bool, str]:
    """(onto the rim, the evidence in words) from the gaps d_n [m] of the stick onsets to
    the sticking disc's rim, oldest first. True only where the newest half of them (at
    least vp.rim_min_onsets) falls monotonically by vp.rim_min_fall or more, follows the
    tangent map within vp.rim_max_residual with a limit at most vp.rim_max_limit of the
    newest gap above zero, and the newest gap is within cycle_tol [m] of the rim (the
    section tolerance of a cycle)."""
    gaps = np.asarray(gaps, dtype=float)
    window = gaps[len(gaps) // 2 :]
    if len(window) < vp.rim_min_onsets:
        return False, f"{len(gaps)} stick onsets, too few to fit their approach to the rim"
    steps = window[:-1] - window[1:]
    if not (np.all(window > 0.0) and np.all(steps > 0.0)):
        return False, "the gaps of the newest stick onsets to the rim do not fall monotonically"
    newest = window[-1]
    fall = window[0] / newest
    root = np.sqrt(steps)
    design = np.vstack([window[:-1], np.ones_like(root)]).T
    (slope, intercept), *_ = np.linalg.lstsq(design, root, rcond=None)
    residual = float(np.sqrt(np.mean((root - design @ (slope, intercept)) ** 2)) / np.mean(root))
    limit = -intercept / slope if slope > 0.0 else np.inf
    evidence = (
        f"the gap of its stick onsets to the rim fell by {fall:.3g} over the newest "
        f"{len(window)} onsets to {newest:.3g} m, following d' = d - c (d - d_inf)^2 with "
        f"c = {slope**2:.3g} 1/m, d_inf = {limit:.3g} m (residual {residual:.2g})"
    )
    onto = (
        fall >= vp.rim_min_fall
        and residual <= vp.rim_max_residual
        and limit <= vp.rim_max_limit * newest
        and newest <= cycle_tol
    )
    return bool(onto), evidence


def repeats(gaps: np.ndarray, cycle_tol: float, vp: VerdictParams) -> tuple[bool, str]:
    """(a cycle reached, the evidence in words) from the gaps d_n [m] of the stick onsets to
    the rim, oldest first. Over the newest half of them (at least vp.rim_min_onsets) either
    * they do not move monotonically and stay within cycle_tol [m] (a creep onto the rim
      falls monotonically, however little), or
    * they converge geometrically, the ratio of successive steps steady within
      vp.rim_max_ratio_drift (on a creep onto the rim 1 - ratio shrinks with the gap) and
      the Aitken remainder within cycle_tol;
    and their limit lies more than cycle_tol off the rim."""
    window = np.asarray(gaps, dtype=float)[len(gaps) // 2 :]
    if len(window) < vp.rim_min_onsets:
        return False, f"{len(gaps)} stick onsets, too few to show a cycle"
    steps = np.diff(window)
    if not (np.all(steps > 0.0) or np.all(steps < 0.0)):
        spread = float(window.max() - window.min())
        return spread <= cycle_tol and window.min() > cycle_tol, (
            f"the newest {len(window)} stick onsets lie {window.min():.6g} m or more off the "
            f"rim and repeat within {spread:.3g} m"
        )
    ratios = steps[1:] / steps[:-1]
    half = len(ratios) // 2
    older, newer = 1.0 - np.mean(ratios[:half]), 1.0 - np.mean(ratios[half:])
    drift = abs(newer - older) / max(older, newer)
    ratio = float(np.mean(ratios[half:]))
    remainder = abs(steps[-1]) * ratio / (1.0 - ratio) if 0.0 < ratio < 1.0 else np.inf
    limit = window[-1] + np.sign(steps[-1]) * remainder
    reached = drift <= vp.rim_max_ratio_drift and remainder <= cycle_tol and limit > cycle_tol
    return bool(reached), (
        f"the newest {len(window)} stick onsets converge with ratio {ratio:.4g} per onset "
        f"(drift {drift:.2g}) to {limit:.6g} m off the rim, {remainder:.3g} m from the newest"
    )
