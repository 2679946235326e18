"""The rigid-plastic limit of a force and a torque on a set of contact points (numba):
Lambda(F, T) = min over contact force patterns carrying (F, T) of N max_i |f_i| / W_i, from
its kinematic form, by iteratively reweighted least squares (IRLS). W_i is point i's
relative weight (pts[i, 2], mean 1: its share of the normal force, so of the friction
limit, times N; 1 where pts has no third column); equal weights give N max_i |f_i|. The
shakedown bound (verdict/shakedown_bound.py) reads it on the run; verdict/admissibility.py
around it.
IRLS_ITERS and IRLS_TOL are the solver's numerics; its accuracy enters the bound's margin
(VerdictParams.bound_solver_rtol)."""

import math

import numpy as np

from frictiondisk.kernel.jit import kernel_entry_allocating
from frictiondisk.kernel.linalg import lu_factor, lu_solve

IRLS_ITERS = 100  # most iterations of `limit_motion`
IRLS_TOL = 1e-10  # ... which stops once its value changes by less than this share


@kernel_entry_allocating
def limit_motion(fx, fy, torque, pts):
    """The optimal rigid slip motion behind Lambda(F, T) on the points pts[:, 0:2] [m]
    with relative weights pts[:, 2] (if given): min over (v, w) of sum_i W_i |v + w J a_i|
    subject to F.v + T w = 1, by iteratively reweighted least squares. Returns
    (v_x, v_y, w, value); Lambda = N / value [N] (the dual: F.v + T w = sum f_i.s_i <=
    sum |f_i| |s_i| <= (Lambda / N) sum W_i |s_i|). force (fx, fy) [N], torque [N m]; not
    for points all at the centre."""
    n = pts.shape[0]
    weighted = pts.shape[1] > 2
    c = np.array([fx, fy, torque])
    cc = fx * fx + fy * fy + torque * torque
    x = c / cc  # a feasible start
    delta = 1e-9 / (math.sqrt(cc) + 1e-300)
    h = np.empty((3, 3))
    hc = np.empty(3)
    piv = np.empty(3, dtype=np.int64)
    prev = math.inf
    value = math.inf
    for _ in range(IRLS_ITERS):
        h[:, :] = 0.0
        for i in range(n):
            ax = pts[i, 0]
            ay = pts[i, 1]
            sx = x[0] - x[2] * ay
            sy = x[1] + x[2] * ax
            share = pts[i, 2] if weighted else 1.0
            wgt = share / math.sqrt(sx * sx + sy * sy + delta * delta)
            h[0, 0] += wgt
            h[1, 1] += wgt
            h[0, 2] -= wgt * ay
            h[1, 2] += wgt * ax
            h[2, 2] += wgt * (ax * ax + ay * ay)
        h[2, 0] = h[0, 2]
        h[2, 1] = h[1, 2]
        for k in range(3):
            h[k, k] += 1e-300
        lu_factor(h, piv)
        lu_solve(h, piv, c, hc)
        scale = c[0] * hc[0] + c[1] * hc[1] + c[2] * hc[2]
        for k in range(3):
            x[k] = hc[k] / scale
        value = 0.0
        for i in range(n):
            sx = x[0] - x[2] * pts[i, 1]
            sy = x[1] + x[2] * pts[i, 0]
            share = pts[i, 2] if weighted else 1.0
            value += share * math.sqrt(sx * sx + sy * sy)
        if abs(prev - value) <= IRLS_TOL * value:
            break
        prev = value
    return x[0], x[1], x[2], value
