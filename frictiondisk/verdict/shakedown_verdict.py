"""Melan and Koiter decide a braked disk on its small orbit. Pure numpy.

A disk that co-rotates on its small orbit (some contact stuck at every instant) carries a
load that is fixed in its body frame, C = A r and the brake torque T = beta_b omega_m, plus
the spring preload that turns once a revolution (frictiondisk/verdict/admissibility.py).
For that periodic load plasticity theory decides the long-term motion outright:

* Melan: where mu F_n exceeds the shakedown demand c_s |x_ms| + Lambda(C, T), a
  time-independent safe residual contact pattern exists, the total slip still to come is
  bounded, and the slip per revolution dies out: `stick`;
* Koiter: below it the contacts slip in every revolution for ever: `creep`.

Near that bound the run's own slip per revolution changes ever more slowly on both sides,
and the kernel's rule (slip <= eps T a revolution counts as none, docs/model.md section 6)
moves its answer below the bound by the mu at which the ratchet slows to eps T, several
tol on the braked disks of the well-posedness study. The bound does not depend on eps.
So for a braked disk that has kept its small orbit for `on_orbit_revs` revolutions
(VerdictParams), the sign of the reserve mu - demand / F_n at its own state decides, where
the reserve is wider than the margin the quasi-static bound neglects, and stays wider: its
distance from zero does not shrink, or shrinks by steps that fall geometrically
(`bound_blocks` blocks of `on_orbit_revs` revolutions) and sum to less than the rest. A
state drifting steadily towards the bound is left to the rules. The machine writes the
reserve at every revolution end (verdict/shakedown_bound.py, field `reserve` of the
revolution log) and stops a run as soon as `bound_blocks` blocks back the bound's verdict;
this module words that verdict for the label, and applies it to runs that ended otherwise
(on a shorter history).

Not applied with `numerics.evidence: observe` (watching runs count only what they show),
with stick_rule `contacts`, to pins and unbraked disks (there the shakedown demand equals
the elastic one, c_s |x_ms| + g R, and no residual pattern is at stake), or to layouts
with unequal weights whose weighted centre is off the disk's centre (there a force also
twists the disk, and the preload's share of a point is not its weight). An annulus
(points of unequal weight in bands, centred) is bounded like a ring, each point's limit
its share of mu F_n (verdict/limit_analysis.py); before 2026-12-05 it was left to the
rules, whose stick there is a ratchet slower than eps T (docs/wellposed.md).
"""

from __future__ import annotations

import numpy as np

from . import shakedown_bound as sdb
from .outcomes import CREEP, STICK, UNDETERMINED
from .params import VerdictParams

__all__ = ["applies", "centred", "decide", "margin"]


def applies(config) -> bool:
    """True where the bound may decide this scene's runs (see the module docstring)."""
    num = config.numerics
    if config.scene != "disk" or config.params.beta_b <= 0.0:
        return False
    if num.stick_rule != "corotation" or num.evidence == "observe":
        return False
    weights = np.asarray(config.contact_weights(), dtype=float)
    return bool(np.all(weights == weights[0])) or centred(config.contact_positions(), weights)


def centred(positions: np.ndarray, weights: np.ndarray) -> bool:
    """Whether the layout's weighted centre sum W_i a_i is the disk's centre (to round-off):
    then a force on the disk is shared elastically in proportion to the weights, with no
    twist, so the preload loads each point as its weight says (a ring, an annulus)."""
    positions = np.asarray(positions, dtype=float)
    weights = np.asarray(weights, dtype=float)
    centre = np.abs((weights[:, None] * positions).sum(axis=0)).max()
    arms = float((weights * np.hypot(positions[:, 0], positions[:, 1])).sum())
    return bool(centre <= 1e-12 * arms)


def margin(config, vp: VerdictParams | None = None) -> float:
    """What the quasi-static bound neglects [1, units of mu]: terms of relative order
    (beta omega_m / c)^2 (contact damping of a co-rotating contact), and the solver."""
    par = config.params
    record = (vp or VerdictParams()).record()
    damping, stiffness = config.contact_damping, config.contact.stiffness
    return float(sdb.margin(record, par.mu, damping, stiffness, par.omega_m))


def decide(
    config,
    outcome: str,
    reason: str,
    rows: np.ndarray | None,
    floor: float,
    vp: VerdictParams,
    stopped: bool = False,
):
    """(outcome, reason) after the bound: unchanged unless it applies and decides.

    outcome, reason: the rules' verdict (`stick`, `creep` and `undetermined` are
    reconsidered; below the floor also `slide` and `stick_slip` on the small orbit in
    the last revolution); rows: the revolution log, oldest first (kernel/records.py
    REVOLUTION rows, with the reserve the machine wrote); floor: the reserve against the
    least demand of any circle (verdict/shakedown_bound.floor_reserve) [1]; vp: the
    thresholds; stopped: the machine stopped the run for the bound.
    """
    if not applies(config):
        return outcome, reason
    width = margin(config, vp)
    orbiting = rows is not None and rows.shape[0] > 0 and bool(rows[-1]["any_stuck"])
    if floor < -width and (outcome == STICK or (orbiting and outcome != UNDETERMINED)):
        # no circle holds it: a stick of the rules is a ratchet slower than eps T, and a
        # disk on its small orbit ratchets there (`slide` or `stick_slip` by the rules)
        where = " on its small orbit" if orbiting else ""
        return CREEP, (
            f"ratchets for ever (Koiter){where}: mu F_n lies below the least shakedown "
            f"demand of any sticking circle, c_s |x_ms| + N beta_b omega_m / sum |a_i| "
            f"(reserve {floor:+.3g}; the bound's margin {width:.2g}), so no circle holds it "
            f"for good (the rules said: {reason})"
        )
    if outcome not in (STICK, CREEP, UNDETERMINED) or rows is None:
        return outcome, reason
    record = vp.record()
    values = np.empty(vp.bound_blocks + 1)
    count = int(sdb.history(record, rows, rows.shape[0] - 1, rows.shape[0], values))
    says = int(sdb.bound_verdict(record, values, count, width))
    if says == 0:
        return outcome, reason
    now = values[0]
    radius = float(np.hypot(rows[-1]["x"], rows[-1]["y"]))
    where = (
        f"on its small orbit at t = {rows[-1]['t']:.6g} s, radius {radius:.6g} m: "
        f"friction reserve mu - shakedown demand / F_n = {now:+.3g} ("
        + ", ".join(f"{value:+.6g}" for value in values[1:count])
        + f" every {vp.on_orbit_revs} revolutions before; the bound's margin {width:.2g})"
    )
    if says > 0:
        bound_says = STICK
        text = (
            f"shakes down (Melan) {where}: a safe residual contact pattern exists, so the "
            "slip per revolution dies out"
        )
    else:
        bound_says = CREEP
        text = (
            f"ratchets for ever (Koiter) {where}: no residual contact pattern carries the "
            "load, so the contacts slip in every revolution"
        )
    if stopped:
        return bound_says, text
    if bound_says == outcome:
        return outcome, f"{reason}; {text}"
    return bound_says, f"{text} (the rules said: {reason})"
