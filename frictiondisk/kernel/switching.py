"""Events and switching of the contact modes inside a step (numba).

Hysteresis band (docs/model.md section 3). Stick ends at |k| = F_St, slide ends at
|k| = F_St + beta eps, so a contact that has just switched sits inside a band where its
own exit threshold is behind it: a new stick contact has |k| = F_St + beta eps > F_St, a
new slide contact |k| = F_St < F_St + beta eps. Such a contact is flagged `band` and
watches a rate instead of its switching function:
* stuck in the band (above the limit): it slides as soon as |k| starts to grow
  (KIND_RISE); otherwise it could stay stuck above the limit for ever;
* sliding in the band (plastic rate below eps): it sticks as soon as stick dynamics
  would not raise |k| (KIND_REENTRY).
It leaves the band when its switching function changes sign, which is tested at step
ends (then the ordinary crossing rules apply).

Each contact's watch is a CONTACT_WATCH record (one per contact): its band flag, whether
it has just switched (fresh), how it entered stick, and the root of its event function
in the current step (kernel/events.py locates it on the step's dense output).
"""

import numpy as np

from .events import KIND_REENTRY, KIND_RISE, KIND_SWITCH, SIMULTANEOUS, brent_root, find_graze
from .jit import kernel_jit
from .model import SLIDE, STICK, rhs, stick_rate_given, switch_rate, switch_value
from .rosenbrock import dense_eval_contact

ENTERED_NONE = 0  # no switch at this event
ENTERED_CROSSING = 1  # switched by crossing its threshold (a stick entry may be refused)
ENTERED_REENTRY = 2  # a band contact re-entering stick where its stick rate fell through 0

CONTACT_WATCH = np.dtype(
    [
        ("band", np.bool_),  # inside the hysteresis band of its mode (module docstring)
        ("fresh", np.bool_),  # switched at the last event (its w sits at 0 to round-off)
        ("entered", np.int8),  # ENTERED_* of the last event
        ("root_s", np.float64),  # its root in the current step, fraction of h (2: none)
        ("root_kind", np.int8),  # KIND_* of that root (kernel/events.py)
    ]
)


@kernel_jit
def in_band(p, pts, modes, y, i):
    """Whether contact i is inside the hysteresis band of its mode (module docstring)."""
    g = switch_value(p, pts, y, i, modes[i])
    return g > 0.0 if modes[i] == STICK else g <= 0.0


@kernel_jit
def begin(p, pts, modes, y, watch):
    """The watches at the start of a run: band flags of the initial state."""
    for i in range(modes.shape[0]):
        watch[i].band = in_band(p, pts, modes, y, i)
        watch[i].fresh = False
        watch[i].entered = ENTERED_NONE
        watch[i].root_s = 2.0
        watch[i].root_kind = KIND_SWITCH


@kernel_jit
def _root(p, pts, modes, y, y1, f, f1, h, wk, watch, i, stol, ybuf, ftmp, nq):
    """Contact i's event in the step from y (rate f) to y1 (rate f1): (found, its fraction
    s of h, KIND_*); s = 0 for a contact found past its threshold without having just
    switched (a crossing missed inside an earlier step: switched here rather than hidden)."""
    sigma = 1.0 if modes[i] == STICK else -1.0
    if watch[i].band:
        kind = KIND_RISE if modes[i] == STICK else KIND_REENTRY
        sign = 1.0 if kind == KIND_RISE else -1.0
        w0 = sign * stick_rate_given(p, pts, modes, y, f, i, ftmp)
        w1 = sign * stick_rate_given(p, pts, modes, y1, f1, i, ftmp)
    else:
        kind = KIND_SWITCH
        w0 = sigma * switch_value(p, pts, y, i, modes[i])
        w1 = sigma * switch_value(p, pts, y1, i, modes[i])
    if w0 >= 0.0:
        if not watch[i].fresh:
            return True, 0.0, kind
        # just switched (w = 0 to round-off): count only a fresh crossing after a dip
        w0 = -1e-300
    s_hi = -1.0
    w_hi = 0.0
    if w1 >= 0.0:
        s_hi = 1.0
        w_hi = w1
    elif kind == KIND_SWITCH:
        d0 = sigma * switch_rate(p, pts, y, f, i) * h
        d1 = sigma * switch_rate(p, pts, y1, f1, i) * h
        sg = find_graze(p, pts, modes, y, y1, wk, i, sigma, w0, w1, d0, d1, ybuf, ftmp)
        if sg > 0.0:
            s_hi = sg
            dense_eval_contact(y, y1, wk, sg, ybuf, nq, i)
            w_hi = sigma * switch_value(p, pts, ybuf, i, modes[i])
    if s_hi > 0.0:
        sr = brent_root(
            p, pts, modes, y, y1, wk, i, sigma, kind, 0.0, w0, s_hi, w_hi, stol, ybuf, ftmp
        )
        if watch[i].fresh and sr <= stol:
            return False, 2.0, kind  # the switch we just made, seen again through round-off
        return True, sr, kind
    return False, 2.0, kind


@kernel_jit
def earliest_event(p, pts, modes, y, y1, f, f1, h, wk, watch, stol, ybuf, ftmp, nq):
    """Locate every contact's event in the step (watch[i].root_s, root_kind) and return
    the earliest as a fraction of h (> 1: none in the step)."""
    s_event = 2.0
    for i in range(modes.shape[0]):
        watch[i].root_s = 2.0
        found, sr, kind = _root(p, pts, modes, y, y1, f, f1, h, wk, watch, i, stol, ybuf, ftmp, nq)
        if found:
            watch[i].root_s = sr
            watch[i].root_kind = kind
            if sr < s_event:
                s_event = sr
    return s_event


@kernel_jit
def switch_at(p, pts, modes, y, f, watch, s_event, h, stol, counters):
    """Switch every contact whose event lies within SIMULTANEOUS of s_event (y: the state
    there), then refuse inconsistent stick entries. Returns the number of switches;
    leaves f = rhs(y) in the final modes."""
    window = max(SIMULTANEOUS / h, stol)
    for i in range(modes.shape[0]):
        watch[i].entered = ENTERED_NONE
        watch[i].fresh = False
        if watch[i].root_s > s_event + window:
            continue
        if watch[i].root_kind != KIND_SWITCH:
            # a band contact whose rate turned: switch only if it is still in the band
            # here, else it is an ordinary contact of its mode from now on
            still_in_band = in_band(p, pts, modes, y, i)
            watch[i].band = False
            if not still_in_band:
                continue
        watch[i].entered = (
            ENTERED_REENTRY if watch[i].root_kind == KIND_REENTRY else ENTERED_CROSSING
        )
        modes[i] = SLIDE if modes[i] == STICK else STICK
        watch[i].fresh = True
    check_entries(p, pts, modes, y, f, watch, counters)
    n_switched = 0
    for i in range(modes.shape[0]):
        n_switched += 1 if watch[i].entered != ENTERED_NONE else 0
    return n_switched


@kernel_jit
def check_entries(p, pts, modes, y, f, watch, counters):
    """Refused-entry check after switches (docs/model.md section 3). Returns the number refused.

    A contact entering stick by crossing its threshold (ENTERED_CROSSING) is refused (stays
    in slide) if, with stick dynamics, |k| - F_St would increase. A re-entry is consistent
    by construction: it happens where that rate has just fallen through 0. Every contact
    that switched gets its band flag. Leaves f = rhs(y) in the final modes.
    """
    rhs(p, pts, modes, y, f)
    for i in range(modes.shape[0]):
        if watch[i].entered != ENTERED_NONE or watch[i].band:
            watch[i].band = in_band(p, pts, modes, y, i)
    n_refused = 0
    for i in range(modes.shape[0]):
        if (
            watch[i].entered == ENTERED_CROSSING
            and modes[i] == STICK
            and switch_rate(p, pts, y, f, i) > 0.0
        ):
            modes[i] = SLIDE
            watch[i].entered = ENTERED_NONE
            watch[i].band = True  # sliding at its end-of-slide threshold: re-entry is watched
            n_refused += 1
    if n_refused > 0:
        counters.refused += n_refused
        rhs(p, pts, modes, y, f)
    return n_refused


@kernel_jit
def step_accepted(p, pts, modes, y, watch):
    """After a whole step without events: nothing has just switched, and a band contact
    whose switching function changed sign is an ordinary one again."""
    for i in range(modes.shape[0]):
        watch[i].fresh = False
    for i in range(modes.shape[0]):
        if watch[i].band and not in_band(p, pts, modes, y, i):
            watch[i].band = False
