"""The evidence a run weighs besides the co-rotation rule (numba): whether its section
shows a shakedown to sticking (`shaken_down`, at every revolution), and what an undecided
run at its horizon may end on (`evidence_at_horizon`): a bound no co-rotation can pass, a
cycle reached, a geometric approach to one, a departure from sticking, a sliding state.
Without such evidence it must go on (within the horizon budget) or end undetermined.
"""

from frictiondisk.kernel.jit import kernel_jit
from frictiondisk.kernel.monitor import newest_revolution as _row

from .corotation import on_orbit, still_settling
from .grazing import grazes_inward, grazes_outward
from .records import (
    EV_CANNOT,
    EV_GRAZE,
    EV_NONE,
    EV_REPEAT,
    EV_RIM,
    EV_SHAKEDOWN,
    EV_SLIDING,
    SOURCE_CYCLES,
    SOURCE_REVOLUTIONS,
)
from .section_evidence import section_evidence
from .section_sequence import (
    cycle_sequence,
    newest_period,
    revolution_sequence,
    slip_tolerance,
)
from .shakedown_bound import floor_reserve, run_margin
from .sliding import steady_sliding


@kernel_jit
def _cycles_recent(motion, phases, revs):
    """Whether the newest whole-body sticking phase began within the last two revolutions
    (older cycles say nothing about the motion now)."""
    if motion.n_phases < 1 or motion.n_rev < 2:
        return False
    newest = phases[(motion.n_phases - 1) % phases.shape[0]].t0
    t0 = revs[_row(motion, 0)].t
    t1 = revs[_row(motion, 1)].t
    return newest >= t1 - (t0 - t1)


@kernel_jit
def _section(vp, rules, motion, vs, phases, revs, omega, seq, source):
    """The evidence of the cycle or revolution section (verdict/section_evidence.py);
    seq: scratch (section_sequence.new_sequence)."""
    if source == SOURCE_CYCLES:
        if not _cycles_recent(motion, phases, revs):
            return EV_NONE
        n = cycle_sequence(motion, phases, omega, seq)
    else:
        n = revolution_sequence(motion, revs, seq)
    if n < 2:
        return EV_NONE
    period = newest_period(motion, phases, revs, source == SOURCE_CYCLES)
    return section_evidence(vp, rules, vs, seq, n, slip_tolerance(vs, period, rules.hold))


@kernel_jit
def shaken_down(vp, rules, motion, vs, phases, revs, omega, seq):
    """Whether the slip per cycle (whole-body sticking onsets, while they are recent) or per
    revolution falls to an extrapolated limit within tolerance: `stick` by shakedown
    (EV_SHAKEDOWN). Sets the evidence fields of vs."""
    if rules.observe:
        return False  # a limit is an extrapolation: only what is seen counts
    for source in (SOURCE_CYCLES, SOURCE_REVOLUTIONS):
        if source == SOURCE_REVOLUTIONS and on_orbit(vp, motion, revs):
            continue  # corotation_verdict reads this slip, with its estimates' agreement
        if _section(vp, rules, motion, vs, phases, revs, omega, seq, source) == EV_SHAKEDOWN:
            vs.evidence = EV_SHAKEDOWN
            vs.ev_source = source
            return True
    return False


@kernel_jit
def horizon_evidence(vp, rules, motion, vs, phases, revs, omega, seq):
    """The evidence (EV_*) on which an undecided run at its horizon may end as not stick:
    the section of its recent whole-body sticking onsets or of its revolutions shows a
    cycle reached, a geometric approach to one or a departure from sticking (a sliding
    slave's revolutions are its section: a steady sliding state repeats or is approached
    geometrically), a Coulomb pin leaves its sticking circle outward every revolution
    (EV_GRAZE, verdict/grazing.py), or it slides on without approaching sticking
    (EV_SLIDING). EV_NONE: it must go on (or end undetermined). A shakedown found here is
    EV_SHAKEDOWN (stick), and so is a Coulomb pin that leaves its circle inward every
    revolution (EV_RIM, stick_rule corotation: it sticks in the limit). Sets the evidence
    fields of vs."""
    best = EV_NONE
    for source in (SOURCE_CYCLES, SOURCE_REVOLUTIONS):
        ev = _section(vp, rules, motion, vs, phases, revs, omega, seq, source)
        if ev == EV_REPEAT or (ev != EV_NONE and not rules.observe):
            best = ev
            vs.ev_source = source
            break
    if best == EV_NONE and not rules.observe and grazes_outward(vp, rules, motion, vs, revs):
        best = EV_GRAZE
        vs.ev_source = SOURCE_REVOLUTIONS
    elif best == EV_NONE and rules.corotation and not rules.observe:
        if grazes_inward(vp, rules, motion, vs, revs):
            best = EV_RIM  # stick in the limit: co-rotation needs no revolution held
            vs.ev_source = SOURCE_REVOLUTIONS
    if best == EV_NONE and not rules.observe and steady_sliding(vp, rules, motion, vs, revs):
        best = EV_SLIDING
        vs.ev_source = SOURCE_REVOLUTIONS
    vs.evidence = best
    return best


@kernel_jit
def cannot_corotate(vp, p, pts, arm, bound):
    """Whether no permanent co-rotation can be held at all, whatever the circle: a rigidly
    co-rotating slave needs a contact force whose largest value over a revolution is at
    least the spring's pull c_s |x_ms| (the preload sweeps every direction; docs/model.md
    section 7), and a torque beta_b omega_m that no contact force pattern within mu F_n
    can carry beyond a lever of the longest arm. Below either, the slave can never stick:
    a bound, not a measurement (EV_CANNOT). The band beta eps of the stuck contacts is added
    to the friction limit. arm: longest contact arm [m] (0: pin). bound: the shakedown
    bound applies (verdict/shakedown_bound.py); then also below the least shakedown demand
    of any circle, by more than the bound's margin."""
    hold = 0.0
    for i in range(pts.shape[0]):
        hold += (p.mu * p.F_n_i + p.beta_i * p.eps) * pts[i, 2]
    pull = p.c_s * abs(p.x_ms)
    if arm > 0.0:
        pull = max(pull, abs(p.beta_b * p.omega_m) / arm)
    if hold < pull:
        return True
    if not bound:
        return False
    return floor_reserve(p, pts) < -run_margin(vp, p)


@kernel_jit
def evidence_at_horizon(vp, rules, motion, vs, phases, revs, omega, seq, held):
    """What an undecided run at its horizon may end on (EV_*; EV_NONE: it must go on): a
    bound that no co-rotation can pass (EV_CANNOT), its section (horizon_evidence), or,
    stick_rule contacts, a sticking phase already held or open (then EV_REPEAT: the rule's
    own decision follows in the machine). A run still settling towards a co-rotation
    verdict (still_settling) goes on. Under stick_rule contacts a shakedown to co-rotation
    with grazing contacts is no `stick` (that rule needs every contact stuck for a
    revolution) and counts as not-stick evidence."""
    if vs.cannot_stick:
        vs.evidence = EV_CANNOT
        return EV_CANNOT
    if held:
        return EV_REPEAT
    evidence = horizon_evidence(vp, rules, motion, vs, phases, revs, omega, seq)
    if evidence == EV_RIM:
        return EV_SHAKEDOWN  # the machine stops it as shaken down; vs.evidence says how
    if evidence == EV_SHAKEDOWN and rules.corotation:
        if vs.ev_source == SOURCE_REVOLUTIONS and on_orbit(vp, motion, revs):
            return EV_NONE  # as in shaken_down: corotation_verdict decides this slip
        return EV_SHAKEDOWN
    if still_settling(vp, rules, motion, vs, revs):
        return EV_NONE
    return evidence
