"""A Coulomb pin grazing its sticking circle (numba; docs/model.md section 6).

A pin stuck on the master is carried on a circle r = R e^{i(omega_m t + theta)} about the
master axis. Its contact must then supply f = K r - c_s a, with K = c_s - m_s omega_m^2 +
i beta_s omega_m and a = (x_ms, 0) the support; |f| is largest, g R + c_s |x_ms| with
g = |K|, where K r points against a. Where that largest demand exceeds mu F_n, the pin
leaves sticking around there and slips, relative to the master, against f: at the largest
demand the outward share of that slip is o = -Re(K) / |K| = (m_s omega_m^2 - c_s) / g,
whatever R. Over a slip arc of at most 2 pi (1 - s) of a revolution (s: the share of the
revolution stuck), the direction turns by at most that much, so it keeps the sign of o
while 2 pi (1 - s) + acos |o| stays short of pi / 2; and a slip short beside R leaves the
circle's geometry as it was.

Above the spring's critical speed (o > 0) every such slip carries the pin outward, onto a
circle that demands more (g R grows with R): it leaves sticking again the next revolution,
with a larger slip, and never shakes down (EV_GRAZE: not stick). A departure however small
its slip: the slip grows as the square of the excess, so that an excess of 1e-8 mu F_n
slips some 1e-15 m a revolution, below any integrator's resolution, while the leaving
itself (a force comparison) stays resolved. Measured on the pin at x_ms 0.1 m, omega_m
1.1 rad/s, 1e-4 below its jump: the slip grows from 1.8e-6 m a revolution by 0.7 % a
revolution and reaches the large stick-slip cycle by 2 000 s.

Below it (o < 0) every slip carries the pin inward, onto a circle that demands less: the
excess falls at every revolution. The slip cannot settle on a rate that stays (R would
fall without end), so it goes to zero and the pin sticks in the limit on the rim of its
sticking disc (EV_RIM: stick), its slip falling algebraically (as n^-2 at the pin of seed
11's scene 42: the tangent map of verdict/rim_approach.py), where no geometric law fits.
"""

import math

from frictiondisk.kernel.jit import kernel_jit
from frictiondisk.kernel.monitor import newest_revolution


@kernel_jit
def outward_share(p):
    """(m_s omega_m^2 - c_s) / g of a Coulomb pin [1] (module docstring); NaN for a disk, a
    Stribeck law (its slip, once started, does not stay small) or g = 0."""
    if p.disk or p.stribeck_r < 1.0:
        return math.nan
    k_re = p.c_s - p.m_s * p.omega_m * p.omega_m
    g = math.hypot(k_re, p.beta_s * p.omega_m)
    return -k_re / g if g > 0.0 else math.nan


@kernel_jit
def least_stuck_share(vp, share):
    """The least share of a revolution stuck as a whole for which a slip of outward share
    `share` keeps its sign over its whole arc, vp.graze_margin [rad] short of tangential
    (module docstring); > 1 (never) where acos |share| leaves no room, NaN for NaN."""
    room = 0.5 * math.pi - vp.graze_margin - math.acos(min(1.0, abs(share)))
    return 1.0 - room / (2.0 * math.pi)


@kernel_jit
def _grazing(vp, rules, motion, vs, revs):
    """Whether in each of the newest vp.graze_revs revolutions the pin stuck as a whole for
    at least least_stuck_share of it, left sticking at some instant and slipped at most
    vp.graze_slip of its circle's radius. Writes ev_points, ev_ratio (the outward share)
    and ev_distance (the newest revolution's slip [m]) of vs."""
    if motion.n_rev < vp.graze_revs:
        return False
    least_stuck = least_stuck_share(vp, vs.graze_outward) * rules.hold
    for back in range(vp.graze_revs):
        row = revs[newest_revolution(motion, back)]
        radius = math.sqrt(row.x * row.x + row.y * row.y)
        if row.all_stuck or not row.ever_all or row.switches < 1:
            return False
        if not (row.stick_t >= least_stuck and row.slip <= vp.graze_slip * radius):
            return False
    vs.ev_points = vp.graze_revs
    vs.ev_ratio = vs.graze_outward
    vs.ev_distance = revs[newest_revolution(motion, 0)].slip
    return True


@kernel_jit
def grazes_outward(vp, rules, motion, vs, revs):
    """Whether the pin grazes its circle (_grazing), each slip carrying it outward: a
    departure from sticking, however its slip below the integrator's resolution seems to
    trend (module docstring)."""
    return vs.graze_outward > 0.0 and _grazing(vp, rules, motion, vs, revs)


@kernel_jit
def grazes_inward(vp, rules, motion, vs, revs):
    """Whether the pin grazes its circle (_grazing), each slip carrying it inward: it creeps
    onto the rim of its sticking disc and sticks in the limit (module docstring)."""
    return vs.graze_outward < 0.0 and _grazing(vp, rules, motion, vs, revs)
