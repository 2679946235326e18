"""Energy balance of the pin and disk scenes: stored energy, input power, dissipation (numba).

Stored energy [J] (kernel/model.py state layout):
    E = 1/2 m_s |r'|^2 + 1/2 J_s phi'^2 + 1/2 c_s |r - r0|^2 + sum_i |Z_i|^2 / (2 c_i)
(the phi' term only for the disk; r0 = (x_ms, 0)). Along any solution of model.rhs, in any
fixed contact modes,
    dE/dt = P_in - D                                                           (*)
exactly, with
    P_in = sum_i F_i . v_m,i           power the driven master puts in [W],
    D    = beta_s |r'|^2 + beta_b phi'^2 + sum_i D_i  >= 0 (up to the band)  [W].
Contact element i (spring c_i || dashpot beta_i, in series with the plastic slider) joins
the slave material point at q_i (velocity v_s,i) to the master material point it is glued
to, at q_i - z_i, with velocity v_m,i = omega_m e_z x (q_i - z_i). Its rate of extension is
u_i = v_s,i - v_m,i = v_i + omega_m e_z x z_i (the objective rate of model.py). The element
exerts F_i on the slave and -F_i on the master, so the slave gains F_i . v_s,i and the master
puts in F_i . v_m,i; what the element keeps is d/dt |Z_i|^2/(2 c_i), the rest it dissipates:
    D_i = -F_i . u_i - Z_i . Z_i' / c_i.
With F_i = -G_i, Z_i' = (c_i/beta_i)(G_i - Z_i) and beta_i u_i = k_i - Z_i (model.py):
    D_i = (|G_i - Z_i|^2 + G_i . (k_i - G_i)) / beta_i,
    stick (G = k):            D_i = beta_i |u_i|^2                       (dashpot)
    slide (G = F_St k/|k|):   D_i = |G_i - Z_i|^2/beta_i + F_St,i (|k_i| - F_St,i)/beta_i
                              (dashpot + slider: F_St times the plastic rate, paper eq. 9).
The remaining terms of dE/dt are the support and brake dampers; the support spring and
the inertia terms cancel against the equations of motion.

The run diagnostic integrates P_in and D over each accepted (partial) step by Simpson's
rule, with the midpoint from the step's dense output, in the modes the piece was integrated
in (integrate_piece).
"""

import math

import numpy as np

from .jit import kernel_entry, kernel_jit
from .model import STICK, contact_constants, friction_limit, n_coords
from .rosenbrock import dense_eval

# The energy record of a run (kernel/records.py RUN_STATE.energy)
ENERGY = np.dtype(
    [
        ("w_in", np.float64),  # work put in by the master, integral of P_in [J]
        ("w_diss", np.float64),  # energy dissipated, integral of D [J]
        ("p_in", np.float64),  # P_in at the current state and modes [W] (start of the next piece)
        ("diss", np.float64),  # D at the current state and modes [W]
        ("slip", np.float64),  # net plastic slip of the mean contact, int sum_i w_i |w_i'| [m]
        ("slip_rate", np.float64),  # its rate at the current state and modes [m/s]
    ]
)


@kernel_entry
def stored_energy(p, pts, y):
    """Kinetic + support-spring + contact-spring energy E of state y [J]."""
    nq = n_coords(p)
    ncon = pts.shape[0]
    vx = y[nq]
    vy = y[nq + 1]
    dx = y[0] - p.x_ms
    dy = y[1]
    e = 0.5 * p.m_s * (vx * vx + vy * vy) + 0.5 * p.c_s * (dx * dx + dy * dy)
    if nq == 3:
        e += 0.5 * p.J_s * y[nq + 2] * y[nq + 2]
    acc = 0.0
    for i in range(ncon):
        zi = 2 * nq + 2 * i
        acc += (y[zi] * y[zi] + y[zi + 1] * y[zi + 1]) / pts[i, 2]
    return e + 0.5 * acc / p.c_i


@kernel_jit
def power_balance(p, pts, modes, y):
    """(P_in [W], D [W], slip rate [m/s]) at state y in the given contact modes: the power
    the master puts in, the power the dampers and friction dissipate (module docstring,
    eq. *), and the net plastic slip rate of the mean contact, sum_i w_i |w_i'| with the
    contact shares w_i (sum 1) and |w_i'| = ||k_i| - F_St,i| / beta_i over the sliding
    contacts (paper eq. 9; 0 in stick). Weighted, it is the plastic work per unit of
    friction force mu F_n, so it does not grow with the number of contacts N.

    The contact kinematics are model.contact_state's, inlined: this runs twice per step,
    and computing cos/sin of phi once and F_St only in slide keeps it cheaper than an rhs
    evaluation (tests/test_energy.py checks eq. * against model.rhs).
    """
    nq = n_coords(p)
    om = p.omega_m
    x = y[0]
    yy = y[1]
    vx0 = y[nq]
    vy0 = y[nq + 1]
    diss = p.beta_s * (vx0 * vx0 + vy0 * vy0)
    phid = 0.0
    cph = 1.0
    sph = 0.0
    if nq == 3:
        phid = y[nq + 2]
        diss += p.beta_b * phid * phid
        cph = math.cos(y[2])
        sph = math.sin(y[2])
    p_in = 0.0
    slip = 0.0
    for i in range(modes.shape[0]):
        ci, bi, fn = contact_constants(p, pts, i)
        inv_c = 1.0 / ci
        inv_b = 1.0 / bi
        ax = 0.0
        ay = 0.0
        if nq == 3:
            ax = cph * pts[i, 0] - sph * pts[i, 1]
            ay = sph * pts[i, 0] + cph * pts[i, 1]
        # sliding velocity v and objective rate u = v + omega_m e_z x z (model.contact_state)
        vx = vx0 - phid * ay + om * (yy + ay)
        vy = vy0 + phid * ax - om * (x + ax)
        zi = 2 * nq + 2 * i
        Zx = y[zi]
        Zy = y[zi + 1]
        ux = vx - om * Zy * inv_c
        uy = vy + om * Zx * inv_c
        gx = Zx + bi * ux  # k; G = k in stick
        gy = Zy + bi * uy
        if modes[i] == STICK:
            diss += bi * (ux * ux + uy * uy)
        else:
            kn = math.sqrt(gx * gx + gy * gy)
            if kn > 0.0:
                fst, _ = friction_limit(p, fn, math.sqrt(vx * vx + vy * vy))
                gx *= fst / kn
                gy *= fst / kn
                diss += fst * (kn - fst) * inv_b
                slip += pts[i, 2] * abs(kn - fst) * inv_b  # weighted: summed below / N
            else:
                gx = 0.0
                gy = 0.0
            ex = gx - Zx
            ey = gy - Zy
            diss += (ex * ex + ey * ey) * inv_b
        # master material point under the contact: q - z, q = r + a, z = Z / c;
        # F . v_m with F = -G and v_m = omega_m (-(q - z)_y, (q - z)_x)
        mx = x + ax - Zx * inv_c
        my = yy + ay - Zy * inv_c
        p_in += om * (gx * my - gy * mx)
    return p_in, diss, slip / modes.shape[0]


@kernel_jit
def begin(p, pts, modes, y, energy):
    """Zero the work integrals and store the powers at the start state."""
    energy.w_in = 0.0
    energy.w_diss = 0.0
    energy.slip = 0.0
    refresh(p, pts, modes, y, energy)


@kernel_jit
def refresh(p, pts, modes, y, energy):
    """Store the powers at state y in the (possibly new) modes, after a switch."""
    p_in, diss, slip = power_balance(p, pts, modes, y)
    energy.p_in = p_in
    energy.diss = diss
    energy.slip_rate = slip


@kernel_jit
def integrate_piece(p, pts, modes, y0, y1, wk, s_end, h, y_end, ymid, energy):
    """Add the integrals of P_in, D and the slip rate over [t, t + s_end h] of the last step.

    Simpson's rule: the end values are exact step states (y0, and y_end = y1 or the dense
    output at an event), the midpoint comes from the step's dense output (order 3), so the
    quadrature error per step is of the order of the step's local error and falls with
    rtol like it. energy.p_in, energy.diss hold the powers at y0 on entry and at y_end on
    return (energy: the ENERGY record). ymid is scratch space.
    """
    dense_eval(y0, y1, wk, 0.5 * s_end, ymid)
    pm, dm, sm = power_balance(p, pts, modes, ymid)
    pe, de, se = power_balance(p, pts, modes, y_end)
    w = s_end * h / 6.0
    energy.w_in += w * (energy.p_in + 4.0 * pm + pe)
    energy.w_diss += w * (energy.diss + 4.0 * dm + de)
    energy.slip += w * (energy.slip_rate + 4.0 * sm + se)
    energy.p_in = pe
    energy.diss = de
    energy.slip_rate = se
