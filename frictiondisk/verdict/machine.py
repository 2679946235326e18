"""The verdict's state machine (numba): what the step loop asks where the motion changes.

The step loop (frictiondisk/simulation/loop.py) only steps and calls the machine
(Attractors.jl's finite_state_machine.jl is the model):

* `begin` at t = 0;
* `phase_opened` where a whole-body sticking phase opens (a cycle closes: its section
  point agrees with the last ones or not, the converge test with numerics.cycle_tol);
* `revolution_closed` where a master revolution closes: the co-rotation rule, the
  section's shakedown and the shakedown bound read the revolution ring;
* `check` at every instant the loop stands at (after a step, an event or a moved
  horizon): the stop rules, and at the horizon `at_horizon`; it answers STEP_ON, RECHECK
  (the horizon moved: ask again) or STOP (VERDICT.state says how the run ended);
* `landing_time`: where the next step must end (the horizon, the instant a sticking
  phase has been held one revolution).

The states (verdict/records.py): SETTLING, and the co-rotation rule's verdict so far
(COROTATING, CREEPING, SHAKEN_DOWN) while the run goes on; the state the run ended in once
the machine stops it (also STICK_HELD, CYCLE_FOUND, BOUND_DECIDED, AT_HORIZON, AT_T_MAX).
Every threshold comes from the VerdictParams record vp, every scene setting from RULES.
"""

import math

from frictiondisk.kernel.jit import kernel_jit
from frictiondisk.kernel.monitor import stuck_for

from .budget import may_extend
from .corotation import corotation_verdict, still
from .grazing import outward_share
from .horizon_evidence import cannot_corotate, evidence_at_horizon, shaken_down
from .records import (
    AT_HORIZON,
    AT_T_MAX,
    BOUND_DECIDED,
    COROTATING,
    CREEPING,
    CYCLE_FOUND,
    EV_NONE,
    EV_SHAKEDOWN,
    FINISHING_PHASE,
    NOT_EXTENDED,
    PHASE_BROKE,
    RECHECK,
    SETTLING,
    SHAKEN_DOWN,
    STEP_ON,
    STICK_HELD,
    STOP,
)
from .shakedown_bound import close_revolution, holds_here


@kernel_jit
def begin(vp, rules, p, pts, motion, vs):
    """The machine at t = 0 (after the monitor's begin: motion.arm is known)."""
    vs.state = SETTLING
    vs.news = SETTLING
    vs.bound_says = 0
    vs.agree = 0
    vs.stribeck = p.stribeck_r < 1.0
    # A slip per revolution below what the slide->stick threshold eps lets slide
    # unresolved over a revolution is none. A model quantity: adding the integrator's atol
    # made the braked disk's mu* move with atol (docs/model.md 6).
    vs.slip_tol = p.eps * rules.hold
    vs.cannot_stick = cannot_corotate(vp, p, pts, motion.arm, rules.bound)
    vs.graze_outward = outward_share(p)
    vs.decay = math.nan
    vs.decay_se = math.nan
    vs.remaining = math.nan
    vs.limit = math.nan
    vs.limit_spread = math.nan
    vs.evidence = EV_NONE
    vs.ev_source = 0
    vs.ev_lag = 0
    vs.ev_points = 0
    vs.ev_distance = math.nan
    vs.ev_ratio = math.nan
    vs.ev_ratio_bound = math.nan
    vs.ev_limit = math.nan
    vs.sliding_revs = 0
    vs.envelope_revs = 0
    vs.t_stop = max(rules.horizon, rules.watch)  # no not-stick verdict within the watch
    vs.extension = NOT_EXTENDED
    vs.settle_revs = 0
    vs.budget_spent = False


@kernel_jit
def end_watch(rules, t):
    """At t >= rules.watch (numerics.observe_until) the watch is over: the rules may
    extrapolate again (rules.observe is the evidence in force now; the only field of RULES
    the machine changes)."""
    if rules.watch > 0.0 and t >= rules.watch:
        rules.observe = False
        rules.watch = 0.0


@kernel_jit
def phase_opened(rules, motion, vs):
    """A whole-body sticking phase opened: the new section point agrees with the cycle so
    far (vs.agree counts up) or not (back to 0). Agreement: the radius step and the arc
    within numerics.cycle_tol, the net drift of the last three radius steps too, and no
    slow outward creep (growing, one-signed radius steps: a departure, not convergence)."""
    if motion.n_sect < 2:
        return  # the first section point: no step yet
    tol = rules.cycle_tol
    dr = motion.sect_dr
    dr1 = motion.sect_dr1
    dr2 = motion.sect_dr2
    creeping = (
        not math.isnan(dr2) and dr * dr1 > 0.0 and dr1 * dr2 > 0.0 and abs(dr) > abs(dr1) > abs(dr2)
    )
    # a creep of one sign with small, steady steps shows in the net drift
    drift = dr + (0.0 if math.isnan(dr1) else dr1)
    drift += 0.0 if math.isnan(dr2) else dr2
    steady = abs(drift) <= tol
    if abs(dr) <= tol and motion.sect_arc <= tol and steady and not creeping:
        vs.agree += 1
    else:
        vs.agree = 0


@kernel_jit
def cycle_found(rules, vs):
    """Whether the cycle's section points agreed numerics.cycle_count times in a row."""
    return vs.agree >= rules.cycle_count


@kernel_jit
def revolution_closed(vp, rules, p, pts, y, motion, vs, revs, phases, seq, values, steps):
    """A master revolution closed at state y (its row the newest of revs; `steps`
    integrator steps so far; before the monitor begins the next). Judges whether it moved
    nothing (`still`), writes the bound's reserve, and reads the co-rotation rule, the
    section's shakedown and the bound: vs.news and vs.bound_says hold what they say at
    this instant, vs.state the verdict so far. seq, values: scratch."""
    row = revs[(motion.n_rev - 1) % revs.shape[0]]
    end_watch(rules, row.t)
    row.still = still(rules, motion, row, steps)
    says = 0
    if rules.bound:
        says = close_revolution(vp, p, pts, y, revs, motion.n_rev, values)
    verdict = corotation_verdict(vp, rules, motion, vs, revs)
    if (
        rules.corotation
        and verdict == SETTLING
        and not vs.cannot_stick
        and shaken_down(vp, rules, motion, vs, phases, revs, p.omega_m, seq)
    ):
        verdict = SHAKEN_DOWN
        vs.state = verdict
    stuck = verdict == COROTATING or verdict == SHAKEN_DOWN
    if rules.bound and stuck and not holds_here(vp, p, revs, motion.n_rev):
        verdict = SETTLING
        vs.state = verdict
    vs.news = verdict
    vs.bound_says = says


@kernel_jit
def _stop(vs, state):
    vs.state = state
    return STOP


@kernel_jit
def check(vp, rules, p, pts, t, motion, vs, revs, phases, seq):
    """The stop rules at time t: STOP (vs.state: how the run ended), RECHECK (the horizon
    moved) or STEP_ON. A revolution verdict counts at the instant its revolution closed."""
    t_eps = 1e-12 * max(1.0, abs(t))
    end_watch(rules, t + t_eps)
    news = vs.news
    says = vs.bound_says
    vs.news = SETTLING
    vs.bound_says = 0
    if rules.corotation:
        if rules.stop_on_stick and news == COROTATING:
            return _stop(vs, COROTATING)
        if rules.stop_on_stick and news == SHAKEN_DOWN:
            return _stop(vs, SHAKEN_DOWN)
        if not rules.converge and news == CREEPING:
            return _stop(vs, CREEPING)
        if (says == 1 and rules.stop_on_stick) or (says == -1 and not rules.converge):
            return _stop(vs, BOUND_DECIDED)  # Melan or Koiter (verdict/shakedown_verdict.py)
    elif rules.stop_on_stick and stuck_for(motion, t) >= rules.hold - t_eps:
        return _stop(vs, STICK_HELD)
    if rules.converge and cycle_found(rules, vs):
        return _stop(vs, CYCLE_FOUND)
    if t >= vs.t_stop - t_eps:
        return at_horizon(vp, rules, p, pts, t, t_eps, motion, vs, revs, phases, seq)
    if not rules.corotation and vs.extension == FINISHING_PHASE and not motion.all_stuck:
        vs.extension = PHASE_BROKE  # the open sticking phase broke: decide now
        vs.t_stop = t
        return RECHECK
    return STEP_ON


@kernel_jit
def at_horizon(vp, rules, p, pts, t, t_eps, motion, vs, revs, phases, seq):
    """The horizon t_stop reached at t without a stop rule: a verdict of the co-rotation
    rule stands; else the run ends (AT_HORIZON or AT_T_MAX, the label reads the rest) on
    evidence that it will not stick, or goes on a revolution at a time within the horizon
    budget; never inside a sticking phase that may still decide `stick`."""
    if rules.corotation and vs.state != SETTLING:
        return _stop(vs, vs.state)  # decided, kept running for stop_on_stick false
    # contacts: a held phase is `stick`; an open one is finished first (below)
    held = not rules.corotation and (
        stuck_for(motion, t) >= rules.hold - t_eps
        or (motion.all_stuck and vs.extension == NOT_EXTENDED)
    )
    go_on = False
    if not rules.converge:
        evidence = evidence_at_horizon(vp, rules, motion, vs, phases, revs, p.omega_m, seq, held)
        if evidence == EV_SHAKEDOWN and rules.corotation:
            if not rules.bound or holds_here(vp, p, revs, motion.n_rev):
                return _stop(vs, SHAKEN_DOWN)
            evidence = EV_NONE
        go_on = evidence == EV_NONE
    if go_on:  # no not-stick verdict without evidence: extend, within the budget
        if may_extend(rules, vs.t_stop, t_eps):
            vs.settle_revs += 1
            vs.t_stop += rules.hold
            return RECHECK
        vs.budget_spent = True
    if motion.all_stuck and vs.extension == NOT_EXTENDED:
        # Never stop inside a sticking phase that may still decide `stick`: it must last
        # one revolution (contacts), or cover the first whole revolution of the grid after
        # it began (corotation).
        vs.extension = FINISHING_PHASE
        if rules.corotation:
            vs.t_stop = (math.floor(motion.t_all / rules.hold) + 2.0) * rules.hold
        else:
            vs.t_stop = motion.t_all + rules.hold
        if t < vs.t_stop - t_eps:
            vs.budget_spent = False
            return RECHECK
    return _stop(vs, AT_T_MAX if rules.converge else AT_HORIZON)


@kernel_jit
def landing_time(rules, motion, vs, t_target):
    """Where the next step must end at the latest: t_target (the revolution's end) or the
    horizon, and under stick_rule contacts the instant an open sticking phase has been
    held one revolution (the decision)."""
    t_target = min(vs.t_stop, t_target)
    if rules.stop_on_stick and not rules.corotation and motion.all_stuck:
        t_target = min(t_target, motion.t_all + rules.hold)
    return t_target
