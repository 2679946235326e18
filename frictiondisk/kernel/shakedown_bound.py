"""Melan's shakedown bound of a braked disk on its small orbit, read by the run itself
(numba). Physics and rule: frictiondisk/outcome/shakedown_verdict.py and docs/model.md
section 6; the loads: frictiondisk/outcome/admissibility.py.

A disk co-rotating with centre r carries C = A r, fixed in its body frame, and the brake
torque T = beta_b omega_m; the spring preload c_s |x_ms| turns once a revolution. Its
friction reserve is mu - (c_s |x_ms| + Lambda(C, T)) / F_n, with Lambda the rigid-plastic
limit of (C, T) on the contact points. The driver writes the reserve at the end of every
revolution into the revolution ring (RV_RESERVE), and `verdict` reads its history there:
the kernel stops a run once the bound decides it (`close_revolution`), and the outcome
layer decides from the same column.
"""

import math

import numpy as np

from .jit import kernel_jit
from .linalg import lu_factor, lu_solve
from .model import P_BETAB, P_BETAI, P_BETAS, P_CI, P_CS, P_FNI, P_MS, P_MU, P_OMEGA, P_XMS
from .monitor_slots import RV_ANY_STUCK, RV_RESERVE

ON_ORBIT_REVS = 5  # revolutions on the small orbit before the bound decides (as the rules)
BLOCKS = 3  # blocks of ON_ORBIT_REVS revolutions whose reserves show it approaching zero
SOLVER_RTOL = 1e-8  # relative accuracy of Lambda from `limit_motion` (measured 1e-9)
IRLS_ITERS = 100  # most iterations of `limit_motion`
IRLS_TOL = 1e-10  # ... which stops once its value changes by less than this share


@kernel_jit
def limit_motion(fx, fy, torque, pts):
    """The optimal rigid slip motion behind Lambda(F, T) on the points pts[:, 0:2] [m]:
    min over (v, w) of sum_i |v + w J a_i| subject to F.v + T w = 1, by iteratively
    reweighted least squares. Returns (v_x, v_y, w, value); Lambda = N / value [N].
    force (fx, fy) [N], torque [N m]; not for points all at the centre."""
    n = pts.shape[0]
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
            wgt = 1.0 / math.sqrt(sx * sx + sy * sy + delta * delta)
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
            value += math.sqrt(sx * sx + sy * sy)
        if abs(prev - value) <= IRLS_TOL * value:
            break
        prev = value
    return x[0], x[1], x[2], value


@kernel_jit
def corotation_reserve(p, pts, x, y, phi):
    """mu - shakedown demand / F_n [1] of the disk co-rotating with centre (x, y) [m] and
    spin angle phi [rad]: the body-frame direction of C = A r fixes the layout angle.
    Equal normal force per point (the caller checks the weights)."""
    omega = p[P_OMEGA]
    k = p[P_CS] - p[P_MS] * omega * omega
    d = p[P_BETAS] * omega
    angle = math.atan2(k * y + d * x, k * x - d * y) - phi
    load = math.hypot(k, d) * math.hypot(x, y)  # |C| = g R [N]
    n = pts.shape[0]
    value = limit_motion(load * math.cos(angle), load * math.sin(angle), p[P_BETAB] * omega, pts)[3]
    demand = p[P_CS] * abs(p[P_XMS]) + n / value
    return p[P_MU] - demand / (p[P_FNI] * n)


@kernel_jit
def floor_reserve(p, pts):
    """mu - the least shakedown demand over every sticking circle and layout angle / F_n
    [1]: c_s |x_ms| + min over C of Lambda(C, T), and that minimum is N T / sum |a_i|
    (every pattern carrying T has max |f_i| >= T / sum |a_i|; equal tangential forces
    reach it, with a resultant C that some circle supplies, as C = A r covers the plane).
    Below zero the disk can stick for good on no circle (Koiter): permanent sticking is
    a shaken-down state, which needs Melan's condition on its circle."""
    n = pts.shape[0]
    arms = 0.0
    for i in range(n):
        arms += math.hypot(pts[i, 0], pts[i, 1])
    if not arms > 0.0:
        return -math.inf  # no lever: the brake torque cannot be carried at all
    torque = abs(p[P_BETAB] * p[P_OMEGA])
    demand = p[P_CS] * abs(p[P_XMS]) + n * torque / arms
    return p[P_MU] - demand / (p[P_FNI] * n)


@kernel_jit
def margin(mu, damping, stiffness, omega):
    """What the quasi-static bound neglects [1, units of mu]: terms of relative order
    (beta omega_m / c)^2 (contact damping [N s/m] against stiffness [N/m] of a co-rotating
    contact), and the solver. omega: master speed [rad/s]."""
    ratio = damping * omega / stiffness
    return mu * (ratio * ratio + SOLVER_RTOL)


@kernel_jit
def run_margin(p):
    """`margin` of a run's packed parameters p (kernel/model.py) [1]."""
    return margin(p[P_MU], p[P_BETAI], p[P_CI], p[P_OMEGA])


@kernel_jit
def history(rv, newest, count, out):
    """The reserves (out, newest first) at the end of the newest row and every
    ON_ORBIT_REVS rows back while the disk stayed on its small orbit: how many (0 where
    the newest ON_ORBIT_REVS rows are not all on it). rv: revolution rows, read as a ring
    (row newest - k at (newest - k) % len(rv)); count: rows that exist."""
    ring = rv.shape[0]
    count = min(count, ring)
    if count < ON_ORBIT_REVS + 1:
        return 0
    m = 0
    for j in range(BLOCKS + 1):
        back = j * ON_ORBIT_REVS  # the value's row, counted back from the newest
        if back >= count:
            break
        # the ON_ORBIT_REVS rows after it (the newest ones for the newest value) on the orbit
        after = max(back - ON_ORBIT_REVS, 0)
        for k in range(after, after + ON_ORBIT_REVS):
            if rv[(newest - k) % ring, RV_ANY_STUCK] != 1.0:
                return m
        out[m] = rv[(newest - back) % ring, RV_RESERVE]
        m += 1
    return m


@kernel_jit
def still_to_come(values, m):
    """How far the reserve may still move towards zero [1], from its history values[:m]
    (newest first): 0 where it moves away from zero (or stands); else the geometric sum of
    its steps, each block's step a ratio q < 1 of the one before (the larger of the
    measured ratios); infinite without that evidence."""
    now = values[0]
    if m < 2:
        return math.inf
    for k in range(m):
        if not now * values[k] > 0.0:
            return math.inf
    first = abs(values[1]) - abs(now)
    if first <= 0.0:
        return 0.0
    if m < BLOCKS + 1:
        return math.inf
    ratio = 0.0
    for k in range(m - 1):
        if not abs(values[k + 1]) - abs(values[k]) > 0.0:
            return math.inf
    for k in range(m - 2):
        step = abs(values[k + 1]) - abs(values[k])
        older = abs(values[k + 2]) - abs(values[k + 1])
        ratio = max(ratio, step / older)
    if ratio >= 1.0:
        return math.inf
    return first * ratio / (1.0 - ratio)


@kernel_jit
def verdict(values, m, width):
    """+1 (Melan: stick), -1 (Koiter: creep) or 0 (no decision) from the history
    values[:m]: the reserve must lie outside the margin `width` and stay outside it after
    all it may still move towards zero."""
    if m < 1:
        return 0
    now = values[0]
    if not abs(now) > width or not abs(now) - still_to_come(values, m) > width:
        return 0
    return 1 if now > 0.0 else -1


@kernel_jit
def stop_ready(rv, newest, count, width, values):
    """The bound's verdict once the full history (BLOCKS + 1 reserves, BLOCKS *
    ON_ORBIT_REVS revolutions on the small orbit) backs it, else 0: the kernel stops a run
    early only on that much evidence. values: scratch of BLOCKS + 1."""
    m = history(rv, newest, count, values)
    if m < BLOCKS + 1:
        return 0
    return verdict(values, m, width)


@kernel_jit
def close_revolution(p, pts, y, rv, count, values):
    """At the end of revolution `count` (state y: x, y, phi, ...): write its reserve into
    its row of the revolution ring rv, and return the bound's verdict once the full history
    backs it (`stop_ready`). values: scratch of BLOCKS + 1."""
    newest = (count - 1) % rv.shape[0]
    rv[newest, RV_RESERVE] = corotation_reserve(p, pts, y[0], y[1], y[2])
    return stop_ready(rv, newest, count, run_margin(p), values)


@kernel_jit
def holds_here(p, rv, count):
    """Whether a stick verdict of the rules may stand at the end of revolution `count`: the
    circle and layout angle the disk is on there do not lie below Melan's bound by more
    than the margin. A disk stuck for good is shaken down on its own circle; one whose slip
    the rules extrapolate to nothing while its own circle cannot hold it is still on its
    way (or never gets there) and runs on. True where no reserve was written."""
    reserve = rv[(count - 1) % rv.shape[0], RV_RESERVE]
    return not reserve < -run_margin(p)
