"""The evidence of self-centring (verdict/motion_evidence.py): the largest speed V_k per
own period falls by a steady ratio q <= q_max (own_ratios ratios within q_steady of each
other), Aitken's limit of V is at most own_rest_zero V_k (it comes to rest), and the mean
contact still slips there faster than own_rest_slip eps (a sliding rest state, not
sticking). Converged where the travel left, d_k q / (1 - q), is within tol_k."""

from __future__ import annotations

import math

import numpy as np

from .outcomes import SELF_CENTRING
from .own_evidence import (
    MotionEvidence,
    OwnScene,
    aitken,
    own_measures,
    own_tolerance,
    steady_ratio,
)
from .params import VerdictParams


def rest_evidence(rows, pts, dist, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
    """self_centring, where the evidence holds (module docstring): a steady geometric fall
    of the speed to an Aitken limit of nothing, or, shown, a motion that has come to rest
    (it moved less than tol_k in each of the newest repeat_count own periods)."""
    speed = rows["v_max"]
    tol = own_tolerance(pts[-1], scene)
    count = vp.repeat_count
    at_rest = bool(np.all(speed[-count:] * rows["dt"][-count:] <= tol))
    q = steady_ratio(speed, vp.own_ratios, vp)
    limit = aitken(speed) if not math.isnan(q) else math.nan
    falls = not math.isnan(limit) and abs(limit) <= vp.own_rest_zero * float(speed[-1])
    if not falls and not at_rest:
        return None
    last = rows[-1]
    slip_rate = float(last["slip"] / last["dt"])
    if slip_rate <= vp.own_rest_slip * scene.eps:
        return None
    rest, tail = pts[-1, :2], 0.0
    if falls:
        tail = float(dist[-1]) * q / (1.0 - q)
        rest = pts[-1, :2] + (pts[-1, :2] - pts[-2, :2]) * q / (1.0 - q)
    shown = at_rest or bool(np.all(dist[-count:] <= tol))
    converged = shown if scene.observe else (shown or tail <= tol)
    measures = own_measures(rows, scene)
    rate = -math.log(q) / measures["own_period"] if falls else math.nan
    radius = float(np.hypot(*rest))
    how = f"falls by {q:.4g} (rate {rate:.4g} 1/s)" if falls else "has fallen"
    return MotionEvidence(
        SELF_CENTRING,
        converged,
        f"self-centres: its largest speed per own period ({measures['own_period']:.4g} s) "
        f"{how} to rest at |r| = {radius:.6g} m, where it still slips at {slip_rate:.3g} m/s; "
        f"travel left {tail:.3g} m (tolerance {tol:.3g} m; beta_s/2m_s = "
        f"{scene.tangential_rate:.4g} 1/s)",
        floquet_ratio=q if falls else math.nan,
        decay_rate=rate,
        r_eq_x=float(rest[0]),
        r_eq_y=float(rest[1]),
        r_eq=radius,
        r_eq_angle=math.atan2(float(rest[1]), float(rest[0])),
        **measures,
    )
