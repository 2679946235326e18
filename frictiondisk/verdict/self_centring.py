"""The evidence of self-centring: a pure slide that comes to rest at a sliding equilibrium
(docs/model.md section 6, "The pure-sliding motions").

* `rest`: V_k falls by a steady ratio q <= q_max (own_ratios ratios within q_steady of each
  other), Aitken's limit of V is at most own_rest_zero V_k, or, shown, the motion moved
  less than tol_k in each of the newest repeat_count own periods; the mean contact still
  slips faster than own_rest_slip eps (a sliding rest state, not sticking). Converged where
  the travel left, d_k q / (1 - q), is within tol_k.
* `ring_ripple`: a disk at rest on a ring of N contacts is shaken by the ring at N phidot
  (its contacts pass at that rate), so its velocity turns once per 2 pi / (N |phidot|)
  with an amplitude that falls with N (the braked disk at omega_m 1.2: 7.1e-7 m with 48
  points, 8.6e-8 m with 96): own periods within ring_ripple_tol of that, and a size not
  shown to grow, are the equilibrium, not a cycle. Converged where the section repeats.
* `dying_spiral`: the size's trend (amplitude_trend.py) falls on a straight line: a spiral
  about its rest point dying out at the measured rate, read ahead (rule amplitude_trend)
  until the size is within tol_k (shown).
"""

from __future__ import annotations

import math

import numpy as np

from . import amplitude_trend as at
from .envelope_trend import DepthTrend
from .outcomes import SELF_CENTRING
from .own_evidence import (
    AMPLITUDE_TREND,
    MotionEvidence,
    OwnScene,
    aitken,
    centre,
    measures,
    rest_point,
    sizes,
    steady_ratio,
    tolerance,
)
from .params import VerdictParams


def rest(rows, pts, dist, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
    """self_centring by a steady fall of the speed to nothing, or shown at rest."""
    speed = rows["v_max"]
    tol = tolerance(pts[-1], scene)
    count = vp.repeat_count
    shown_at_rest = bool(np.all(speed[-count:] * rows["dt"][-count:] <= tol))
    q = steady_ratio(speed, vp.own_ratios, vp)
    limit = aitken(speed) if not math.isnan(q) else math.nan
    falls = not math.isnan(limit) and abs(limit) <= vp.own_rest_zero * float(speed[-1])
    if not falls and not shown_at_rest:
        return None
    slip_rate = _slip_rate(rows)
    if slip_rate <= vp.own_rest_slip * scene.eps:
        return None
    point, tail = pts[-1, :2], 0.0
    if falls:
        tail = float(dist[-1]) * q / (1.0 - q)
        point = pts[-1, :2] + (pts[-1, :2] - pts[-2, :2]) * q / (1.0 - q)
    shown = shown_at_rest or bool(np.all(dist[-count:] <= tol))
    converged = shown if scene.observe else (shown or tail <= tol)
    m = measures(rows, scene, vp)
    rate = -math.log(q) / m["own_period"] if falls else math.nan
    where = rest_point(point)
    how = f"falls by {q:.4g} (rate {rate:.4g} 1/s)" if falls else "has fallen"
    return MotionEvidence(
        SELF_CENTRING,
        converged,
        f"self-centres: its largest speed per own period ({m['own_period']:.4g} s) "
        f"{how} to rest at |r| = {where['r_eq']:.6g} m, where it still slips at "
        f"{slip_rate:.3g} m/s; travel left {tail:.3g} m (tolerance {tol:.3g} m; "
        f"beta_s/2m_s = {scene.tangential_rate:.4g} 1/s)",
        floquet_ratio=q if falls else math.nan,
        decay_rate=rate,
        **where,
        **m,
    )


def _slip_rate(rows: np.ndarray) -> float:
    last = rows[-1]
    return float(last["slip"] / last["dt"])


def ring_period_share(rows: np.ndarray, scene: OwnScene) -> float:
    """The newest own periods' largest |T N |phidot| / 2 pi - 1|: 0 for the ring's ripple
    about a rest point (NaN for the pin or a ring of fewer than two points)."""
    if scene.arm <= 0.0 or scene.n_contacts < 2:
        return math.nan
    turns = scene.n_contacts * np.abs(rows["spin"]) / (2.0 * math.pi)
    return float(np.max(np.abs(turns - 1.0)))


def ring_ripple(rows, pts, dist, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
    """self_centring where the velocity turns with the ring's ripple (module docstring)."""
    newest = rows[-min(rows.shape[0], vp.amp_trend_count) :]
    share = ring_period_share(newest, scene)
    if math.isnan(share) or share > vp.ring_ripple_tol or newest.shape[0] < vp.amp_trend_count:
        return None
    trend = at.size_trend(rows, vp)
    if at.kind(trend, vp) == at.GROWS:
        return None  # a growth under the ripple leaves the rest point
    slip_rate = _slip_rate(rows)
    if slip_rate <= vp.own_rest_slip * scene.eps:
        return None
    tol = tolerance(pts[-1], scene)
    count = vp.repeat_count
    converged = bool(np.all(dist[-count:] <= tol))
    m = measures(rows, scene, vp)
    where = rest_point(centre(rows[-1]))
    size = float(sizes(rows)[-1])
    return MotionEvidence(
        SELF_CENTRING,
        converged,
        f"self-centres: at rest at |r| = {where['r_eq']:.6g} m, where it still slips at "
        f"{slip_rate:.3g} m/s, shaken by its ring of {scene.n_contacts} contacts: its "
        f"velocity turns once per {m['own_period']:.4g} s = 2 pi / (N phidot) within "
        f"{share:.2g}, over a path of size {size:.3g} m (the ring's ripple, not a cycle); "
        f"newest section step {float(dist[-1]):.3g} m (tolerance {tol:.3g} m)",
        **where,
        **m,
    )


def dying_spiral(rows, trend: DepthTrend, scene: OwnScene, vp: VerdictParams) -> MotionEvidence:
    """self_centring read from a size that falls on a straight line (module docstring)."""
    m = measures(rows, scene, vp)
    size = float(sizes(rows)[-1])
    tol = tolerance(np.array([rows["x"][-1], rows["y"][-1]]), scene)
    converged = size <= tol
    where = rest_point(centre(rows[-1]))
    return MotionEvidence(
        SELF_CENTRING,
        converged,
        f"self-centres: a spiral about its rest point at |r| = {where['r_eq']:.6g} m dying "
        f"out, {at.describe(trend)}; size now {size:.3g} m (tolerance {tol:.3g} m)",
        floquet_ratio=math.exp(trend.rate * m["own_period"]),
        decay_rate=-trend.rate,
        rule="" if converged else AMPLITUDE_TREND,
        **where,
        **m,
    )
