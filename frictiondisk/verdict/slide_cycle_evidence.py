"""The evidence of a pure-sliding limit cycle, slide_cycle (verdict/motion_evidence.py): V
keeps moving (Aitken's limit at least own_motion_keep V_k) and the own section repeats
(repeat_count distances within tol_k) or contracts by a steady ratio q <= q_max (converged
where the travel left is within tol_k); or a disk's whirl whose step-mean |r| stays within
its ring's ripple. The envelope's readings of a whirl are in modulated_evidence.py."""

from __future__ import annotations

import math

import numpy as np

from .outcomes import SLIDE_CYCLE
from .own_evidence import (
    MotionEvidence,
    OwnScene,
    aitken,
    cycle_reason,
    own_measures,
    own_tolerance,
    steady_ratio,
)
from .params import VerdictParams


def section_cycle_evidence(
    rows, pts, dist, scene: OwnScene, vp: VerdictParams
) -> MotionEvidence | None:
    """slide_cycle from a repeating or contracting section (module docstring)."""
    speed = rows["v_max"]
    limit = aitken(speed)
    moving = math.isnan(limit) or limit >= vp.own_motion_keep * float(speed[-1])
    tol = own_tolerance(pts[-1], scene)
    if not moving or float(speed[-1] * rows["dt"][-1]) <= tol:
        return None  # a motion that moves less than tol in a period is at rest
    measures = own_measures(rows, scene)
    if dist.shape[0] >= vp.repeat_count and np.all(dist[-vp.repeat_count :] <= tol):
        how = f"its own section repeats within {float(np.max(dist[-vp.repeat_count :])):.3g} m"
        return MotionEvidence(SLIDE_CYCLE, True, cycle_reason(how, measures), **measures)
    q = steady_ratio(dist, vp.own_ratios, vp)
    if math.isnan(q) or scene.observe:
        return None
    tail = float(dist[-1]) * q / (1.0 - q)
    rate = -math.log(q) / measures["own_period"]
    how = (
        f"its own section contracts by {q:.4g} per own period (Floquet rate {rate:.4g} 1/s), "
        f"travel left {tail:.3g} m (tolerance {tol:.3g} m)"
    )
    return MotionEvidence(
        SLIDE_CYCLE,
        tail <= tol,
        cycle_reason(how, measures),
        floquet_ratio=q,
        decay_rate=rate,
        **measures,
    )


def _band(rows: np.ndarray) -> tuple[float, float]:
    """(half the range of the step-mean |r|, the median half-range of |r| within a step)."""
    return 0.5 * float(np.ptp(rows["r_mean"])), float(np.median(rows["r_max"] - rows["r_min"])) / 2


def ring_ripple_evidence(
    rows, pts, dist, scene: OwnScene, vp: VerdictParams
) -> MotionEvidence | None:
    """slide_cycle for a disk's whirl whose step-mean |r| stays, over the newest own_window
    steps, within the ripple of |r| inside one step (its discrete ring's, N |Omega - phidot|;
    averaged over a step a ripple can only shrink, while a modulation moves the step mean
    further than |r| moves within a step). Converged where that band is steady: within
    band_change of the band of the window before."""
    window = vp.own_window
    if scene.arm <= 0.0 or scene.n_contacts < 2 or rows.shape[0] < window:
        return None
    if float(rows["v_max"][-1] * rows["dt"][-1]) <= own_tolerance(pts[-1], scene):
        return None  # at rest
    band, ripple = _band(rows[-window:])
    if band > ripple:
        return None
    converged = False
    how = f"its step-mean |r| stays within {band:.3g} m, inside the ripple of its ring"
    if rows.shape[0] >= 2 * window:
        before, _ = _band(rows[-2 * window : -window])
        converged = before <= vp.band_change * band and band <= vp.band_change * before
        how += f" ({ripple:.3g} m within an own period; {before:.3g} m the window before)"
    measures = own_measures(rows, scene)
    measures["mean_radius"] = float(np.mean(rows["r_mean"][-window:]))
    return MotionEvidence(SLIDE_CYCLE, converged, cycle_reason(how, measures), **measures)
