"""Kernel status + monitor summary -> outcome and reason (docs/model.md section 6)."""

from __future__ import annotations

import dataclasses
import math

from frictiondisk.kernel import monitor as mon
from frictiondisk.kernel import status as st

ERROR_REASONS = {
    st.MAX_STEPS: "work budget exhausted: numerics.max_steps = {max_steps} steps at t = {t:.6g} s",
    st.MAX_EVENTS: "work budget exhausted: numerics.max_events = {max_events} switches at t = {t:.6g} s",
    st.STEP_TOO_SMALL: "integrator failed: step size underflow at t = {t:.6g} s",
    st.NONFINITE: "integrator failed: non-finite state at t = {t:.6g} s",
    st.ZENO: "integrator failed: endless switching at one instant (Zeno) at t = {t:.6g} s",
}


@dataclasses.dataclass(frozen=True)
class Revolutions:
    """The per-revolution measures behind the co-rotation verdict (kernel/monitor.py)."""

    count: int  # whole master revolutions completed
    slip: float  # net plastic slip over the last revolution [m]
    drift: float  # drift of the slave centre over it, in the master frame [m]
    spin_drift: float  # drift of the spin phase phi - omega_m t over it [rad] (NaN: pin)
    decay: float  # mean log ratio of successive slips over the verdict window [1/rev]
    decay_se: float  # its standard error [1/rev]
    remaining: float  # slip still to come under that decay [m]
    limit: float  # extrapolated limit of the slip per revolution [m] (NaN: none)
    limit_spread: float  # range of that estimate made 0 ... m revolutions back [m] (NaN: none)
    on_orbit: bool  # some contact stuck at every instant of the last revolution
    settling: bool  # still on its way to a decision when the horizon budget ran out
    tol: float  # slip per revolution that counts as none, eps T [m]


@dataclasses.dataclass(frozen=True)
class Evidence:
    """What the motion's own section showed at the last check (kernel/sections.py)."""

    kind: int  # monitor_slots.EV_*
    source: int  # monitor_slots.SOURCE_CYCLES or SOURCE_REVOLUTIONS (0: none)
    distance: float  # newest section distance [m]
    ratio: float  # its contraction ratio per step (distance / the one before)
    ratio_bound: float  # the extrapolated bound on that ratio (EV_CONTRACT)
    limit: float  # slip limit [m] (EV_SHAKEDOWN) or travel still to come [m] (EV_CONTRACT)
    lag: int  # sticking phases (revolutions) per period of a repeating cycle
    points: int  # section points read

    @property
    def step(self) -> str:
        return "cycle" if self.source == mon.SOURCE_CYCLES else "revolution"

    @property
    def section(self) -> str:
        return (
            "the onsets of whole-body sticking"
            if self.source == mon.SOURCE_CYCLES
            else "the state at every master revolution"
        )

    def describe(self) -> str:
        """The evidence in words, with its measures."""
        kind = self.kind
        if kind == mon.EV_REPEAT:
            every = "" if self.lag == 1 else f" every {self.lag} {self.step}s"
            return (
                f"the section at {self.section} repeats{every} within "
                f"{self.distance:.3g} m: a cycle reached"
            )
        if kind == mon.EV_CONTRACT:
            return (
                f"the section at {self.section} contracts geometrically by {self.ratio:.3g} "
                f"per {self.step} (bound {self.ratio_bound:.3g}), {self.limit:.3g} m still to "
                "travel, towards a cycle that still slips"
            )
        if kind == mon.EV_DEPART:
            return (
                f"the section at {self.section} moves away from sticking: slip per {self.step} "
                f"growing, sticking time shrinking, steps of {self.distance:.3g} m (ratio "
                f"{self.ratio:.3g})"
            )
        if kind == mon.EV_SLIDING:
            return (
                "slides as a whole, its slip per revolution not falling revolution after "
                "revolution (no approach to sticking)"
            )
        if kind == mon.EV_CANNOT:
            return (
                "no co-rotation can hold: mu F_n is below the spring's pull c_s |x_ms| (or the "
                "brake torque over the longest arm, or, with a brake, the least shakedown "
                "demand c_s |x_ms| + N beta_b omega_m / sum |a_i|) on every sticking circle"
            )
        if kind == mon.EV_SHAKEDOWN:
            return (
                f"its slip per {self.step} falls at every {self.step} to an extrapolated limit "
                f"of {self.limit:.3g} m"
            )
        if math.isnan(self.ratio):
            return f"no evidence from its section yet ({self.points} section points)"
        return (
            f"no evidence from its section: contraction {self.ratio:.3g} per step "
            f"(bound {self.ratio_bound:.3g}), newest step {self.distance:.3g} m"
        )


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
    stick_rule: str = "contacts"  # numerics.stick_rule
    revs: Revolutions | None = None
    evidence: Evidence | None = None


def _rates(r: Revolutions) -> str:
    spin = "" if math.isnan(r.spin_drift) else f", spin drift {r.spin_drift:.3g} rad"
    return f"slip {r.slip:.3g} m, centre drift {r.drift:.3g} m{spin} per revolution"


def _trend(r: Revolutions) -> str:
    if math.isnan(r.decay):
        return "no slip trend (a revolution without slip)"
    return (
        f"slip per revolution changes by a factor exp({r.decay:.3g} \u00b1 {r.decay_se:.2g}) "
        "per revolution"
    )


def classify(facts: RunFacts) -> tuple[str, str]:
    """Return (outcome, reason); never guesses: anything unclear is `undetermined`."""
    t = facts.t_end
    revs = facts.revs
    if facts.status in ERROR_REASONS:
        reason = ERROR_REASONS[facts.status].format(
            t=t, max_steps=facts.max_steps, max_events=facts.max_events
        )
        return "undetermined", reason
    if facts.status == st.COROTATING:
        how = (
            "it repeated within the integrator's tolerance, with every contact stuck "
            f"throughout or no slip above eps T = {revs.tol:.3g} m in the last revolutions"
            if revs.remaining == 0.0
            else f"shakedown: {_trend(revs)} towards a limit of "
            f"{revs.limit:.3g} m (estimates spread {revs.limit_spread:.2g} m) <= "
            f"eps T = {revs.tol:.3g} m (slip still to come {revs.remaining:.3g} m)"
        )
        return "stick", (
            f"co-rotates with the master without net slip at t = {t:.6g} s: last revolution "
            f"{_rates(revs)}; {how}"
        )
    if facts.status == st.SHAKEN_DOWN:
        ev = facts.evidence
        return "stick", (
            f"shakes down to co-rotation at t = {t:.6g} s: {ev.describe()} <= "
            f"eps T = {revs.tol:.3g} m a revolution (last revolution {_rates(revs)})"
        )
    if facts.status == st.CREEPING:
        limit = (
            ""
            if math.isnan(revs.limit)
            else f", extrapolated limit {revs.limit:.3g} m, its estimates spread "
            f"{revs.limit_spread:.2g} m"
        )
        return "creep", (
            f"ratchets on its small orbit at t = {t:.6g} s: {_rates(revs)}, not decaying "
            f"to zero ({_trend(revs)}{limit})"
        )
    if facts.status == st.BOUND_DECIDED:
        # worded by outcome/shakedown_verdict.py, which reads the same reserves
        return "undetermined", (
            f"the run stopped at t = {t:.6g} s for the shakedown bound, which then did not "
            "decide (a kernel and outcome mismatch)"
        )
    # integrators without revolution measures apply the contacts rule (the pin only)
    contacts_rule = facts.stick_rule == "contacts" or revs is None
    if facts.status == st.STICK_HELD or (contacts_rule and facts.stuck_for >= facts.hold):
        return "stick", (
            f"every contact stuck without interruption for one master revolution "
            f"({facts.hold:.6g} s) from t = {t - facts.stuck_for:.6g} s"
        )
    lo, hi = facts.window
    if facts.status == st.CYCLE_CONVERGED:
        return "stick_slip", f"limit cycle with sticking and sliding converged at t = {t:.6g} s"
    if revs is not None and revs.settling:
        if facts.stick_rule == "corotation" and revs.count < mon.VERDICT_REVS:
            where = (
                f"after {revs.count} whole revolutions ({mon.VERDICT_REVS} are needed to "
                "tell stick, creep and stick_slip apart)"
            )
        elif revs.on_orbit and facts.stick_rule == "corotation":
            where = "on its small orbit, co-rotation not yet decided"
        else:
            evidence = facts.evidence.describe() if facts.evidence else "no evidence"
            where = f"without evidence that it will not stick: {evidence}"
        return "undetermined", (
            f"horizon budget reached at t = {t:.6g} s {where}: last revolution {_rates(revs)}; "
            f"{_trend(revs)} (raise numerics.horizon_budget or t_decide)"
        )
    why = ""
    if facts.evidence is not None and facts.evidence.kind == mon.EV_SHAKEDOWN:
        why = (
            f"; {facts.evidence.describe()}: co-rotation with grazing contacts, which "
            "stick_rule contacts does not count as stick"
        )
    elif facts.evidence is not None and facts.evidence.kind != mon.EV_NONE:
        why = f"; {facts.evidence.describe()}"
    if facts.frac_all == 0.0:
        # outcome, stick_fraction and size all mean whole-body sticking (every contact)
        partial = (
            f"; single contacts stuck {facts.frac_any:.3g} of it" if facts.frac_any > 0 else ""
        )
        return "slide", (
            f"the slave never stuck as a whole in the final window [{lo:.6g}, {hi:.6g}] s"
            f"{partial}{why}"
        )
    if facts.status == st.TMAX_REACHED:
        return "undetermined", (
            f"limit cycle not converged by numerics.t_max = {t:.6g} s "
            f"(stick fraction {facts.frac_all:.3g} in the final window)"
        )
    if facts.status == st.HORIZON_REACHED:
        return "stick_slip", (
            f"sticking and sliding alternate in the final window [{lo:.6g}, {hi:.6g}] s "
            f"(stick fraction {facts.frac_all:.3g}){why}"
        )
    return "undetermined", f"unknown kernel status {facts.status} at t = {t:.6g} s"


def revolution(omega_m: float) -> float:
    """One master revolution 2 pi / omega_m [s]; 2 pi s for a master at rest (omega_m = 0)."""
    return 2.0 * math.pi / omega_m if omega_m > 0.0 else 2.0 * math.pi
