"""Kernel status + monitor summary -> outcome and reason (docs/model.md section 6)."""

from __future__ import annotations

import dataclasses
import math

from .kernel import status as st

ERROR_REASONS = {
    st.MAX_STEPS: "work budget exhausted: numerics.max_steps = {max_steps} steps at t = {t:.6g} s",
    st.MAX_EVENTS: "work budget exhausted: numerics.max_events = {max_events} switches at t = {t:.6g} s",
    st.STEP_TOO_SMALL: "integrator failed: step size underflow at t = {t:.6g} s",
    st.NONFINITE: "integrator failed: non-finite state at t = {t:.6g} s",
    st.ZENO: "integrator failed: endless switching at one instant (Zeno) at t = {t:.6g} s",
}


@dataclasses.dataclass(frozen=True)
class RunFacts:
    """What the kernel reports about one run, in the units of the model (s, m)."""

    status: int
    t_end: float
    stuck_for: float  # uninterrupted whole-body sticking at t_end [s]
    hold: float  # sticking time that decides `stick` [s]
    window: tuple[float, float]  # final window [s]
    frac_all: float  # window fraction with every contact sticking (decides the outcome)
    frac_any: float  # window fraction with some contact sticking (reported only)
    converge_mode: bool
    max_steps: int
    max_events: int


def classify(facts: RunFacts) -> tuple[str, str]:
    """Return (outcome, reason); never guesses: anything unclear is `undetermined`."""
    t = facts.t_end
    if facts.status in ERROR_REASONS:
        reason = ERROR_REASONS[facts.status].format(
            t=t, max_steps=facts.max_steps, max_events=facts.max_events
        )
        return "undetermined", reason
    if facts.status == st.STICK_HELD or facts.stuck_for >= facts.hold:
        return "stick", (
            f"every contact stuck without interruption for one master revolution "
            f"({facts.hold:.6g} s) from t = {t - facts.stuck_for:.6g} s"
        )
    lo, hi = facts.window
    if facts.status == st.CYCLE_CONVERGED:
        return "stick_slip", f"limit cycle with sticking and sliding converged at t = {t:.6g} s"
    if facts.frac_all == 0.0:
        # outcome, stick_fraction and size all mean whole-body sticking (every contact)
        partial = (
            f"; single contacts stuck {facts.frac_any:.3g} of it" if facts.frac_any > 0 else ""
        )
        return "slide", (
            f"the slave never stuck as a whole in the final window [{lo:.6g}, {hi:.6g}] s{partial}"
        )
    if facts.status == st.TMAX_REACHED:
        return "undetermined", (
            f"limit cycle not converged by numerics.t_max = {t:.6g} s "
            f"(stick fraction {facts.frac_all:.3g} in the final window)"
        )
    if facts.status == st.HORIZON_REACHED:
        return "stick_slip", (
            f"sticking and sliding alternate in the final window [{lo:.6g}, {hi:.6g}] s "
            f"(stick fraction {facts.frac_all:.3g}); no permanent sticking by the horizon"
        )
    return "undetermined", f"unknown kernel status {facts.status} at t = {t:.6g} s"


def revolution(omega_m: float) -> float:
    """One master revolution 2 pi / omega_m [s]; 2 pi s for a master at rest (omega_m = 0)."""
    return 2.0 * math.pi / omega_m if omega_m > 0.0 else 2.0 * math.pi
