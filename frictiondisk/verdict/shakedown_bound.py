"""Melan's shakedown bound of a braked disk on its small orbit, read by the run itself
(numba). Physics and rule: frictiondisk/verdict/shakedown_verdict.py and docs/model.md
section 6; the loads: frictiondisk/verdict/admissibility.py.

A disk co-rotating with centre r carries C = A r, fixed in its body frame, and the brake
torque T = beta_b omega_m; the spring preload c_s |x_ms| turns once a revolution. Its
friction reserve is mu - (c_s |x_ms| + Lambda(C, T)) / F_n, with Lambda the rigid-plastic
limit of (C, T) on the contact points (verdict/limit_analysis.py). The state machine writes
the reserve at the end of every revolution into the revolution ring (`reserve`), and
`bound_verdict` reads its history there: the machine stops a run once the bound decides
it (`close_revolution`), and the label decides from the same column. Thresholds:
VerdictParams on_orbit_revs, bound_blocks, bound_solver_rtol.
"""

import math

from frictiondisk.kernel.jit import kernel_entry, kernel_jit

from .limit_analysis import limit_motion


@kernel_jit
def corotation_reserve(p, pts, x, y, phi):
    """mu - shakedown demand / F_n [1] of the disk co-rotating with centre (x, y) [m] and
    spin angle phi [rad]: the body-frame direction of C = A r fixes the layout angle.
    Point i carries pts[i, 2] / N of F_n (limit_analysis); the preload's share follows
    the same weights, which needs a layout centred on its weights (the caller checks)."""
    omega = p.omega_m
    k = p.c_s - p.m_s * omega * omega
    d = p.beta_s * omega
    angle = math.atan2(k * y + d * x, k * x - d * y) - phi
    load = math.hypot(k, d) * math.hypot(x, y)  # |C| = g R [N]
    n = pts.shape[0]
    value = limit_motion(load * math.cos(angle), load * math.sin(angle), p.beta_b * omega, pts)[3]
    demand = p.c_s * abs(p.x_ms) + n / value
    return p.mu - demand / (p.F_n_i * n)


@kernel_entry
def floor_reserve(p, pts):
    """mu - the least shakedown demand over every sticking circle and layout angle / F_n
    [1]: c_s |x_ms| + min over C of Lambda(C, T), and that minimum is N T / sum W_i |a_i|
    (every pattern carrying T has max N |f_i| / W_i >= N T / sum W_i |a_i|; tangential
    forces in proportion to the weights reach it, with a resultant C that some circle
    supplies, as C = A r covers the plane).
    Below zero the disk can stick for good on no circle (Koiter): permanent sticking is
    a shaken-down state, which needs Melan's condition on its circle."""
    n = pts.shape[0]
    arms = 0.0
    for i in range(n):
        arms += pts[i, 2] * math.hypot(pts[i, 0], pts[i, 1])
    if not arms > 0.0:
        return -math.inf  # no lever: the brake torque cannot be carried at all
    torque = abs(p.beta_b * p.omega_m)
    demand = p.c_s * abs(p.x_ms) + n * torque / arms
    return p.mu - demand / (p.F_n_i * n)


@kernel_entry
def margin(vp, mu, damping, stiffness, omega):
    """What the quasi-static bound neglects [1, units of mu]: terms of relative order
    (beta omega_m / c)^2 (contact damping [N s/m] against stiffness [N/m] of a co-rotating
    contact), and the solver (vp.bound_solver_rtol). omega: master speed [rad/s]."""
    ratio = damping * omega / stiffness
    return mu * (ratio * ratio + vp.bound_solver_rtol)


@kernel_jit
def run_margin(vp, p):
    """`margin` of a run's parameter record p (kernel/model.py PARAMETERS) [1]."""
    return margin(vp, p.mu, p.beta_i, p.c_i, p.omega_m)


@kernel_entry
def history(vp, revs, newest, count, out):
    """The reserves (out, newest first) at the end of the newest row and every
    vp.on_orbit_revs rows back while the disk stayed on its small orbit: how many (0 where
    the newest on_orbit_revs rows are not all on it). revs: REVOLUTION rows, read as a ring
    (row newest - k at (newest - k) % len(revs)); count: rows that exist."""
    ring = revs.shape[0]
    count = min(count, ring)
    if count < vp.on_orbit_revs + 1:
        return 0
    m = 0
    for j in range(vp.bound_blocks + 1):
        back = j * vp.on_orbit_revs  # the value's row, counted back from the newest
        if back >= count:
            break
        # the on_orbit_revs rows after it (the newest ones for the newest value) on the orbit
        after = max(back - vp.on_orbit_revs, 0)
        for k in range(after, after + vp.on_orbit_revs):
            if not revs[(newest - k) % ring].any_stuck:
                return m
        out[m] = revs[(newest - back) % ring].reserve
        m += 1
    return m


@kernel_jit
def still_to_come(vp, values, m):
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
    if m < vp.bound_blocks + 1:
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


@kernel_entry
def bound_verdict(vp, values, m, width):
    """+1 (Melan: stick), -1 (Koiter: creep) or 0 (no decision) from the history
    values[:m]: the reserve must lie outside the margin `width` and stay outside it after
    all it may still move towards zero."""
    if m < 1:
        return 0
    now = values[0]
    if not abs(now) > width or not abs(now) - still_to_come(vp, values, m) > width:
        return 0
    return 1 if now > 0.0 else -1


@kernel_jit
def stop_ready(vp, revs, newest, count, width, values):
    """The bound's verdict once the full history (bound_blocks + 1 reserves, bound_blocks
    x on_orbit_revs revolutions on the small orbit) backs it, else 0: the machine stops a
    run early only on that much evidence. values: scratch of bound_blocks + 1."""
    m = history(vp, revs, newest, count, values)
    if m < vp.bound_blocks + 1:
        return 0
    return bound_verdict(vp, values, m, width)


@kernel_jit
def close_revolution(vp, p, pts, y, revs, count, values):
    """At the end of revolution `count` (state y: x, y, phi, ...): write its reserve into
    its row of the revolution ring, and return the bound's verdict once the full history
    backs it (`stop_ready`). values: scratch of bound_blocks + 1."""
    newest = (count - 1) % revs.shape[0]
    revs[newest].reserve = corotation_reserve(p, pts, y[0], y[1], y[2])
    return stop_ready(vp, revs, newest, count, run_margin(vp, p), values)


@kernel_jit
def holds_here(vp, p, revs, count):
    """Whether a stick verdict of the rules may stand at the end of revolution `count`: the
    circle and layout angle the disk is on there do not lie below Melan's bound by more
    than the margin. A disk stuck for good is shaken down on its own circle; one whose slip
    the rules extrapolate to nothing while its own circle cannot hold it is still on its
    way (or never gets there) and runs on. True where no reserve was written."""
    reserve = revs[(count - 1) % revs.shape[0]].reserve
    return not reserve < -run_margin(vp, p)
