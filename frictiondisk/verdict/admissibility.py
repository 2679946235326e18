"""Quasi-static admissibility of permanent rigid co-rotation (pin and disk), pure numpy.

A slave that sticks for good co-rotates rigidly with the master: its centre runs on a
circle r(t) = R e(theta0 + omega_m t) about the master axis and (disk) phi' = omega_m.
The contacts must then supply, at every instant (docs/model.md section 4, r'' = -omega_m^2 r):

    F(t) = m_s r'' - F_s = -c_s r0 + A r(t),    A = (c_s - m_s omega_m^2) I + beta_s omega_m J
    T    = beta_b omega_m                        (torque about the slave centre)

with r0 = (x_ms, 0) and J the rotation by +90 degrees. |A r| = g R with the pin's
g = sqrt((c_s - m_s omega_m^2)^2 + (beta_s omega_m)^2). In the slave's body frame
(which turns with omega_m) the co-rotating part C = A r and the torque are constant, and
the spring preload P = -c_s r0 (fixed in space) turns backwards once per revolution:
|F| ranges over [|g R - c_s |x_ms||, g R + c_s |x_ms|] and every contact point sees the
preload from every direction once per revolution.

Each contact point carries at most mu F_n / N (equal normal force on N points). Four
conditions on mu F_n [N], from weakest to strongest (for the pin, with N = 1 and T = 0,
all four are docs/model.md's oracle mu F_n >= c_s x_ms + g R):

* `collapse_demand`: max over the revolution of the rigid-plastic limit Lambda(F(t), T):
  below it no contact pattern at all can carry the load at some instant (gross slip).
* `shakedown_demand` (Melan): c_s |x_ms| + Lambda(C, T). Above it some time-independent,
  self-equilibrated residual contact pattern makes the whole revolution elastic, and
  associated plastic micro-slip finds one (Melan's theorem); below it (Koiter) contacts
  slip in every revolution for ever (alternating plasticity or ratcheting).
* `elastic_demand`: the load of the worst point, from a stress-free contact state, with
  the load shared elastically (equal stiffness per point): f_i = F/N + (T/(N rho)) t_i,
  so mu F_n >= c_s |x_ms| + max_i |C + (T/rho) t_i|.
* `additive_demand`: c_s |x_ms| + g R + T/rho, the continuous-ring value of the elastic
  demand and an upper bound of it for any layout on a ring of radius rho (docs/model.md section 7).

Lambda(F, T) = min over contact force patterns {f_i} with sum f_i = F, sum a_i x f_i = T
of N max_i |f_i| [N]: the smallest mu F_n that can carry (F, T) with the best
redistribution. It is computed from its kinematic (upper bound) form,
Lambda = max over rigid slip motions (v, w) of N (F.v + T w) / sum_i |v + w J a_i|, as a
convex minimisation solved by iteratively reweighted least squares; the optimal motion also
gives the optimal static pattern (the certificate returned by `limit_pattern`).

Units: SI (m, N, N m, rad/s, kg). Corrections of relative order (beta omega_m / c)^2 ~ 2e-5
(the contact damping term of a co-rotating contact) are neglected.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from frictiondisk.verdict.limit_analysis import limit_motion

__all__ = [
    "Demands",
    "LoadCase",
    "additive_demand",
    "collapse_demand",
    "demands",
    "elastic_demand",
    "elastic_pattern",
    "g_factor",
    "limit_capacity",
    "limit_pattern",
    "ring_points",
    "shakedown_demand",
]


def g_factor(omega_m: float, c_s: float, m_s: float, beta_s: float) -> float:
    """g = sqrt((c_s - m_s omega_m^2)^2 + (beta_s omega_m)^2) [N/m]: |A r| = g |r|."""
    return math.hypot(c_s - m_s * omega_m**2, beta_s * omega_m)


def ring_points(n: int, rho: float, phase: float = 0.0) -> np.ndarray:
    """Body-frame contact points on a ring: rho (cos, sin)(phase + 2 pi i / n) [m], (n, 2)."""
    ang = phase + 2.0 * np.pi * np.arange(n) / n
    return rho * np.column_stack((np.cos(ang), np.sin(ang)))


@dataclasses.dataclass(frozen=True)
class LoadCase:
    """Loads on the contacts of a slave co-rotating on a circle of radius R [m].

    omega_m [rad/s], c_s [N/m], beta_s [N s/m], m_s [kg], x_ms [m], beta_b [N m s/rad].
    """

    R: float
    omega_m: float = 1.1
    c_s: float = 1.0
    beta_s: float = 0.1
    m_s: float = 1.0
    x_ms: float = 0.1
    beta_b: float = 0.0

    @classmethod
    def of(cls, params, radius: float, beta_b: float) -> LoadCase:
        """The load case of a scene's `params` (config.Params) on a circle of `radius`
        [m], with brake damping `beta_b` [N m s/rad] (0 for a pin)."""
        return cls(
            R=float(radius),
            omega_m=params.omega_m,
            c_s=params.c_s,
            beta_s=params.beta_s,
            m_s=params.m_s,
            x_ms=params.x_ms,
            beta_b=float(beta_b),
        )

    @property
    def g(self) -> float:
        """g [N/m] (see `g_factor`)."""
        return g_factor(self.omega_m, self.c_s, self.m_s, self.beta_s)

    @property
    def preload(self) -> float:
        """|P| = c_s |x_ms| [N]: the spring preload, fixed in space."""
        return self.c_s * abs(self.x_ms)

    @property
    def torque(self) -> float:
        """T = beta_b omega_m [N m]: the brake torque the contacts carry."""
        return self.beta_b * self.omega_m

    def force(self, theta) -> np.ndarray:
        """Required contact force F [N] in the fixed frame at orbit angle theta [rad],
        shape (..., 2): F = -c_s r0 + A r, r = R (cos, sin) theta."""
        theta = np.asarray(theta, dtype=float)
        rx, ry = self.R * np.cos(theta), self.R * np.sin(theta)
        k = self.c_s - self.m_s * self.omega_m**2
        d = self.beta_s * self.omega_m
        fx = -self.c_s * self.x_ms + k * rx - d * ry
        fy = k * ry + d * rx
        return np.stack((fx, fy), axis=-1)

    def force_range(self) -> tuple[float, float]:
        """(min, max) of |F| over one revolution [N]: |g R -+ c_s |x_ms||."""
        gr = self.g * self.R
        return abs(gr - self.preload), gr + self.preload

    def body_loads(self, n_theta: int = 360, layout_angle: float = 0.0):
        """Required force in the body frame over one revolution and the constant parts.

        layout_angle [rad]: direction of the co-rotating part C = A r in the body frame
        (fixed at sticking; it only matters for a discrete layout).
        Returns (F_body (n_theta, 2) [N], C (2,) [N]).
        """
        c_dir = np.array([math.cos(layout_angle), math.sin(layout_angle)])
        c_vec = self.g * self.R * c_dir
        psi = np.linspace(0.0, 2.0 * np.pi, n_theta, endpoint=False)
        p_body = self.preload * np.column_stack((np.cos(psi), np.sin(psi)))
        return c_vec[None, :] + p_body, c_vec


def elastic_pattern(force, torque: float, points: np.ndarray) -> np.ndarray:
    """Contact forces f_i [N] carrying (force [N], torque [N m]) elastically with equal
    stiffness per point and no residual: the slave's rigid displacement (d, dphi) solves
    sum (d + dphi J a_i) = F/c, sum a_i x (d + dphi J a_i) = T/c. Shape (..., N, 2)."""
    pts = np.asarray(points, dtype=float)
    n = pts.shape[0]
    sx, sy = pts[:, 0].sum(), pts[:, 1].sum()
    s2 = float((pts**2).sum())
    # unknowns (dx, dy, dphi) scaled by c: [[n, 0, -sy], [0, n, sx], [-sy, sx, s2]]
    force = np.asarray(force, dtype=float)
    if s2 == 0.0:  # every point at the centre (pin): no torque can be carried
        if np.any(np.asarray(torque) != 0.0):
            raise ValueError("points at the centre cannot carry a torque")
        return np.broadcast_to(force[..., None, :] / n, (*force.shape[:-1], n, 2)).copy()
    mat = np.array([[n, 0.0, -sy], [0.0, n, sx], [-sy, sx, s2]])
    rhs = np.concatenate(
        (force, np.broadcast_to(np.asarray(torque, float), force.shape[:-1])[..., None]), -1
    )
    sol = np.linalg.solve(mat, rhs[..., None])[..., 0]
    d = sol[..., None, 0:2]
    dphi = sol[..., None, 2:3]
    jay = np.column_stack((-pts[:, 1], pts[:, 0]))
    return d + dphi * jay


def _irls(force, torque, points):
    """min sum_i |v + w J a_i| subject to F.v + T w = 1 (IRLS, verdict/limit_analysis.py,
    which the kernel also reads on the run); returns (v, w, value)."""
    pts = np.ascontiguousarray(points, dtype=float)
    vx, vy, w, val = limit_motion(float(force[0]), float(force[1]), float(torque), pts)
    return np.array([vx, vy]), float(w), float(val)


def limit_pattern(force, torque: float, points: np.ndarray):
    """Rigid-plastic limit of (force [N], torque [N m]) on the points: (Lambda [N], f (N, 2)).

    Lambda = min over patterns with the given resultants of N max_i |f_i|. f is the optimal
    pattern read off the optimal slip motion: f_i = (Lambda / N) s_i / |s_i|, s_i the slip
    velocity of point i (a contact at the instantaneous centre takes what balances).
    """
    force = np.asarray(force, dtype=float)
    pts = np.asarray(points, dtype=float)
    n = pts.shape[0]
    if np.linalg.norm(force) == 0.0 and torque == 0.0:
        return 0.0, np.zeros((n, 2))
    if float(np.abs(pts).max(initial=0.0)) == 0.0:  # all points at the centre (pin)
        if torque != 0.0:
            return math.inf, np.full((n, 2), np.nan)
        return float(np.linalg.norm(force)), np.broadcast_to(force / n, (n, 2)).copy()
    v, w, val = _irls(force, torque, pts)
    lam = n / val
    s = v[None, :] + w * np.column_stack((-pts[:, 1], pts[:, 0]))
    norms = np.linalg.norm(s, axis=1)
    at_centre = norms <= 1e-6 * norms.max()
    dirs = s / np.where(at_centre, 1.0, norms)[:, None]
    f = (lam / n) * dirs
    f[at_centre] = 0.0
    if at_centre.any():
        # the point(s) at the instantaneous centre do not slip: they take the rest of the
        # load (|f| <= lam / N at the optimum, up to the solver's tolerance)
        f[at_centre] = (force - f.sum(axis=0)) / int(at_centre.sum())
    return float(lam), f


def limit_capacity(force, torque: float, points: np.ndarray) -> float:
    """Lambda(F, T) [N]: the least mu F_n that can carry force [N] and torque [N m]."""
    return limit_pattern(force, torque, points)[0]


def _layout_angles(points: np.ndarray, layout_angle):
    if layout_angle is not None:
        return [float(layout_angle)]
    n = np.asarray(points).shape[0]
    # the discrete layout repeats every 2 pi / n: sample half a period each side
    return list(np.linspace(0.0, 2.0 * np.pi / max(n, 1), 5))


def additive_demand(case: LoadCase, rho: float) -> float:
    """c_s |x_ms| + g R + beta_b omega_m / rho [N] (docs/model.md section 7); rho = 0: pin."""
    extra = 0.0 if case.torque == 0.0 else case.torque / rho
    return case.preload + case.g * case.R + extra


def elastic_demand(case: LoadCase, points: np.ndarray, layout_angle=None) -> float:
    """mu F_n [N] for which the elastic sharing from a stress-free state never reaches the
    limit: c_s |x_ms| + max_i |C + (T / rho_i) t_i| (via `elastic_pattern`). layout_angle
    None: the worst direction of C relative to the layout."""
    pts = np.asarray(points, dtype=float)
    n = pts.shape[0]
    worst = 0.0
    for ang in _layout_angles(pts, layout_angle):
        _, c_vec = case.body_loads(1, ang)
        f = elastic_pattern(c_vec, case.torque, pts)
        worst = max(worst, n * float(np.linalg.norm(f, axis=1).max()))
    return case.preload + worst


def shakedown_demand(case: LoadCase, points: np.ndarray, layout_angle=None) -> float:
    """Melan: c_s |x_ms| + Lambda(C, T) [N], C = A r (|C| = g R, constant in the body
    frame). layout_angle None: the worst direction of C relative to the layout."""
    pts = np.asarray(points, dtype=float)
    worst = 0.0
    for ang in _layout_angles(pts, layout_angle):
        _, c_vec = case.body_loads(1, ang)
        worst = max(worst, limit_capacity(c_vec, case.torque, pts))
    return case.preload + worst


def collapse_demand(
    case: LoadCase, points: np.ndarray, layout_angle=None, n_theta: int = 72
) -> float:
    """max over one revolution of Lambda(F(t), T) [N]: below it the contacts cannot carry
    the load at some instant whatever their residual pattern (gross slip)."""
    pts = np.asarray(points, dtype=float)
    worst = 0.0
    for ang in _layout_angles(pts, layout_angle):
        f_body, _ = case.body_loads(n_theta, ang)
        for fb in f_body:
            worst = max(worst, limit_capacity(fb, case.torque, pts))
    return worst


@dataclasses.dataclass(frozen=True)
class Demands:
    """The four demands on mu F_n [N] for one load case, weakest first."""

    collapse: float
    shakedown: float
    elastic: float
    additive: float


def demands(case: LoadCase, points: np.ndarray, rho: float, layout_angle=None) -> Demands:
    """All four demands [N] for a slave on contact `points` (ring radius rho [m])."""
    return Demands(
        collapse=collapse_demand(case, points, layout_angle),
        shakedown=shakedown_demand(case, points, layout_angle),
        elastic=elastic_demand(case, points, layout_angle),
        additive=additive_demand(case, rho),
    )
