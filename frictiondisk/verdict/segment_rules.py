"""The stop rules of an integrator that stops only between smooth segments (the scipy-Radau
cross-check, frictiondisk/simulation/radau.py), on the same records as the state machine
(verdict/machine.py) but without revolutions: the contacts rule (every contact stuck for
one master revolution is `stick`; the rules agree with co-rotation for the pin), the
converge test, and the horizon, never stopping inside a sticking phase that may still
decide `stick`. Plain Python over the numba records: the segments are scipy's.
"""

from __future__ import annotations

from frictiondisk.kernel.monitor import stuck_for

from .machine import cycle_found
from .records import (
    AT_HORIZON,
    AT_T_MAX,
    CYCLE_FOUND,
    FINISHING_PHASE,
    NOT_EXTENDED,
    RECHECK,
    SETTLING,
    STEP_ON,
    STICK_HELD,
    STOP,
)


def begin(rules, vs) -> None:
    """The verdict record at t = 0 (rules: a RULES record, vs: a VERDICT record)."""
    vs["state"] = SETTLING
    vs["agree"] = 0
    vs["t_stop"] = rules["horizon"]
    vs["extension"] = NOT_EXTENDED


def _stop(vs, state: int) -> int:
    vs["state"] = state
    return STOP


def check(rules, motion, vs, t: float) -> int:
    """STOP (vs["state"]: how the run ended), RECHECK (the horizon moved) or STEP_ON at a
    segment end at time t [s] (motion: the MOTION record the monitor keeps)."""
    all_stuck = bool(motion["all_stuck"])
    if rules["stop_on_stick"] and all_stuck:
        # the segment is capped at exactly t_all + hold: compare with that same sum
        held = stuck_for(motion, t) >= rules["hold"]
        if held or t >= motion["t_all"] + rules["hold"]:
            return _stop(vs, STICK_HELD)
    if rules["converge"] and cycle_found(rules, vs):
        return _stop(vs, CYCLE_FOUND)
    at_horizon = AT_T_MAX if rules["converge"] else AT_HORIZON
    if t >= vs["t_stop"]:
        # Never stop inside a sticking phase that may still decide `stick`.
        if rules["stop_on_stick"] and all_stuck and vs["extension"] == NOT_EXTENDED:
            vs["extension"] = FINISHING_PHASE
            vs["t_stop"] = motion["t_all"] + rules["hold"]
            if t < vs["t_stop"]:
                return RECHECK
        return _stop(vs, at_horizon)
    if vs["extension"] == FINISHING_PHASE and not all_stuck:
        return _stop(vs, at_horizon)
    return STEP_ON


def segment_end(rules, motion, vs) -> float:
    """Where the next segment must end at the latest [s]: the horizon, or the instant an
    open sticking phase has been held one revolution."""
    t1 = vs["t_stop"]
    if rules["stop_on_stick"] and motion["all_stuck"]:
        t1 = min(t1, motion["t_all"] + rules["hold"])
    return t1
