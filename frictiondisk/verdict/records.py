"""The verdict's records and named codes (read in numba as records, like kernel/records.py).

RULES: what this run's scene asks of the verdict (numerics.stick_rule, mode, evidence,
stop_on_stick, the horizons, cycle_tol), filled by frictiondisk/simulation/pack.py.
VERDICT: the state machine's own state (frictiondisk/verdict/machine.py) and the measures
behind its decisions, which the label (frictiondisk/verdict/label.py) words after the run.
"""

from __future__ import annotations

import numpy as np

# --- the machine's states (VERDICT.state) ----------------------------------------------
# While the run goes on the state is SETTLING or the co-rotation rule's verdict so far
# (COROTATING, CREEPING, SHAKEN_DOWN: read again at every revolution); once the machine
# stops the run it is the state the run ended in. The values are the kernel status codes
# of a run the verdict ended (the integrator's own failures: kernel/status.py, 10 and up).
SETTLING = 0  # no verdict yet: the run goes on
STICK_HELD = 1  # every contact stuck for one master revolution (stick_rule contacts): stick
AT_HORIZON = 2  # the decision horizon reached: the label reads the final window and evidence
CYCLE_FOUND = 3  # mode converge: the cycle's section points agreed cycle_count times
AT_T_MAX = 4  # mode converge: t_max reached without a converged cycle
COROTATING = 5  # co-rotates with the master without net slip (stick_rule corotation): stick
CREEPING = 6  # ratchets on its small orbit (stick_rule corotation): creep
SHAKEN_DOWN = 7  # its slip per cycle or revolution falls to nothing: stick
BOUND_DECIDED = 8  # Melan or Koiter decides a braked disk on its small orbit

# --- the horizon (VERDICT.extension) -----------------------------------------------------
NOT_EXTENDED = 0  # the horizon is t_stop as set (or extended by whole revolutions)
FINISHING_PHASE = 1  # extended to finish an open whole-body sticking phase
PHASE_BROKE = 2  # that phase broke: decide now

# --- what the machine tells the step loop -----------------------------------------------
STEP_ON = 0  # take the next step
RECHECK = 1  # the horizon moved: ask again at the same instant
STOP = 2  # stop: VERDICT.state says how the run ended

# --- evidence from the motion's own section (VERDICT.evidence) ----------------------------
EV_NONE = 0  # nothing yet: the run must go on (or end undetermined)
EV_REPEAT = 1  # the section repeats within tolerance: a cycle reached (not stick)
EV_CONTRACT = 2  # the section contracts geometrically to a cycle with slip (not stick)
EV_DEPART = 3  # slip grows and sticking time shrinks step after step (not stick)
EV_SHAKEDOWN = 4  # slip per step falls to an extrapolated limit <= tolerance (stick)
EV_CANNOT = 5  # no co-rotating state can be held: mu F_n below the spring's or brake's pull
EV_SLIDING = 6  # slides as a whole, its slip per revolution and its lowest value not falling
EV_GRAZE = 7  # leaves sticking briefly every revolution, each slip carrying it outward (not stick)
EV_RIM = 8  # ... each slip carrying it inward, onto the rim of its sticking disc (stick)
SOURCE_CYCLES = 1  # the section of the onsets of whole-body sticking phases
SOURCE_REVOLUTIONS = 2  # the section of the state at every whole master revolution

RULES = np.dtype(
    [
        ("corotation", np.bool_),  # stick_rule corotation (else contacts)
        ("converge", np.bool_),  # mode converge: run until the limit cycle converged
        ("stop_on_stick", np.bool_),  # stop at a stick verdict
        ("observe", np.bool_),  # evidence observe (now): verdicts only on what the run shows
        ("watch", np.float64),  # observe until this time, then extrapolate [s] (0: no watch)
        ("follow_until", np.float64),  # a departure decides only at the last horizon before [s]
        ("bound", np.bool_),  # the shakedown bound decides this braked disk too
        ("hold", np.float64),  # one master revolution T [s]
        ("horizon", np.float64),  # t_decide or t_max [s]
        ("budget", np.float64),  # largest horizon a run still settling may extend to [s]
        ("cycle_tol", np.float64),  # agreement of a converged cycle's section points [m]
        ("cycle_count", np.int64),  # successive section points that must agree
        ("rtol", np.float64),  # the integrator's tolerances, for the section tolerances
        ("atol", np.float64),
    ]
)

VERDICT = np.dtype(
    [
        ("state", np.int64),  # SETTLING ... BOUND_DECIDED (above)
        ("news", np.int64),  # the verdict of a revolution closed at this instant (SETTLING: none)
        ("bound_says", np.int64),  # the bound at a revolution closed now: +1 Melan, -1 Koiter, 0
        ("agree", np.int64),  # consecutive agreeing section points (mode converge)
        ("stribeck", np.bool_),  # the friction law falls with the slip speed (r < 1)
        ("cannot_stick", np.bool_),  # no co-rotation can be held (horizon_evidence.cannot_corotate)
        # outward share of a grazing slip's direction (verdict/grazing.py; NaN: not a Coulomb pin)
        ("graze_outward", np.float64),
        ("slip_tol", np.float64),  # slip per revolution that counts as none, eps T [m]
        # the co-rotation rule's measures of the last revolution verdict
        ("decay", np.float64),  # mean log ratio of successive slips per revolution [1/rev]
        ("decay_se", np.float64),  # its standard error [1/rev]
        ("remaining", np.float64),  # slip still to come under geometric decay [m]
        ("limit", np.float64),  # extrapolated limit of the slip per revolution [m]
        ("limit_spread", np.float64),  # range of that estimate made 0 ... m revolutions back [m]
        # the section evidence of the last check
        ("evidence", np.int64),  # EV_* (above)
        ("ev_source", np.int64),  # SOURCE_CYCLES or SOURCE_REVOLUTIONS (0: none)
        ("ev_lag", np.int64),  # sticking phases (revolutions) per period behind EV_REPEAT
        ("ev_points", np.int64),  # section points behind the evidence
        ("ev_distance", np.float64),  # newest section distance [m]
        ("ev_ratio", np.float64),  # its contraction ratio per step
        ("ev_ratio_bound", np.float64),  # the extrapolated bound on that ratio (EV_CONTRACT)
        ("ev_limit", np.float64),  # slip limit (EV_SHAKEDOWN) or travel still to come [m]
        ("sliding_revs", np.int64),  # revolutions slid as a whole at the last sliding check
        ("envelope_revs", np.int64),  # H of its lowest-slip comparison (verdict/sliding.py)
        # the horizon
        ("t_stop", np.float64),  # where the run stops unless a rule decides earlier [s]
        ("extension", np.int64),  # NOT_EXTENDED, FINISHING_PHASE or PHASE_BROKE
        ("settle_revs", np.int64),  # revolutions the horizon grew by for a run still settling
        ("budget_spent", np.bool_),  # a run still settling hit the horizon budget
    ]
)
