"""The pin with exact Coulomb friction: a hard stick constraint, no regularization.

The independent c -> infinity reference of the regularized model (the
paper notes a single contact needs no regularization). Selected by
`numerics.method: coulomb` (scene pin only).

* Stick: the pin moves with the master, r(t) = R(omega (t - t_s)) r_s, and the friction
  force follows from the equations of motion:
      F_req(t) = m r'' - F_s = M r(t) - c_s r0,  M = (c_s - m omega^2) I + beta_s omega E,
  E = e_z x (a quarter turn). M commutes with rotations, so F_req = R(omega tau) M r_s -
  c_s r0: its largest magnitude over a revolution is g |r_s| + c_s |x_ms| with
  g = sqrt((c_s - m omega^2)^2 + (beta_s omega)^2). If that is <= mu F_n the stick is
  permanent (decided exactly at entry); otherwise the pin breaks away when |F_req| first
  reaches mu F_n, a time found in closed form.
* Slide: m r'' = F_s - mu F_n v/|v|, v = r' - omega E r (a smooth ODE while |v| > 0),
  integrated by Radau (the friction term is stiff where |v| is small) until |v| falls
  to V_STICK. There the pin sticks if the stick force
  is admissible; otherwise it slides on, its velocity passing through zero.
* Breakaway direction: slip starts along -F_req (the relative acceleration is
  -(F_req + mu F_n u)/m, parallel to u only for u = -F_req/|F_req|).

What a run is (a permanent stick, a creep onto the rim, the final window) is decided by
frictiondisk/verdict/coulomb_rules.py; this module only integrates.
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy.integrate import solve_ivp

from frictiondisk.simulation.result import SimulationResult
from frictiondisk.verdict.coulomb_rules import CoulombRules
from frictiondisk.verdict.horizon import horizon_of, revolution
from frictiondisk.verdict.outcomes import STICK, UNDETERMINED
from frictiondisk.verdict.params import VerdictParams
from frictiondisk.verdict.reserve import friction_reserve

# The integrator's numerics (no verdict thresholds: those are VerdictParams rim_*)
V_STICK = 1e-10  # [m/s] sliding speed taken as zero (the stop takes ~1e-9 s from here)
RTOL, ATOL = 1e-11, 1e-14


def _rotate(vec, angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * vec[0] - s * vec[1], s * vec[0] + c * vec[1]])


class _Pin:
    def __init__(self, config):
        p = config.params
        self.m, self.c_s, self.beta_s = p.m_s, p.c_s, p.beta_s
        self.om, self.limit = p.omega_m, p.mu * p.F_n
        self.r0 = np.array([p.x_ms, 0.0])

    def stick_force(self, r):
        """F_req [N]: the friction force that keeps the pin on the master at r."""
        mr = (self.c_s - self.m * self.om**2) * r + self.beta_s * self.om * np.array([-r[1], r[0]])
        return mr - self.c_s * self.r0

    def breakaway(self, r_s) -> float:
        """Time [s] after sticking at r_s when |F_req| first exceeds mu F_n (inf if never)."""
        a = self.stick_force(r_s) + self.c_s * self.r0  # M r_s
        b = self.c_s * self.r0
        na, nb = math.hypot(*a), math.hypot(*b)
        if self.om == 0.0 or na == 0.0 or nb == 0.0:
            return math.inf  # |F_req| is constant in stick
        # |F_req|^2 = na^2 + nb^2 - 2 na nb cos(theta + alpha), theta = omega tau
        alpha = math.atan2(a[1], a[0]) - math.atan2(b[1], b[0])
        k = (na * na + nb * nb - self.limit**2) / (2.0 * na * nb)
        if k >= 1.0:
            return math.inf
        k = max(k, -1.0)
        # cos(theta + alpha) falls through k: theta + alpha = acos(k) (mod 2 pi), first > 0
        theta = (math.acos(k) - alpha) % (2.0 * math.pi)
        return theta / self.om

    def slide_rhs(self, t, y):
        r, rd = y[:2], y[2:]
        v = rd - self.om * np.array([-r[1], r[0]])
        speed = math.hypot(*v)
        friction = -self.limit * v / speed if speed > 0.0 else np.zeros(2)
        acc = (-self.c_s * (r - self.r0) - self.beta_s * rd + friction) / self.m
        return np.concatenate([rd, acc])

    def sliding_speed(self, y):
        return math.hypot(y[2] + self.om * y[1], y[3] - self.om * y[0])


def simulate_coulomb(
    config,
    record: bool = False,
    dt_out: float = 0.0,
    *,
    dense_lu: bool = False,
    verdict: VerdictParams | None = None,
) -> SimulationResult:
    """Run the pin with exact Coulomb friction; outcome rules as in docs/model.md section 6
    (verdict/coulomb_rules.py). record, dt_out, dense_lu: no trajectory and no stage
    matrix here (the arguments of every method, simulation/simulate.py)."""
    if config.scene != "pin":
        raise ValueError("numerics.method coulomb is defined for scene pin only")
    wall0 = time.perf_counter()
    rules = CoulombRules(config, verdict or VerdictParams())
    t_end, sticks, n_steps, outcome, reason = _integrate(config, _Pin(config), rules)
    window = config.numerics.window_revs * revolution(config.params.omega_m)
    lo = max(0.0, t_end - window)
    stuck = sum(max(0.0, min(b, t_end) - max(a, lo)) for a, b, _ in sticks)
    frac = stuck / (t_end - lo) if t_end > lo else 0.0
    if outcome is None:
        outcome, reason = rules.not_stuck(frac, lo, t_end, sticks)
    first = sticks[0] if sticks else (math.nan, math.nan, math.nan)
    return SimulationResult(
        outcome=outcome,
        reason=reason,
        R1=first[2],
        t_R1=first[0],
        size=sticks[-1][2] if outcome == STICK else math.nan,
        a=math.nan,
        # each stick phase begins with a slide->stick switch and, unless it is still
        # going at the end, ends with a stick->slide switch
        n_transitions=sum(1 if end >= t_end else 2 for _, end, _ in sticks),
        stick_fraction=1.0 if outcome == STICK else frac,
        t_end=t_end,
        n_steps=n_steps,
        n_rejected=0,
        n_refused=0,
        cycle_converged=False,
        wall_s=time.perf_counter() - wall0,
        method="coulomb",
        trajectory=None,
        reserve=friction_reserve(config, first[2]),
    )


def _integrate(config, pin: _Pin, rules: CoulombRules):
    """Stick and slide from t = 0 to the horizon or a permanent stick: (t_end [s], the
    stick phases (t_start, t_end, radius), steps, outcome, reason); outcome None where the
    run reached its horizon unstuck (the final window decides)."""
    num = config.numerics
    horizon = horizon_of(config)
    p = config.params
    y = np.array([p.x_ms + p.x0, p.y0, p.vx0, p.vy0])
    t = 0.0
    sticks: list[tuple[float, float, float]] = []  # (t_start, t_end, radius)
    n_steps = 0
    outcome, reason = None, ""

    def stop_sliding(t, y):
        return pin.sliding_speed(y) - V_STICK

    stop_sliding.terminal = True
    stop_sliding.direction = -1.0

    # at rest relative to the master (at the start, or where the slide-stop event fired;
    # scipy places that event to its root tolerance, so the speed is not re-tested)
    stopped = pin.sliding_speed(y) <= V_STICK
    while t < horizon:
        if stopped:
            stopped = False
            r_s = y[:2].copy()
            force = pin.stick_force(r_s)
            if math.hypot(*force) <= pin.limit:  # admissible: stick
                radius = math.hypot(*r_s)
                permanent = rules.at_onset(t, radius, sticks)
                if permanent is not None:
                    reason, circle = permanent
                    sticks.append((t, math.inf, circle))
                    outcome = STICK
                    break
                tau = pin.breakaway(r_s)
                t_break = min(t + tau, horizon)
                sticks.append((t, t_break, radius))
                angle = pin.om * (t_break - t)
                r = _rotate(r_s, angle)
                y = np.concatenate([r, pin.om * np.array([-r[1], r[0]])])
                t = t_break
                if t >= horizon:
                    break
                # breakaway: slip starts along -F_req
                direction = -pin.stick_force(r)
                direction /= math.hypot(*direction)
                y[2:] += 10.0 * V_STICK * direction
                continue
            # not admissible: the velocity passes through zero; keep sliding
            y[2:] += 10.0 * V_STICK * (-force / math.hypot(*force))
        sol = solve_ivp(
            pin.slide_rhs,
            (t, horizon),
            y,
            method="Radau",  # the friction term is stiff where |v| is small
            rtol=RTOL,
            atol=ATOL,
            events=stop_sliding,
            max_step=0.05,
        )
        n_steps += len(sol.t) - 1
        if sol.status == -1:
            outcome, reason = UNDETERMINED, rules.failure_reason(sol.message)
            break
        t, y = float(sol.t[-1]), sol.y[:, -1].copy()
        stopped = sol.status == 1
        if n_steps > num.max_steps:
            outcome, reason = UNDETERMINED, rules.budget_reason()
            break

    return t, sticks, n_steps, outcome, reason
