"""The named records of one run: numpy structured dtypes that numba reads as records.

Every number a run keeps has a name: the kernel reads `options.rtol`, `counters.steps`,
`motion.t_all`, `revs[k].slip`. A scalar record is one element of a length-1 array
(`one(OPTIONS)`): numba reads and writes its fields by name as fast as array slots, and
the caller sees every write. Ring buffers are arrays of records (REVOLUTION, PHASE,
INTERVAL rows). The parameter record of the equations is model.PARAMETERS, the energy
record energy.ENERGY. Units: SI (s, m, rad).

REV_RING, RING and OWN_RING are capacities (how many rows a ring keeps), not thresholds.
"""

from __future__ import annotations

import numpy as np

# Revolutions kept: enough for log-spaced extrapolation over the horizon budget
# (8 x 30 s at the fastest master of the studies, T = 2.5 s, is 96 revolutions).
REV_RING = 512
# Sticking phases (and intervals with some contact stuck) kept
RING = 16384
# Steps of the motion's own section kept (kernel/own_section.py): at least 4 envelopes of a
# modulated cycle at 20-100 whirls an envelope
OWN_RING = 512

# The integrator's options for one run (filled from numerics by simulation/pack.py)
OPTIONS = np.dtype(
    [
        ("fixed_step", np.bool_),  # rodas4-fixed: steps of dt, no error control
        ("stepper", np.int8),  # kernel/steppers.py RODAS4 or RODAS5
        ("dense_lu", np.bool_),  # factor the stage matrix densely (O(N^3)) instead of as an arrow
        ("record", np.bool_),  # keep the trajectory (kernel/recording.py)
        ("rtol", np.float64),  # relative tolerance
        ("atol", np.float64),  # absolute tolerance [each state's SI unit]
        ("dt", np.float64),  # step of rodas4-fixed [s]
        ("h_max", np.float64),  # largest step [s]
        ("dt_out", np.float64),  # recording interval [s]; 0: every step
        ("max_steps", np.int64),  # step budget
        ("max_events", np.int64),  # mode-switch budget
    ]
)

# What the step loop counts
COUNTERS = np.dtype(
    [
        ("steps", np.int64),  # accepted steps
        ("rejected", np.int64),  # rejected steps
        ("events", np.int64),  # contact mode switches
        ("refused", np.int64),  # refused stick entries (docs/model.md section 3)
        ("recorded", np.int64),  # rows of the trajectory buffers written
        ("truncated", np.bool_),  # the trajectory buffers ran out of rows
    ]
)

# The step loop's own state between steps (the step-size controller's memory included)
STEPPER = np.dtype(
    [
        ("t", np.float64),  # time [s]
        ("h", np.float64),  # the next step [s]
        ("err", np.float64),  # scaled error of the last step
        ("err_old", np.float64),  # ... of the one before (Gustafsson's predictive controller)
        ("h_old", np.float64),  # the step before [s]
        ("first", np.bool_),  # no step-size prediction (after the start or a switch)
        ("t_rev", np.float64),  # end of the current master revolution [s]
        ("t_last_event", np.float64),  # time of the last switch [s]
        ("same_time", np.int64),  # switches in a row at one instant (Zeno guard)
    ]
)

# What the motion did (kernel/monitor.py): sticking phases, section points, revolutions.
# Facts only: the verdict (frictiondisk/verdict/) judges them.
MOTION = np.dtype(
    [
        ("nq", np.int64),  # generalized coordinates: 2 (pin) or 3 (disk)
        ("arm", np.float64),  # longest contact arm max |p_i| [m] (0 for the pin)
        ("all_stuck", np.bool_),  # every contact sticks
        ("some_stuck", np.bool_),  # some contact sticks
        ("opened", np.bool_),  # a whole-body sticking phase opened at the last update
        ("switches", np.int64),  # contact mode switches
        ("t_all", np.float64),  # onset of the current whole-body sticking phase [s] (NaN: none)
        ("t_any", np.float64),  # onset of the current "some contact sticks" phase [s] (NaN)
        ("x_all", np.float64),  # slave centre x at that onset [m]
        ("y_all", np.float64),  # ... and y [m]
        ("slip_all", np.float64),  # slip integral at that onset [m]
        ("steps_all", np.float64),  # integrator steps before that onset
        ("n_phases", np.int64),  # whole-body sticking phases closed (rows pushed to phases)
        ("n_intervals", np.int64),  # "some contact sticks" intervals closed
        ("r1", np.float64),  # first sticking radius [m]
        ("t_r1", np.float64),  # time of first sticking [s]
        ("n_sect", np.int64),  # slide->stick section points seen (whole-body onsets)
        ("r_sect", np.float64),  # radius at the last section point [m]
        ("ang_sect", np.float64),  # angle at the last section point [rad]
        ("sect_dr", np.float64),  # signed radius change between the last two section points [m]
        ("sect_dr1", np.float64),  # the one before [m]
        ("sect_dr2", np.float64),  # the one before that [m]
        ("sect_arc", np.float64),  # arc between the last two section points |d angle| r [m]
        ("rmax", np.float64),  # largest |r| in the current sliding phase [m]
        ("a", np.float64),  # excess of the last completed sliding phase over its onset [m]
        ("size", np.float64),  # radius of the last sticking segment [m]
        ("n_rev", np.int64),  # revolutions completed
        ("rev_t0", np.float64),  # start of the current revolution [s]
        ("rev_slip0", np.float64),  # slip integral at its start [m]
        ("rev_steps0", np.int64),  # integrator steps before it
        ("rev_switches0", np.int64),  # mode switches before it
        ("rev_not_all", np.bool_),  # not every contact stuck at some instant of it
        ("rev_none", np.bool_),  # no contact stuck at some instant of it
        ("rev_ever_all", np.bool_),  # every contact stuck at some instant of it
    ]
)

# One completed master revolution (row of the revolution ring; newest at (n_rev - 1) % REV_RING)
REVOLUTION = np.dtype(
    [
        ("t", np.float64),  # end of the revolution [s]
        ("slip", np.float64),  # net plastic slip of the mean contact, sum_i w_i int |w_i'| dt [m]
        ("drift_r", np.float64),  # |r(t) - r(t - T)|: drift of the centre in the master frame [m]
        ("drift_phi", np.float64),  # phi(t) - phi(t - T) - omega_m T: drift of the spin [rad]
        ("switches", np.int64),  # contact mode switches during the revolution
        ("all_stuck", np.bool_),  # every contact stuck throughout
        ("any_stuck", np.bool_),  # some contact stuck at every instant (the small orbit)
        ("ever_all", np.bool_),  # every contact stuck at some instant
        ("still", np.bool_),  # centre and spin repeated within the integrator's tolerance
        ("stick_t", np.float64),  # time with every contact stuck [s]
        # the state at the revolution's end, all in metres (its section point):
        ("x", np.float64),  # slave centre x [m]
        ("y", np.float64),  # slave centre y [m]
        ("u", np.float64),  # x velocity / omega_m [m]
        ("v", np.float64),  # y velocity / omega_m [m]
        ("w", np.float64),  # spin rate x longest arm / omega_m [m] (0 for the pin)
        # mu - shakedown demand / F_n at the revolution's end [1] (braked disks under the
        # shakedown bound only, frictiondisk/verdict/shakedown_bound.py; else NaN)
        ("reserve", np.float64),
    ]
)

# One closed whole-body sticking phase (row of the phase ring): its interval and section
# point (the slave centre at its onset), the slip integral and the steps at its onset
PHASE = np.dtype(
    [
        ("t0", np.float64),  # onset [s]
        ("t1", np.float64),  # end [s]
        ("x", np.float64),  # slave centre x at the onset [m]
        ("y", np.float64),  # slave centre y at the onset [m]
        ("slip", np.float64),  # slip integral at the onset [m] (NaN without the slip measure)
        ("steps", np.float64),  # integrator steps before the onset
    ]
)

# One closed interval with some contact stuck (row of the interval ring)
INTERVAL = np.dtype([("t0", np.float64), ("t1", np.float64)])


# The motion's own section (kernel/own_section.py): where the unwrapped velocity phase
# psi = atan2(ydot, xdot) has turned a whole turn since the last row, and what the motion did
# over that step. Its state between rows:
OWN = np.dtype(
    [
        ("n", np.int64),  # rows closed (newest at (n - 1) % OWN_RING)
        ("start", np.int64),  # first row of the current sliding regime (rows since a lock)
        ("psi", np.float64),  # unwrapped velocity phase at the last instant [rad] (NaN: at rest)
        ("level", np.float64),  # unwrapped phase of the last row, a multiple of 2 pi [rad] (NaN)
        ("t0", np.float64),  # start of the open step [s]
        ("slip0", np.float64),  # slip integral at its start [m]
        ("phi0", np.float64),  # spin angle at its start [rad] (0 for the pin)
        ("switches0", np.int64),  # contact mode switches before it
        ("r_int", np.float64),  # integral of |r| dt over it so far [m s]
        ("r_min", np.float64),  # smallest |r| in it so far [m]
        ("r_max", np.float64),  # largest |r| in it so far [m]
        ("v_max", np.float64),  # largest |rdot| in it so far [m/s]
        ("x_min", np.float64),  # least x in it so far [m]
        ("x_max", np.float64),  # largest x [m]
        ("y_min", np.float64),  # least y [m]
        ("y_max", np.float64),  # largest y [m]
        ("locked", np.bool_),  # every contact stuck at some instant of it
        ("longest", np.float64),  # the longest row closed so far [s] (0: none yet)
    ]
)

# One step of the own section (row of the own ring; newest at (n - 1) % OWN_RING)
OWN_STEP = np.dtype(
    [
        ("t", np.float64),  # end of the step: psi reached the next multiple of 2 pi [s]
        ("dt", np.float64),  # its duration, the motion's own period [s]
        ("x", np.float64),  # slave centre x at its end [m]
        ("y", np.float64),  # ... y [m]
        ("xd", np.float64),  # velocity x [m/s] (ydot = 0 there, xdot > 0)
        ("yd", np.float64),  # velocity y [m/s]
        ("phid", np.float64),  # spin rate [rad/s] (0 for the pin)
        ("r_mean", np.float64),  # time mean of |r| over the step [m]
        ("r_min", np.float64),  # smallest |r| over it [m]
        ("r_max", np.float64),  # largest |r| over it [m]
        ("v_max", np.float64),  # largest |rdot| over it [m/s]
        ("x_min", np.float64),  # least x of the centre over it [m]
        ("x_max", np.float64),  # largest x [m]
        ("y_min", np.float64),  # least y [m]
        ("y_max", np.float64),  # largest y [m]
        ("spin", np.float64),  # integral of phidot dt over it [rad] (0 for the pin)
        ("slip", np.float64),  # net plastic slip of the mean contact over it [m]
        ("stick_all_t", np.float64),  # time with every contact stuck [s]
        ("stick_any_t", np.float64),  # time with some contact stuck [s]
        ("switches", np.int64),  # contact mode switches in it
        ("turn", np.int64),  # +1: psi turned forwards a whole turn, -1: backwards, 0: it
        # did not turn within REST_SPAN times the longest row before (closed by time)
        ("locked", np.bool_),  # every contact stuck at some instant: not a sliding step
    ]
)


def one(dtype: np.dtype):
    """A zeroed record of `dtype` (a view into a length-1 array: writes reach the array)."""
    return np.zeros(1, dtype=dtype)[0]


def filled(dtype: np.dtype, **values):
    """A record of `dtype` with every field given by name (a view into a length-1 array,
    as `one`'s), made in one call instead of one write per field. KeyError names a field
    not given, TypeError one that `dtype` lacks."""
    extra = values.keys() - set(dtype.names)
    if extra:
        raise TypeError(f"no such fields in the record: {', '.join(sorted(extra))}")
    return np.array([tuple(values[name] for name in dtype.names)], dtype=dtype)[0]
