"""Equations of motion of the pin and disk scenes (docs/model.md sections 2-4), numba only.

Contacts: pts has one row (px, py, w) per contact: body-frame point p_i [m] and relative
weight w = N w_i (mean 1; 1.0 on a ring, frictiondisk/model/layouts.py). Contact i has stiffness
c_i = w p.c_i, damping beta_i = w p.beta_i and normal force F_n,i = w p.F_n_i.

State layout, nq = 2 (pin) or 3 (disk):
    y[0:nq]        x, y [m] (, phi [rad])
    y[nq:2nq]      vx, vy [m/s] (, phidot [rad/s])
    y[2nq+2i:+2]   Z_i = c_i z_i, elastic contact force of contact i in the fixed frame [N]

Every contact law is written as  F_i = -G_i,  dZ_i/dt = (c_i/beta_i) (G_i - Z_i)  with
    G_i = k_i                      (stick)
    G_i = F_St,i k_i / |k_i|       (slide, plastic flow of paper eq. 9)
    k_i = Z_i + beta_i u_i,  u_i = v_i + omega_m e_z x z_i   (objective rate, docs/model.md section 3)
In stick this is dZ/dt = c u; both forms are the same law.

Switching functions of contact i (docs/model.md section 3):
    stick -> slide when g_i = |k_i| - F_St,i crosses 0 upwards;
    slide -> stick when g_i - beta_i eps crosses 0 downwards (the plastic rate
    (|k| - F_St)/beta falls through eps).
The stick limit is exactly F_St (eps only decides when sliding ends). Between the two
thresholds lies a band of width beta eps where either mode is possible; kernel/switching.py
handles contacts inside it.
"""

import math

import numpy as np

from .jit import kernel_entry, kernel_jit

# The parameter record p (one element of a PARAMETERS array, built by
# frictiondisk/simulation/pack.py `pack_parameters`): the scene's physics, read by name.
PARAMETERS = np.dtype(
    [
        ("mu", np.float64),  # static friction coefficient mu
        ("omega_m", np.float64),  # master speed omega_m [rad/s]
        ("c_s", np.float64),  # support stiffness c_s [N/m]
        ("beta_s", np.float64),  # support damping beta_s [N s/m]
        ("m_s", np.float64),  # slave mass m_s [kg]
        ("J_s", np.float64),  # slave inertia J_s [kg m^2]
        ("beta_b", np.float64),  # brake damping beta_b [N m s/rad]
        ("x_ms", np.float64),  # axes offset x_ms [m]
        ("c_i", np.float64),  # mean stiffness per contact c/N [N/m] (times pts[i, 2]: c_i)
        ("beta_i", np.float64),  # mean damping per contact beta/N [N s/m] (times pts[i, 2])
        ("F_n_i", np.float64),  # mean normal force per contact F_n/N [N] (times pts[i, 2])
        ("eps", np.float64),  # slide->stick threshold of the plastic rate eps [m/s]
        ("stribeck_r", np.float64),  # Stribeck ratio r = mu_kinetic / mu_static
        ("stribeck_v_s", np.float64),  # Stribeck speed v_s [m/s]
        ("stribeck_delta", np.float64),  # Stribeck exponent delta
        ("disk", np.bool_),  # True for the disk (rotation degree of freedom), False for the pin
    ]
)

STICK = 1
SLIDE = 0


@kernel_jit
def n_coords(p):
    """Number of generalized coordinates: 2 (pin) or 3 (disk)."""
    return 3 if p.disk else 2


@kernel_jit
def contact_constants(p, pts, i):
    """Stiffness c_i [N/m], damping beta_i [N s/m] and normal force F_n,i [N] of contact i."""
    w = pts[i, 2]
    return p.c_i * w, p.beta_i * w, p.F_n_i * w


@kernel_jit
def friction_limit(p, fn, speed):
    """Stribeck limit F_St = F_n,i mu(|v|) [N] of a contact with normal force fn [N], and
    its derivative with respect to |v|."""
    fn_mu = fn * p.mu
    r = p.stribeck_r
    if r == 1.0:
        return fn_mu, 0.0
    vs = p.stribeck_v_s
    delta = p.stribeck_delta
    xi = speed / vs
    if xi <= 0.0:
        return fn_mu, 0.0
    ex = math.exp(-(xi**delta))
    f = fn_mu * (r + (1.0 - r) * ex)
    df = -fn_mu * (1.0 - r) * ex * delta * xi ** (delta - 1.0) / vs
    return f, df


@kernel_jit
def body_rotation(p, y):
    """(cos phi, sin phi) of the slave's rotation; (1, 0) for the pin."""
    if not p.disk:
        return 1.0, 0.0
    return math.cos(y[2]), math.sin(y[2])


@kernel_jit
def contact_state(p, pts, y, i):
    """Arm (ax, ay), sliding velocity v_i, vector k_i and limit F_St,i of contact i.

    v_i = (slave velocity at q_i) - omega_m e_z x q_i, q_i = r + a_i  (docs/model.md section 2).
    """
    c, s = body_rotation(p, y)
    return contact_state_rot(p, pts, y, i, c, s)


@kernel_jit
def contact_state_rot(p, pts, y, i, c, s):
    """contact_state with (cos phi, sin phi) = (c, s) given: loops over the contacts
    compute them once (body_rotation) instead of once per contact."""
    nq = n_coords(p)
    om = p.omega_m
    ax = 0.0
    ay = 0.0
    if nq == 3:
        ax = c * pts[i, 0] - s * pts[i, 1]
        ay = s * pts[i, 0] + c * pts[i, 1]
    phid = y[nq + 2] if nq == 3 else 0.0
    vx = y[nq] - phid * ay + om * (y[1] + ay)
    vy = y[nq + 1] + phid * ax - om * (y[0] + ax)
    zi = 2 * nq + 2 * i
    Zx = y[zi]
    Zy = y[zi + 1]
    ci, bi, fn = contact_constants(p, pts, i)
    # u = v + omega_m e_z x (Z / c): the master point under the contact has moved by -z.
    kx = Zx + bi * (vx - om * Zy / ci)
    ky = Zy + bi * (vy + om * Zx / ci)
    speed = math.sqrt(vx * vx + vy * vy)
    fst, dfst = friction_limit(p, fn, speed)
    return ax, ay, vx, vy, kx, ky, fst, dfst


@kernel_entry
def switch_value(p, pts, y, i, mode):
    """Switching function of contact i in `mode` [N]: |k_i| - F_St,i in stick,
    |k_i| - F_St,i - beta_i eps in slide. Its sign change ends the mode."""
    _, _, _, _, kx, ky, fst, _ = contact_state(p, pts, y, i)
    g = math.sqrt(kx * kx + ky * ky) - fst
    if mode == SLIDE:
        g -= p.beta_i * pts[i, 2] * p.eps
    return g


@kernel_jit
def switch_rate(p, pts, y, f, i):
    """Time derivative of the switching function of contact i (either mode: they differ
    by a constant) along the motion with state rate f = dy/dt [N/s]."""
    nq = n_coords(p)
    om = p.omega_m
    ci, bi, _ = contact_constants(p, pts, i)
    ax, ay, vx, vy, kx, ky, fst, dfst = contact_state(p, pts, y, i)
    xd = y[nq]
    yd = y[nq + 1]
    if nq == 3:
        phid = y[nq + 2]
        phidd = f[nq + 2]
    else:
        phid = 0.0
        phidd = 0.0
    # dv/dt = r'' + phi'' e_z x a - phi' (phi' - omega) a - omega e_z x r'
    vdx = f[nq] - phidd * ay - phid * (phid - om) * ax + om * yd
    vdy = f[nq + 1] + phidd * ax - phid * (phid - om) * ay - om * xd
    zi = 2 * nq + 2 * i
    Zdx = f[zi]
    Zdy = f[zi + 1]
    kdx = Zdx + bi * (vdx - om * Zdy / ci)
    kdy = Zdy + bi * (vdy + om * Zdx / ci)
    kn = math.sqrt(kx * kx + ky * ky)
    rate = 0.0
    if kn > 0.0:
        rate = (kx * kdx + ky * kdy) / kn
    speed = math.sqrt(vx * vx + vy * vy)
    if dfst != 0.0 and speed > 0.0:
        rate -= dfst * (vx * vdx + vy * vdy) / speed
    return rate


@kernel_jit
def stick_rate(p, pts, modes, y, i, fbuf):
    """ds_i/dt if contact i were in stick, the other contacts unchanged [N/s].

    Used where no state rate at y is at hand (root finding of a band contact's event on
    the dense output, O(N)); with f = rhs(y), stick_rate_given does it in O(1). fbuf is
    scratch space for the state rate."""
    old = modes[i]
    modes[i] = STICK
    rhs(p, pts, modes, y, fbuf)
    modes[i] = old
    return switch_rate(p, pts, y, fbuf, i)


@kernel_jit
def stick_rate_given(p, pts, modes, y, f, i, fbuf):
    """stick_rate from f = rhs(y) in `modes`, in O(1) instead of O(N).

    Putting contact i into stick changes only its force G_i (-> k_i) and its own Z rate,
    so only the entries switch_rate reads are formed in fbuf: the accelerations and
    Z_i' (the rest of fbuf is left as is)."""
    if modes[i] == STICK:
        return switch_rate(p, pts, y, f, i)
    nq = n_coords(p)
    ax, ay, _, _, kx, ky, fst, _ = contact_state(p, pts, y, i)
    kn = math.sqrt(kx * kx + ky * ky)
    gx = 0.0
    gy = 0.0
    if kn > 0.0:
        gx = fst * kx / kn
        gy = fst * ky / kn
    dx = kx - gx  # change of G_i; the slave feels -G_i
    dy = ky - gy
    fbuf[nq] = f[nq] - dx / p.m_s
    fbuf[nq + 1] = f[nq + 1] - dy / p.m_s
    if nq == 3:
        fbuf[nq + 2] = f[nq + 2] - (ax * dy - ay * dx) / p.J_s
    ci, bi, _ = contact_constants(p, pts, i)
    zi = 2 * nq + 2 * i
    fbuf[zi] = ci / bi * (kx - y[zi])
    fbuf[zi + 1] = ci / bi * (ky - y[zi + 1])
    return switch_rate(p, pts, y, fbuf, i)


@kernel_jit
def rhs(p, pts, modes, y, f):
    """dy/dt of the scene in the given contact modes (paper eqs. 3-10, docs/model.md section 4)."""
    nq = n_coords(p)
    ncon = modes.shape[0]
    m = p.m_s
    fx = -p.c_s * (y[0] - p.x_ms) - p.beta_s * y[nq]
    fy = -p.c_s * y[1] - p.beta_s * y[nq + 1]
    torque = 0.0
    c, s = body_rotation(p, y)
    for i in range(ncon):
        ax, ay, _, _, kx, ky, fst, _ = contact_state_rot(p, pts, y, i, c, s)
        if modes[i] == STICK:
            gx = kx
            gy = ky
        else:
            kn = math.sqrt(kx * kx + ky * ky)
            if kn > 0.0:
                gx = fst * kx / kn
                gy = fst * ky / kn
            else:
                gx = 0.0
                gy = 0.0
        ci, bi, _ = contact_constants(p, pts, i)
        zi = 2 * nq + 2 * i
        f[zi] = ci / bi * (gx - y[zi])
        f[zi + 1] = ci / bi * (gy - y[zi + 1])
        fx -= gx
        fy -= gy
        torque -= ax * gy - ay * gx
    for j in range(nq):
        f[j] = y[nq + j]
    f[nq] = fx / m
    f[nq + 1] = fy / m
    if nq == 3:
        f[nq + 2] = (torque - p.beta_b * y[nq + 2]) / p.J_s


@kernel_jit
def _contact_linearization(p, pts, modes, y, i, c, s, dg, pm):
    """Linearization of contact i's force G_i (rhs: F_i = -G_i, Z_i' = (c_i/beta_i)(G_i - Z_i)).

    dg (2, 2 nq) receives dG_i/d(x, y, (phi), vx, vy, (phidot)) through the sliding
    velocity; pm (2, 2) receives dG_i/dZ_i. Returns (ax, ay, gx, gy, c_i/beta_i). The
    rows of the Jacobian follow from these alone: every contact couples only to the
    rigid-body coordinates (kernel/linalg.py, arrow form).
    """
    nq = n_coords(p)
    om = p.omega_m
    ci, bi, _ = contact_constants(p, pts, i)
    phid = y[nq + 2] if nq == 3 else 0.0
    ax, ay, vx, vy, kx, ky, fst, dfst = contact_state_rot(p, pts, y, i, c, s)
    kn = math.sqrt(kx * kx + ky * ky)
    # M = dG/dk and g = dG/dF_St
    if modes[i] == STICK or kn == 0.0:
        m00 = 1.0
        m01 = 0.0
        m10 = 0.0
        m11 = 1.0
        gx = kx
        gy = ky
        g0 = 0.0
        g1 = 0.0
    else:
        ux = kx / kn
        uy = ky / kn
        sc = fst / kn
        m00 = sc * (1.0 - ux * ux)
        m01 = -sc * ux * uy
        m10 = m01
        m11 = sc * (1.0 - uy * uy)
        gx = fst * ux
        gy = fst * uy
        g0 = ux
        g1 = uy
    # dk/dZ = I + (beta omega / c) E,  E = [[0, -1], [1, 0]]
    w = bi * om / ci
    pm[0, 0] = m00 + m01 * w
    pm[0, 1] = -m00 * w + m01
    pm[1, 0] = m10 + m11 * w
    pm[1, 1] = -m10 * w + m11
    # Q = beta M + g (dF_St/dv)^T
    speed = math.sqrt(vx * vx + vy * vy)
    dsx = 0.0
    dsy = 0.0
    if dfst != 0.0 and speed > 0.0:
        dsx = dfst * vx / speed
        dsy = dfst * vy / speed
    q00 = bi * m00 + g0 * dsx
    q01 = bi * m01 + g0 * dsy
    q10 = bi * m10 + g1 * dsx
    q11 = bi * m11 + g1 * dsy
    # dG/d(coordinate) = Q dv/d(coordinate); dv/dx = (0, -om), dv/dy = (om, 0),
    # dv/dvx = (1, 0), dv/dvy = (0, 1), dv/dphi = (om - phid) a, dv/dphidot = e_z x a
    dg[0, 0] = -q01 * om
    dg[1, 0] = -q11 * om
    dg[0, 1] = q00 * om
    dg[1, 1] = q10 * om
    dg[0, nq] = q00
    dg[1, nq] = q10
    dg[0, nq + 1] = q01
    dg[1, nq + 1] = q11
    if nq == 3:
        dpx = (om - phid) * ax
        dpy = (om - phid) * ay
        dg[0, 2] = q00 * dpx + q01 * dpy
        dg[1, 2] = q10 * dpx + q11 * dpy
        dg[0, nq + 2] = -q00 * ay + q01 * ax
        dg[1, nq + 2] = -q10 * ay + q11 * ax
    return ax, ay, gx, gy, ci / bi


@kernel_jit
def _rigid_jacobian(p, y, jac):
    """The rigid-body part of d(rhs)/dy (rows and columns 0 .. 2 nq - 1) without contacts."""
    nq = n_coords(p)
    m = p.m_s
    for i in range(2 * nq):
        for j in range(2 * nq):
            jac[i, j] = 0.0
    for j in range(nq):
        jac[j, nq + j] = 1.0
    jac[nq, 0] = -p.c_s / m
    jac[nq + 1, 1] = -p.c_s / m
    jac[nq, nq] = -p.beta_s / m
    jac[nq + 1, nq + 1] = -p.beta_s / m
    if nq == 3:
        jac[nq + 2, nq + 2] = -p.beta_b / p.J_s


@kernel_jit
def jacobian(p, pts, modes, y, jac, lin):
    """Analytic Jacobian d(rhs)/dy in the given contact modes, dense (n, n). lin: scratch
    of at least (4, 2 nq) for one contact's linearization (`_contact_linearization`)."""
    nq = n_coords(p)
    m = p.m_s
    jac[:, :] = 0.0
    _rigid_jacobian(p, y, jac)
    dg = lin[0:2, : 2 * nq]
    pm = lin[2:4, :2]
    c, s = body_rotation(p, y)
    for i in range(modes.shape[0]):
        ax, ay, gx, gy, rate = _contact_linearization(p, pts, modes, y, i, c, s, dg, pm)
        zi = 2 * nq + 2 * i
        for col in range(2 * nq):
            dgx = dg[0, col]
            dgy = dg[1, col]
            jac[nq, col] -= dgx / m
            jac[nq + 1, col] -= dgy / m
            jac[zi, col] += rate * dgx
            jac[zi + 1, col] += rate * dgy
            if nq == 3:
                jac[nq + 2, col] -= (ax * dgy - ay * dgx) / p.J_s
        for a in range(2):
            for b in range(2):
                jac[nq + a, zi + b] -= pm[a, b] / m
                jac[zi + a, zi + b] += rate * (pm[a, b] - (1.0 if a == b else 0.0))
        if nq == 3:
            jac[nq + 2, zi] -= (ax * pm[1, 0] - ay * pm[0, 0]) / p.J_s
            jac[nq + 2, zi + 1] -= (ax * pm[1, 1] - ay * pm[0, 1]) / p.J_s
            # the arm itself turns with phi: d(a x F)/dphi += -(a . F) with F = -G
            jac[nq + 2, 2] += (ax * gx + ay * gy) / p.J_s


@kernel_jit
def jacobian_arrow(p, pts, modes, y, jac, lin):
    """Analytic Jacobian d(rhs)/dy in the arrow form of kernel/linalg.py, shape (n, 4 nq + 2):
    the numbers of `jacobian` (to round-off: 1/m_s, 1/J_s are multiplied), in O(N) time
    and memory. Every contact entry is written once, so only the rigid rows are zeroed.
    lin: scratch as for `jacobian`."""
    nq = n_coords(p)
    r = 2 * nq
    inv_m = 1.0 / p.m_s
    inv_j = 1.0 / p.J_s
    _rigid_jacobian(p, y, jac)
    dg = lin[0:2, :r]
    pm = lin[2:4, :2]
    c, s = body_rotation(p, y)
    for i in range(modes.shape[0]):
        ax, ay, gx, gy, rate = _contact_linearization(p, pts, modes, y, i, c, s, dg, pm)
        zi = r + 2 * i
        for col in range(r):
            dgx = dg[0, col]
            dgy = dg[1, col]
            jac[nq, col] -= dgx * inv_m
            jac[nq + 1, col] -= dgy * inv_m
            jac[zi, col] = rate * dgx
            jac[zi + 1, col] = rate * dgy
            if nq == 3:
                jac[nq + 2, col] -= (ax * dgy - ay * dgx) * inv_j
        # contact row zi + a: columns r, r + 1 hold its 2x2 block, r + 2 + k holds the
        # entry (k, zi + a) of the rigid rows (column zi + a of the Jacobian, transposed);
        # the position rows k < nq do not depend on Z
        for k in range(nq):
            jac[zi, r + 2 + k] = 0.0
            jac[zi + 1, r + 2 + k] = 0.0
        for a in range(2):
            for b in range(2):
                jac[zi + b, r + 2 + nq + a] = -pm[a, b] * inv_m
                jac[zi + a, r + b] = rate * (pm[a, b] - (1.0 if a == b else 0.0))
        if nq == 3:
            jac[zi, r + 2 + nq + 2] = -(ax * pm[1, 0] - ay * pm[0, 0]) * inv_j
            jac[zi + 1, r + 2 + nq + 2] = -(ax * pm[1, 1] - ay * pm[0, 1]) * inv_j
            jac[nq + 2, 2] += (ax * gx + ay * gy) * inv_j
