"""A Coulomb pin grazing its sticking circle (numba; docs/model.md section 6).

A pin stuck on the master is carried on a circle r = R e^{i(omega_m t + theta)} about the
master axis. Its contact must then supply f = K r - c_s a, with K = c_s - m_s omega_m^2 +
i beta_s omega_m and a = (x_ms, 0) the support; |f| is largest, g R + c_s |x_ms| with
g = |K|, where K r points against a. Where that largest demand exceeds mu F_n by a little,
the pin leaves sticking there for a moment and slips, relative to the master, against f:
the outward share of that slip is -Re(K) / |K| = (m_s omega_m^2 - c_s) / g.

Above the spring's critical speed (m_s omega_m^2 > c_s) every such slip carries the pin
outward, onto a circle that demands more (g R grows with R): it leaves sticking again the
next revolution, with a larger slip, and never shakes down. A departure from sticking
however small its slip: the slip grows as the square of the excess, so that an excess of
1e-8 mu F_n slips some 1e-15 m a revolution, below any integrator's resolution, while the
leaving itself (a force comparison) stays resolved. Measured on the pin at x_ms 0.1 m,
omega_m 1.1 rad/s, 1e-4 below its jump: the slip grows from 1.8e-6 m a revolution by 0.7 %
a revolution and reaches the large stick-slip cycle by 2 000 s.

Below the critical speed the slip carries the pin inward, onto circles that demand less:
no departure, and this rule says nothing there.
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
def _grazing(vp, rules, motion, vs, revs):
    """Whether in each of the newest vp.graze_revs revolutions the pin stuck as a whole for
    at least vp.graze_share of it and left sticking at some instant. Writes ev_points,
    ev_ratio (the outward share) and ev_distance (the newest revolution's slip [m]) of vs."""
    if motion.n_rev < vp.graze_revs:
        return False
    least_stuck = vp.graze_share * rules.hold
    for back in range(vp.graze_revs):
        row = revs[newest_revolution(motion, back)]
        if row.all_stuck or not row.ever_all or row.switches < 1 or row.stick_t < least_stuck:
            return False
    vs.ev_points = vp.graze_revs
    vs.ev_ratio = vs.graze_outward
    vs.ev_distance = revs[newest_revolution(motion, 0)].slip
    return True


@kernel_jit
def grazes_outward(vp, rules, motion, vs, revs):
    """Whether the pin grazes its circle (_grazing), each slip carrying it outward by at
    least vp.graze_outward of itself (vs.graze_outward): a departure from sticking, however
    its slip below the integrator's resolution seems to trend (module docstring)."""
    return vs.graze_outward >= vp.graze_outward and _grazing(vp, rules, motion, vs, revs)
