"""The verdict of the exact Coulomb pin (frictiondisk/simulation/coulomb.py integrates it).

The pin sticks for good at an onset r_s where the co-rotating circle through it is
admissible, g |r_s| + c_s |x_ms| <= mu F_n (decided exactly at the onset); that is, inside
its sticking disc of radius R* = (mu F_n - c_s |x_ms|) / g. Just above the bound it can
creep onto the disc's rim without entering it (verdict/rim_approach.py): every
`rim_check_every` onsets the gaps to the rim are tested, and a creep onto it sticks in
the limit. A run that reaches its horizon unstuck is `stick_slip` or `slide` by its final
window; with numerics.evidence observe only where shown (no disc at all, or onsets that
repeat off the rim), else `undetermined`. Reasons keep their wording: runs.nc stores them.
"""

from __future__ import annotations

import math

from .outcomes import SLIDE, STICK_SLIP, UNDETERMINED
from .params import VerdictParams
from .rim_approach import repeats, rim_limit


class CoulombRules:
    """The exact Coulomb pin's rules for one scene (thresholds from `vp`)."""

    def __init__(self, config, vp: VerdictParams):
        p = config.params
        self.vp = vp
        self.num = config.numerics
        self.limit = p.mu * p.F_n  # [N]
        self.preload = p.c_s * abs(p.x_ms)  # c_s |x_ms| [N]
        # [N/m] the force per metre of radius a co-rotating circle asks of the contact
        self.g = math.hypot(p.c_s - p.m_s * p.omega_m**2, p.beta_s * p.omega_m)
        self.disc = self._disc_radius()

    def _disc_radius(self) -> float:
        """R* [m]: radius of the sticking disc, g R* + c_s |x_ms| = mu F_n (< 0: none)."""
        reserve = self.limit - self.preload
        if self.g == 0.0:
            return math.inf if reserve >= 0.0 else -math.inf
        return reserve / self.g

    def at_onset(self, t: float, radius: float, sticks: list) -> tuple[str, float] | None:
        """At an admissible stick onset at time t [s] on a circle of `radius` [m], after
        the onsets `sticks` ((t_start, t_end, radius) each): (reason, sticking radius [m])
        of a permanent stick, or None (it breaks away again)."""
        if self.g * radius + self.preload <= self.limit:
            return (
                f"the sticking circle R = {radius:.9g} m is admissible: "
                f"g R + c_s |x_ms| <= mu F_n (exact Coulomb stick from t = {t:.6g} s)"
            ), radius
        if self.disc > 0.0 and len(sticks) % self.vp.rim_check_every == 0:
            gaps = [s[2] - self.disc for s in sticks]
            onto, evidence = rim_limit(gaps, self.num.cycle_tol, self.vp)
            if onto:
                return (
                    f"sticks in the limit on the rim of its sticking disc R* = "
                    f"{self.disc:.9g} m (exact Coulomb, creeping onto it by t = {t:.6g} s): "
                    f"{evidence}"
                ), self.disc
        return None

    def failure_reason(self, message: str) -> str:
        """Why a run whose integrator failed (scipy's `message`) is undetermined."""
        return f"integrator failed: {message}"

    def budget_reason(self) -> str:
        """Why a run that used up numerics.max_steps is undetermined."""
        return f"work budget exhausted: numerics.max_steps = {self.num.max_steps} steps"

    def not_stuck(self, frac: float, lo: float, t_end: float, sticks: list) -> tuple[str, str]:
        """(outcome, reason) of a run that reached its horizon unstuck, with stick fraction
        `frac` in its final window [lo, t_end] [s]. With numerics.evidence observe only
        where it is shown: no sticking disc exists (mu F_n < c_s |x_ms|), so no motion can
        stick, or the stick onsets repeat off the rim (a cycle); otherwise `undetermined`
        with the onsets' approach to the rim."""
        if frac > 0.0:
            outcome = STICK_SLIP
            reason = f"sticking and sliding alternate in the final window [{lo:.6g}, {t_end:.6g}] s"
        else:
            outcome = SLIDE
            reason = f"no sticking in the final window [{lo:.6g}, {t_end:.6g}] s"
        if self.disc < 0.0:
            return outcome, reason + (
                "; no sticking disc exists (mu F_n < c_s |x_ms|): it cannot stick"
            )
        if self.num.evidence != "observe":
            return outcome, reason
        gaps = [s[2] - self.disc for s in sticks]
        cycle, shown = repeats(gaps, self.num.cycle_tol, self.vp)
        if cycle:
            return outcome, f"{reason}; {shown}: a cycle reached"
        _, evidence = rim_limit(gaps, self.num.cycle_tol, self.vp)
        return UNDETERMINED, (
            f"horizon reached at t = {t_end:.6g} s without evidence that it will not stick "
            f"(numerics.evidence observe; {reason}): {evidence}; {shown}"
        )
