"""The two sections of the motion, as sequences the evidence reads (numba).

* cycles: the onset of every whole-body sticking phase (the phase ring): the slave centre
  there, the arc it then sticks for, and the slip and time to the next onset;
* revolutions: the state at the end of every whole master revolution (the revolution
  ring): centre, velocity and spin rate, all in metres.

Each gives a sequence of section points p_n [m] with the slip s_n [m] and the sticking
time tau_n [s] of each step between them: a tuple (points (SEQ_MAX, N_COORD), slip
(SEQ_MAX), stick (SEQ_MAX)) of scratch arrays (`new_sequence`), filled oldest first.
"""

import math

import numpy as np

from frictiondisk.kernel.jit import kernel_jit, kernel_jit_allocating
from frictiondisk.kernel.records import REV_RING

SEQ_MAX = 512  # capacity: newest section points read (the revolution ring's length)
N_COORD = 5  # coordinates of a section point [m]


@kernel_jit_allocating
def new_sequence():
    """Scratch for a section sequence: (points, slip, stick)."""
    return np.empty((SEQ_MAX, N_COORD)), np.empty(SEQ_MAX), np.empty(SEQ_MAX)


@kernel_jit
def cycle_sequence(motion, phases, omega, seq):
    """Fill seq (oldest first) with the section of the whole-body sticking onsets: point
    (x, y, omega |r| tau) [m], slip to the next onset [m], sticking time tau [s]. The
    newest onset closes the last step. Returns the count."""
    points, slip, stick = seq
    n_phases = min(motion.n_phases, phases.shape[0], SEQ_MAX + 1)
    n = n_phases - 1
    if n < 1:
        return 0
    first = motion.n_phases - n_phases
    for j in range(n):
        a = phases[(first + j) % phases.shape[0]]
        b = phases[(first + j + 1) % phases.shape[0]]
        tau = a.t1 - a.t0
        points[j, 0] = a.x
        points[j, 1] = a.y
        points[j, 2] = omega * math.hypot(a.x, a.y) * tau
        points[j, 3] = 0.0
        points[j, 4] = 0.0
        slip[j] = b.slip - a.slip
        stick[j] = tau
    return n


@kernel_jit
def revolution_sequence(motion, revs, seq):
    """Fill seq (oldest first) with the section of the whole master revolutions of the
    current regime (the trailing revolutions that all did, or all did not, stick as a whole
    at some instant: a slave that slid for ten revolutions and then began to stick has
    changed its motion, and the sliding revolutions say nothing about the cycle now): the
    state at each revolution's end [m], its slip [m] and whole-body sticking time [s].
    Returns the count."""
    points, slip, stick = seq
    n = min(motion.n_rev, REV_RING, SEQ_MAX)
    newest = revs[(motion.n_rev - 1) % REV_RING].ever_all
    for back in range(n):
        if revs[(motion.n_rev - 1 - back) % REV_RING].ever_all != newest:
            n = back
            break
    first = motion.n_rev - n
    for j in range(n):
        r = revs[(first + j) % REV_RING]
        points[j, 0] = r.x
        points[j, 1] = r.y
        points[j, 2] = r.u
        points[j, 3] = r.v
        points[j, 4] = r.w
        slip[j] = r.slip
        stick[j] = r.stick_t
    return n


@kernel_jit
def slip_tolerance(vs, period, hold):
    """The slip over a section step of `period` [s] that counts as none [m]: the per
    revolution tolerance eps T (vs.slip_tol) scaled to the step."""
    return vs.slip_tol * max(period, 1e-300) / hold


@kernel_jit
def newest_period(motion, phases, revs, cycles):
    """Duration [s] of the newest step of the cycle (cycles) or revolution section."""
    if cycles:
        k = motion.n_phases - 1
        a = (k - 1) % phases.shape[0]
        b = k % phases.shape[0]
        return phases[b].t0 - phases[a].t0
    k = (motion.n_rev - 1) % REV_RING
    j = (motion.n_rev - 2) % REV_RING
    return revs[k].t - revs[j].t
