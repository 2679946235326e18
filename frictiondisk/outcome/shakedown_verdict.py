"""Melan and Koiter decide a braked disk on its small orbit. Pure numpy.

A disk that co-rotates on its small orbit (some contact stuck at every instant) carries a
load that is fixed in its body frame, C = A r and the brake torque T = beta_b omega_m, plus
the spring preload that turns once a revolution (frictiondisk/outcome/admissibility.py).
For that periodic load plasticity theory decides the long-term motion outright:

* Melan: where mu F_n exceeds the shakedown demand c_s |x_ms| + Lambda(C, T), a
  time-independent safe residual contact pattern exists, the total slip still to come is
  bounded, and the slip per revolution dies out: `stick`;
* Koiter: below it the contacts slip in every revolution for ever: `creep`.

Near that bound the run's own slip per revolution changes ever more slowly on both sides,
and the kernel's rule (slip <= eps T a revolution counts as none, docs/model.md section 6)
moves its answer below the bound by the mu at which the ratchet slows to eps T, several
tol on the braked disks of the well-posedness study. The bound does not depend on eps.
So for a braked disk that has kept its small orbit for `ON_ORBIT_REVS` revolutions, the
sign of the reserve mu - demand / F_n at its own state decides, where the reserve is wider
than the margin the quasi-static bound neglects, and stays wider: its distance from zero
does not shrink, or shrinks by steps that fall geometrically (BLOCKS blocks of
ON_ORBIT_REVS revolutions) and sum to less than the rest. A state drifting steadily towards
the bound is left to the rules.

Not applied with `numerics.evidence: observe` (watching runs count only what they show),
with stick_rule `contacts`, to pins and unbraked disks (there the shakedown demand equals
the elastic one, c_s |x_ms| + g R, and no residual pattern is at stake), or to layouts
with unequal weights (the bound assumes equal normal force per point).
"""

from __future__ import annotations

import math

import numpy as np

from frictiondisk.kernel import monitor as mon
from frictiondisk.outcome import admissibility as ad

__all__ = ["ON_ORBIT_REVS", "applies", "corotation_reserve", "decide", "margin"]

ON_ORBIT_REVS = 5  # revolutions on the small orbit before the bound decides (as the rules)
BLOCKS = 3  # blocks of ON_ORBIT_REVS revolutions whose reserves show it approaching zero
SOLVER_RTOL = 1e-8  # relative accuracy of Lambda from admissibility._irls (measured 1e-9)


def applies(config) -> bool:
    """True where the bound may decide this scene's runs (see the module docstring)."""
    num = config.numerics
    if config.scene != "disk" or config.params.beta_b <= 0.0:
        return False
    if num.stick_rule != "corotation" or num.evidence == "observe":
        return False
    weights = np.asarray(config.contact_weights(), dtype=float)
    return bool(np.all(weights == weights[0]))


def corotation_reserve(config, x: float, y: float, phi: float) -> float:
    """mu - shakedown demand / F_n [1] of the disk co-rotating with centre (x, y) [m] and
    spin angle phi [rad]: the body-frame direction of C = A r fixes the layout angle."""
    par = config.params
    k = par.c_s - par.m_s * par.omega_m**2
    d = par.beta_s * par.omega_m
    layout_angle = math.atan2(k * y + d * x, k * x - d * y) - phi
    case = ad.LoadCase.of(par, math.hypot(x, y), par.beta_b)
    demand = ad.shakedown_demand(case, config.contact_positions(), layout_angle)
    return par.mu - demand / par.F_n


def margin(config) -> float:
    """What the quasi-static bound neglects [1, units of mu]: terms of relative order
    (beta omega_m / c)^2 (contact damping of a co-rotating contact), and the solver."""
    par = config.params
    ratio = config.contact_damping * par.omega_m / config.contact.stiffness
    return par.mu * (ratio**2 + SOLVER_RTOL)


def _reserve_history(config, state: np.ndarray, rows: np.ndarray, t_end: float) -> list[float]:
    """The reserve at the end of the last revolution and every ON_ORBIT_REVS revolutions
    back while the disk was on its small orbit (at most BLOCKS + 1 values, newest first)."""
    omega = config.params.omega_m
    # all at revolution ends: within a revolution the centre swings with the turning
    # preload (by about F / c), which would read as a change of the reserve
    phi = state[2] - omega * (t_end - rows[-1, mon.RV_T])  # at the end of the last row
    out = [corotation_reserve(config, rows[-1, mon.RV_X], rows[-1, mon.RV_Y], phi)]
    end = rows.shape[0]
    for _ in range(BLOCKS):
        start = end - ON_ORBIT_REVS
        if start < 1 or not np.all(rows[start:end, mon.RV_ANY_STUCK] == 1.0):
            break
        # the spin angle at the end of row start - 1: whole turns drop out of the layout angle
        phi -= float(np.sum(rows[start:end, mon.RV_DRIFT_PHI]))
        row = rows[start - 1]
        out.append(corotation_reserve(config, row[mon.RV_X], row[mon.RV_Y], phi))
        end = start
    return out


def _still_to_come(history: list[float]) -> float:
    """How far the reserve may still move towards zero [1]: 0 where it moves away from
    zero (or stands); else the geometric sum of its steps, each block's step a ratio q < 1
    of the one before (the larger of the measured ratios); infinite without that evidence."""
    now = history[0]
    steps = [abs(history[k + 1]) - abs(history[k]) for k in range(len(history) - 1)]
    if not steps or any(now * value <= 0.0 for value in history):
        return math.inf
    if steps[0] <= 0.0:
        return 0.0
    if len(steps) < BLOCKS or min(steps) <= 0.0:
        return math.inf
    ratio = max(steps[k] / steps[k + 1] for k in range(len(steps) - 1))
    if ratio >= 1.0:
        return math.inf
    return steps[0] * ratio / (1.0 - ratio)


def decide(config, outcome: str, reason: str, state: np.ndarray, rows: np.ndarray, t_end: float):
    """(outcome, reason) after the bound: unchanged unless it applies and decides.

    outcome, reason: the rules' verdict (only `stick`, `creep` and an `undetermined`
    horizon are reconsidered); state: the final state (x, y, phi, ...); rows: the revolution
    log, oldest first (monitor.RV_* columns); t_end [s].
    """
    if outcome not in ("stick", "creep", "undetermined") or not applies(config):
        return outcome, reason
    if rows is None or rows.shape[0] < ON_ORBIT_REVS + 1:
        return outcome, reason
    if not np.all(rows[-ON_ORBIT_REVS:, mon.RV_ANY_STUCK] == 1.0):
        return outcome, reason
    history = _reserve_history(config, state, rows, t_end)
    now = history[0]
    width = margin(config)
    left = abs(now) - _still_to_come(history)
    if abs(now) <= width or left <= width:
        return outcome, reason
    radius = math.hypot(rows[-1, mon.RV_X], rows[-1, mon.RV_Y])
    where = (
        f"on its small orbit at t = {rows[-1, mon.RV_T]:.6g} s, radius {radius:.6g} m: "
        f"friction reserve mu - shakedown demand / F_n = {now:+.3g} ("
        + ", ".join(f"{value:+.6g}" for value in history[1:])
        + f" every {ON_ORBIT_REVS} revolutions before; the bound's margin {width:.2g})"
    )
    if now > 0.0:
        bound_says = "stick"
        text = (
            f"shakes down (Melan) {where}: a safe residual contact pattern exists, so the "
            "slip per revolution dies out"
        )
    else:
        bound_says = "creep"
        text = (
            f"ratchets for ever (Koiter) {where}: no residual contact pattern carries the "
            "load, so the contacts slip in every revolution"
        )
    if bound_says == outcome:
        return outcome, f"{reason}; {text}"
    return bound_says, f"{text} (the rules said: {reason})"
