"""The evidence of a pure-sliding limit cycle (docs/model.md section 6, "The pure-sliding
motions").

* `cycle`: V keeps moving (Aitken's limit at least own_motion_keep V_k) and the section
  contracts by a steady ratio q <= q_max (converged where the travel left is within tol_k),
  or it repeats (repeat_count distances within tol_k) with its size shown steady;
* `ripple`: for a disk's whirl the step-mean |r| stays, over the newest own_window steps,
  within the ripple of |r| inside one step (its discrete ring's, N |Omega - phidot|;
  averaged over a step a ripple can only shrink, while a modulation moves the step mean
  further than |r| moves within a step), with its size shown steady. Converged where that
  band is within band_change of the band of the window before.

A repeat within a tolerance, or a band inside a ripple, is no cycle by itself: a spiral
about a rest point near a Hopf point repeats within any tolerance for long while its size
falls or grows. `shown` asks the size's trend (amplitude_trend.py): steady, the cycle
stands; falling on a straight line it is a spiral dying out (self_centring.py); growing it
leaves its rest point (`leaves`, read ahead, not converged); anything else names nothing.
"""

from __future__ import annotations

import math

import numpy as np

from . import amplitude_trend as at
from .outcomes import SLIDE_CYCLE
from .own_evidence import (
    AMPLITUDE_TREND,
    MotionEvidence,
    OwnScene,
    aitken,
    at_rest,
    cycle_reason,
    measures,
    sizes,
    steady_ratio,
    tolerance,
)
from .params import VerdictParams
from .self_centring import dying_spiral


def shown(rows, found: MotionEvidence, scene: OwnScene, vp: VerdictParams):
    """`found` where the size's trend is steady; a dying spiral or a motion leaving its rest
    point where it falls or grows; None where the trend names nothing (module docstring)."""
    trend = at.size_trend(rows, vp)
    what = at.kind(trend, vp)
    if what == at.STEADY:
        return found
    if scene.observe:
        return None  # evidence observe: nothing read ahead
    if what == at.FALLS:
        return dying_spiral(rows, trend, scene, vp)
    if what == at.GROWS:
        return leaves(rows, trend, scene, vp)
    return None


def leaves(rows, trend, scene: OwnScene, vp: VerdictParams) -> MotionEvidence:
    """A size that grows beyond its errors: the rest point is unstable and the motion
    leaves it for a cycle, read ahead (rule amplitude_trend, never converged)."""
    m = measures(rows, scene, vp)
    return MotionEvidence(
        SLIDE_CYCLE,
        False,
        f"a pure-sliding cycle, read ahead: the motion leaves its rest point, "
        f"{at.describe(trend)} (size now {float(sizes(rows)[-1]):.3g} m; own period "
        f"{m['own_period']:.6g} s, mean radius {m['mean_radius']:.6g} m)",
        floquet_ratio=math.exp(trend.rate * m["own_period"]),
        decay_rate=-trend.rate,
        rule=AMPLITUDE_TREND,
        **m,
    )


def cycle(rows, pts, dist, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
    """slide_cycle from a contracting section, or a repeating one of steady size."""
    speed = rows["v_max"]
    limit = aitken(speed)
    moving = math.isnan(limit) or limit >= vp.own_motion_keep * float(speed[-1])
    tol = tolerance(pts[-1], scene)
    if not moving or at_rest(rows, tol):
        return None  # a motion that moves less than tol in a period is at rest
    m = measures(rows, scene, vp)
    if dist.shape[0] >= vp.repeat_count and np.all(dist[-vp.repeat_count :] <= tol):
        how = f"its own section repeats within {float(np.max(dist[-vp.repeat_count :])):.3g} m"
        trend = at.size_trend(rows, vp)
        if trend is not None:
            how += f", its size steady ({at.describe(trend)})"
        found = MotionEvidence(SLIDE_CYCLE, True, cycle_reason(how, m), **m)
        return shown(rows, found, scene, vp)
    q = steady_ratio(dist, vp.own_ratios, vp)
    if math.isnan(q) or scene.observe:
        return None
    tail = float(dist[-1]) * q / (1.0 - q)
    rate = -math.log(q) / m["own_period"]
    how = (
        f"its own section contracts by {q:.4g} per own period (Floquet rate {rate:.4g} 1/s), "
        f"travel left {tail:.3g} m (tolerance {tol:.3g} m)"
    )
    return MotionEvidence(
        SLIDE_CYCLE, tail <= tol, cycle_reason(how, m), floquet_ratio=q, decay_rate=rate, **m
    )


def band(rows: np.ndarray) -> tuple[float, float]:
    """(half the range of the step-mean |r|, the median half-range of |r| within a step)."""
    return 0.5 * float(np.ptp(rows["r_mean"])), float(np.median(rows["r_max"] - rows["r_min"])) / 2


def ripple(rows, pts, dist, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
    """slide_cycle for a disk's whirl inside its ring's ripple, of steady size."""
    window = vp.own_window
    if scene.arm <= 0.0 or scene.n_contacts < 2 or rows.shape[0] < window:
        return None
    if at_rest(rows, tolerance(pts[-1], scene)):
        return None
    inside, within = band(rows[-window:])
    if inside > within:
        return None
    converged = False
    how = f"its step-mean |r| stays within {inside:.3g} m, inside the ripple of its ring"
    if rows.shape[0] >= 2 * window:
        before, _ = band(rows[-2 * window : -window])
        converged = before <= vp.band_change * inside and inside <= vp.band_change * before
        how += f" ({within:.3g} m within an own period; {before:.3g} m the window before)"
    m = measures(rows, scene, vp)
    m["mean_radius"] = float(np.mean(rows["r_mean"][-window:]))
    found = MotionEvidence(SLIDE_CYCLE, converged, cycle_reason(how, m), **m)
    return shown(rows, found, scene, vp)
