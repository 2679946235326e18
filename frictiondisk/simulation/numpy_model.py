"""The pin and disk scenes of docs/model.md sections 2-4 in plain numpy (`NumpyModel`).

Right-hand side, switching functions, their rate along the motion and the Jacobian's
sparsity, written again from the model document and independent of the numba kernel: the
equations behind the scipy Radau cross-check (simulation/radau.py) and the studies that
evaluate the model pointwise (studies/brake/rotation_term.py).
"""

from __future__ import annotations

import dataclasses

import numpy as np

__all__ = ["SLIDE", "STICK", "NumpyModel"]

STICK = 1  # contact mode codes, as in kernel/model.py and Trajectory.mode
SLIDE = 0

COMPLEX_STEP = 1e-30  # [s] step of the complex-step derivative of s along the motion


@dataclasses.dataclass(frozen=True)
class NumpyModel:
    """Pin or disk scene of docs/model.md sections 2-4, vectorized numpy (independent of the kernel).

    State layout as kernel/model.py, nq = 2 (pin) or 3 (disk):
        y[0:nq] = x, y (, phi);  y[nq:2nq] = vx, vy (, phidot);  y[2nq+2i:+2] = Z_i [N].
    Every method takes y of shape (n,) or (n, k) (k states at once, as scipy's vectorized
    finite-difference Jacobian asks) and returns arrays with the same trailing shape.
    Real or complex y: `switch` is analytic in y, so a complex step differentiates it.
    """

    disk: bool
    pts: np.ndarray  # body-frame contact points p_i [m], shape (N, 2)
    mu: float  # static friction coefficient
    omega_m: float  # master speed [rad/s]
    c_s: float  # support stiffness [N/m]
    beta_s: float  # support damping [N s/m]
    m_s: float  # slave mass [kg]
    J_s: float  # slave inertia [kg m^2]
    beta_b: float  # brake damping [N m s/rad]
    x_ms: float  # axes offset [m]
    c_i: np.ndarray  # stiffness of each contact w_i c [N/m], shape (N, 1)
    beta_i: np.ndarray  # damping of each contact w_i beta [N s/m], shape (N, 1)
    F_n_i: np.ndarray  # normal force of each contact w_i F_n [N], shape (N, 1)
    eps: float  # slide->stick threshold of the plastic rate [m/s]
    stribeck_r: float  # mu_kinetic / mu_static
    stribeck_v_s: float  # [m/s]
    stribeck_delta: float
    # True: u_i = v_i + omega_m e_z x z_i (docs/model.md section 3, the model). False: u_i = v_i, the
    # contact state integrated without the rotation term -- a study variant only
    # (studies/brake/rotation_term.py), reachable from Python, never from a scene file.
    objective_rate: bool = True

    @classmethod
    def from_config(cls, config, objective_rate: bool = True) -> NumpyModel:
        """Read the parameters from a SceneConfig (docs/model.md section 3: totals spread over
        the N points by the layout's weights w_i, sum w_i = 1).

        objective_rate=False drops the rotation term of the contact rate (study only)."""
        par = config.params
        con = config.contact
        n = config.n_contacts
        pts = np.asarray(config.contact_positions(), dtype=float).reshape(n, 2)
        w = (np.asarray(config.contact_weights(), dtype=float) / n).reshape(n, 1)
        return cls(
            disk=config.scene == "disk",
            pts=pts,
            mu=par.mu,
            omega_m=par.omega_m,
            c_s=par.c_s,
            beta_s=par.beta_s,
            m_s=par.m_s,
            J_s=par.J_s,
            beta_b=par.beta_b,
            x_ms=par.x_ms,
            c_i=w * con.stiffness,
            beta_i=w * config.contact_damping,
            F_n_i=w * par.F_n,
            eps=con.eps,
            stribeck_r=con.stribeck.r,
            stribeck_v_s=con.stribeck.v_s,
            stribeck_delta=con.stribeck.delta,
            objective_rate=objective_rate,
        )

    @property
    def nq(self) -> int:
        return 3 if self.disk else 2

    @property
    def n_contacts(self) -> int:
        return self.pts.shape[0]

    @property
    def n_states(self) -> int:
        return 2 * self.nq + 2 * self.n_contacts

    # --- kinematics and friction law ---------------------------------------------------

    def friction_limit(self, speed):
        """Stribeck limit F_St = F_n,i mu(|v|), mu(v) = mu [r + (1 - r) exp(-(v/v_s)^delta)]."""
        fn_mu = self.F_n_i * self.mu
        r = self.stribeck_r
        if r == 1.0:
            return fn_mu + 0.0 * speed
        xi = speed / self.stribeck_v_s
        return fn_mu * (r + (1.0 - r) * np.exp(-(xi**self.stribeck_delta)))

    def contacts(self, y):
        """Per-contact quantities, each of shape (N, k) for y of shape (n, k):

        arm a_i = R(phi) p_i, sliding velocity v_i, k_i = Z_i + beta_i u_i, F_St,i.
        """
        nq = self.nq
        om = self.omega_m
        rx, ry = y[0], y[1]  # slave centre r
        rdx, rdy = y[nq], y[nq + 1]  # its velocity r'
        Zx = y[2 * nq :: 2]
        Zy = y[2 * nq + 1 :: 2]
        if self.disk:
            phi, phid = y[2], y[nq + 2]
            cos, sin = np.cos(phi), np.sin(phi)
            px, py = self.pts[:, 0:1], self.pts[:, 1:2]
            ax = cos * px - sin * py
            ay = sin * px + cos * py
        else:
            phid = 0.0
            ax = 0.0 * Zx
            ay = 0.0 * Zy
        # contact point q = r + a; slave material velocity r' + phi' e_z x a;
        # master material velocity omega_m e_z x q (docs/model.md section 2)
        qx, qy = rx + ax, ry + ay
        slave_vx, slave_vy = rdx - phid * ay, rdy + phid * ax
        master_vx, master_vy = -om * qy, om * qx
        vx, vy = slave_vx - master_vx, slave_vy - master_vy
        # exact relative displacement rate u = v + omega_m e_z x z, z = Z / c_i (docs/model.md section 3)
        if self.objective_rate:
            zx, zy = Zx / self.c_i, Zy / self.c_i
            ux, uy = vx - om * zy, vy + om * zx
        else:  # the variant without the rotation term (studies/brake/rotation_term.py)
            ux, uy = vx, vy
        kx, ky = Zx + self.beta_i * ux, Zy + self.beta_i * uy
        speed = np.sqrt(vx * vx + vy * vy)  # sqrt, not hypot: analytic for the complex step
        return ax, ay, vx, vy, ux, uy, kx, ky, self.friction_limit(speed), Zx, Zy

    def switch(self, y, modes):
        """Switching functions [N], shape (N,) or (N, k): |k_i| - F_St,i for a contact in
        stick, |k_i| - F_St,i - beta_i eps in slide (docs/model.md section 3)."""
        y2 = np.asarray(y)
        flat = y2.ndim == 1
        if flat:
            y2 = y2[:, None]
        *_, kx, ky, fst, _, _ = self.contacts(y2)
        stick = (np.asarray(modes) == STICK)[:, None]
        offset = np.where(stick, 0.0, self.beta_i * self.eps)
        s = np.sqrt(kx * kx + ky * ky) - fst - offset
        return s[:, 0] if flat else s

    def in_band(self, y, modes):
        """Contacts inside the hysteresis band of their mode: stuck above the limit, or
        sliding below the end-of-slide threshold (kernel/switching.py)."""
        s = self.switch(y, modes)
        return np.where(np.asarray(modes) == STICK, s > 0.0, s <= 0.0)

    def rhs(self, y, modes):
        """dy/dt in the given contact modes (1 = stick, 0 = slide), docs/model.md sections 3-4."""
        y2 = np.asarray(y, dtype=float)
        flat = y2.ndim == 1
        if flat:
            y2 = y2[:, None]
        nq = self.nq
        ax, ay, _, _, ux, uy, kx, ky, fst, Zx, Zy = self.contacts(y2)
        stick = np.asarray(modes) == STICK
        # stick: Z' = c u, F = -k;  slide (plastic flow, eq. 9): Z' = (c/beta)(F_St k/|k| - Z),
        # F = -F_St k/|k| (and F = 0 at k = 0). Only the branches in use are computed.
        if stick.all():
            Zdx, Zdy = self.c_i * ux, self.c_i * uy
            Fx, Fy = -kx, -ky
        else:
            kn = np.sqrt(kx * kx + ky * ky)
            scale = fst / np.where(kn == 0.0, 1.0, kn)  # k = 0 there, so the force is 0
            gx, gy = scale * kx, scale * ky
            rate = self.c_i / self.beta_i
            Zdx, Zdy = rate * (gx - Zx), rate * (gy - Zy)
            Fx, Fy = -gx, -gy
            if stick.any():
                col = stick[:, None]
                Zdx = np.where(col, self.c_i * ux, Zdx)
                Zdy = np.where(col, self.c_i * uy, Zdy)
                Fx = np.where(col, -kx, Fx)
                Fy = np.where(col, -ky, Fy)

        f = np.empty_like(y2)
        f[0:nq] = y2[nq : 2 * nq]
        # m_s r'' = F_s + sum F_i,  F_s = -c_s (r - r0) - beta_s r',  r0 = (x_ms, 0)
        f[nq] = (-self.c_s * (y2[0] - self.x_ms) - self.beta_s * y2[nq] + Fx.sum(axis=0)) / self.m_s
        f[nq + 1] = (-self.c_s * y2[1] - self.beta_s * y2[nq + 1] + Fy.sum(axis=0)) / self.m_s
        if self.disk:
            # J_s phi'' = -beta_b phi' + sum (a_i x F_i) . e_z
            torque = (ax * Fy - ay * Fx).sum(axis=0)
            f[nq + 2] = (torque - self.beta_b * y2[nq + 2]) / self.J_s
        f[2 * nq :: 2] = Zdx
        f[2 * nq + 1 :: 2] = Zdy
        return f[:, 0] if flat else f

    def jacobian_sparsity(self) -> np.ndarray:
        """Structure of d(rhs)/dy, (n, n) of 0/1: the rigid-body block is full, contact
        i's two rows touch the rigid coordinates and Z_i, the accelerations touch every Z."""
        r = 2 * self.nq
        n = self.n_states
        pattern = np.zeros((n, n), dtype=np.int8)
        pattern[:r, :r] = 1
        pattern[self.nq : r, r:] = 1
        pattern[r:, :r] = 1
        for z in range(r, n, 2):
            pattern[z : z + 2, z : z + 2] = 1
        return pattern

    def switch_rate(self, y, f):
        """ds_i/dt along the motion y' = f, shape (N,): complex-step derivative of s (the
        same in both modes: they differ by a constant).

        ds/dt = grad s . f = Im s(y + i h f) / h exactly to round-off (no subtractive
        cancellation, so h can be 1e-30): s is analytic in y away from |k| = 0 and |v| = 0.
        """
        y = np.asarray(y, dtype=float)
        stick = np.full(self.n_contacts, STICK)
        shifted = y + 1j * COMPLEX_STEP * np.asarray(f, dtype=float)
        return self.switch(shifted, stick).imag / COMPLEX_STEP

    def stick_rate(self, y, modes, i):
        """ds_i/dt if contact i were in stick (the other contacts in `modes`)."""
        trial = np.array(modes, dtype=np.int8)
        trial[i] = STICK
        return self.switch_rate(y, self.rhs(y, trial))[i]

    def initial_modes(self, y):
        """Stick iff |k_i(0)| < F_St,i (docs/model.md section 3)."""
        s = self.switch(y, np.full(self.n_contacts, STICK))
        return np.where(s < 0.0, STICK, SLIDE).astype(np.int8)
