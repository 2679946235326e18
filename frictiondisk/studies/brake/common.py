"""What the parts of the brake study share: the scene, the bounds, a plain bisection and the
co-rotation rule measured on a recorded run."""

from __future__ import annotations

import math

import numpy as np

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate
from frictiondisk.verdict import admissibility as ad

OMEGA = 1.1  # [rad/s]
REV = 2 * math.pi / OMEGA  # [s]
N_POINTS, RHO = 12, 0.05  # default layout [1], [m]
POINTS = ad.ring_points(N_POINTS, RHO)
# co-rotation rule: the centre in the master frame and the spin phase phi - omega_m t
# repeat every revolution to within these (integration error at rtol 1e-8: < 2e-9 m,
# < 1e-12 rad; at rtol 1e-6 up to 7e-8 m, hence rtol 1e-8 here)
DRIFT_TOL = 1e-8  # [m/rev]
LAG_TOL = 1e-7  # [rad/rev]


def scene(mu, beta_b, phidot0, **numerics):
    return scene_from_dict(
        {
            "scene": "disk",
            "params": {"mu": float(mu), "beta_b": float(beta_b), "phidot0": float(phidot0)},
            "numerics": numerics,
        }
    )


def bisect(is_stick, lo, hi, tol):
    """Bracket [lo, hi] with is_stick(lo) False and is_stick(hi) True, to width tol."""
    s_lo, s_hi = is_stick(lo), is_stick(hi)
    if s_lo or not s_hi:
        return math.nan, math.nan
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if is_stick(mid):
            hi = mid
        else:
            lo = mid
    return lo, hi


def regular_rows(tr, dt):
    """Indices of the samples at multiples of dt (drops the extra rows at switches)."""
    k = np.round(tr.t / dt)
    reg = np.abs(tr.t - k * dt) < 1e-9
    _, first = np.unique(k[reg], return_index=True)
    return np.flatnonzero(reg)[first]


def transitions_per_rev(tr, nrev: int) -> list[int]:
    """Stick/slide transitions of all contacts in each master revolution."""
    return [
        int(
            np.abs(
                np.diff(tr.mode[(tr.t >= k * REV) & (tr.t < (k + 1) * REV)].astype(int), axis=0)
            ).sum()
        )
        for k in range(nrev)
    ]


def corotation(mu, beta_b, phidot0, nrev=12, per=50, rtol=1e-8):
    """Run nrev revolutions without stopping at stick and measure, over the last 3:
    drift of the centre in the master frame [m/rev], of the spin phase [rad/rev],
    mode transitions per revolution, fewest contacts stuck at once."""
    dt = REV / per
    cfg = scene(
        mu, beta_b, phidot0, stop_on_stick=False, t_decide=nrev * REV, rtol=rtol, atol=rtol * 1e-3
    )
    res = simulate(cfg, record=True, dt_out=dt)
    tr = res.trajectory
    idx = regular_rows(tr, dt)
    i1, i0 = idx[-1], idx[-1 - 3 * per]

    def in_master_frame(i):
        c, s = math.cos(-OMEGA * tr.t[i]), math.sin(-OMEGA * tr.t[i])
        return np.array([c * tr.x[i] - s * tr.y[i], s * tr.x[i] + c * tr.y[i]])

    drift = float(np.linalg.norm(in_master_frame(i1) - in_master_frame(i0)) / 3)
    lag = float(abs((tr.phi[i1] - OMEGA * tr.t[i1]) - (tr.phi[i0] - OMEGA * tr.t[i0])) / 3)
    late = tr.t > tr.t[-1] - 3 * REV
    trans = np.abs(np.diff(tr.mode.astype(int), axis=0)).sum(axis=1)[late[1:]].sum() / 3
    return {
        "mu": float(mu),
        "outcome": res.outcome,
        "R": float(math.hypot(tr.x[-1], tr.y[-1])),
        "drift_m_per_rev": drift,
        "lag_rad_per_rev": lag,
        "transitions_per_rev": float(trans),
        "min_stuck": int(tr.mode[late].sum(axis=1).min()),
        "corotates": drift < DRIFT_TOL and lag < LAG_TOL,
        "trajectory": tr,
    }


def bounds(beta_b, radius):
    """The four demands of admissibility.py as friction coefficients (F_n = 1 N)."""
    d = ad.demands(ad.LoadCase(R=radius, beta_b=beta_b), POINTS, RHO)
    return {
        "collapse": d.collapse,
        "shakedown": d.shakedown,
        "elastic": d.elastic,
        "additive": d.additive,
    }
