"""Slot layout of the monitor's state (kernel/monitor.py): the indices into its float
array mf (F_*) and int array mi (I_*), the columns of the revolution ring rv (RV_*), the
array and ring sizes (N_*, REV_RING, RING) and the codes of corotation_verdict
(VERDICT_*). Plain integers, read by the numba functions as compile-time constants.
"""

# mf indices
F_T_ALL = 0  # start of the current whole-body sticking phase [s] (NaN if not all stick)
F_T_ANY = 1  # start of the current "some contact sticks" phase [s] (NaN if none)
F_R1 = 2  # first sticking radius [m]
F_T_R1 = 3  # time of first sticking [s]
F_R_SECT = 4  # radius at the last slide->stick section point [m]
F_ANG_SECT = 5  # angle at the last section point [rad]
F_RMAX = 6  # largest |r| in the current sliding phase [m]
F_A = 7  # excess a of the last completed sliding phase [m]
F_SIZE = 8  # radius of the last sticking segment [m]
F_DR1 = 9  # signed radius change between the last two section points [m]
F_DR2 = 10  # the one before [m]
F_CYCLE_TOL = 11
F_T_REV = 12  # start of the current revolution [s]
F_SLIP_REV = 13  # slip integral at the start of the current revolution [m]
F_LAMBDA = 14  # mean log decay of the slip per revolution over the verdict window [1/rev]
F_LAMBDA_SE = 15  # its standard error [1/rev]
F_REMAIN = 16  # predicted slip still to come under geometric decay [m]
F_ARM = 17  # longest contact arm max |p_i| [m] (0 for the pin)
F_SLIP_TOL = 18  # slip per revolution that counts as none: eps T [m]
F_S_INF = 19  # extrapolated limit of the slip per revolution [m]
F_X_ALL = 20  # slave centre x at the onset of the current whole-body sticking phase [m]
F_Y_ALL = 21  # ... and y [m]
F_SLIP_ALL = 22  # slip integral at that onset [m]
F_STEPS_ALL = 23  # integrator steps before that onset
F_RTOL = 24  # the integrator's rtol and atol [m], for the section tolerances
F_ATOL = 25
F_EV_D = 26  # newest section distance behind the evidence [m]
F_EV_Q = 27  # its contraction ratio per step (distance / the one before)
F_EV_QUP = 28  # the extrapolated bound on that ratio (EV_CONTRACT)
F_EV_LIMIT = (
    29  # extrapolated limit of the slip per step [m] (EV_SHAKEDOWN) or remaining travel [m]
)
F_S_INF_SPREAD = 30  # range of the same estimate made 0 ... m revolutions back [m]
N_MF = 31

# mi indices
I_ALL = 0  # 1 while every contact sticks
I_ANY = 1  # 1 while some contact sticks
I_NTRANS = 2  # contact mode switches
I_NSECT = 3  # section points seen
I_NAGREE = 4  # consecutive agreeing section points
I_RS_N = 5  # intervals pushed to the all-stick ring
I_RA_N = 6  # intervals pushed to the any-stick ring
I_CYCLE_COUNT = 7
I_NQ = 8
I_NREV = 9  # revolutions completed
I_REV_NOT_ALL = 10  # 1 once not every contact stuck during the current revolution
I_REV_NONE = 11  # 1 once no contact stuck during the current revolution
I_REV_NTRANS = 12  # mode switches before the current revolution
I_REV_EVER_ALL = 13  # 1 once every contact stuck at some instant of the current revolution
I_VERDICT = 14  # the last corotation_verdict (VERDICT_*)
I_REV_STEPS = 15  # integrator steps before the current revolution
I_EVIDENCE = 16  # the section evidence of the last check (kernel/sections.py EV_*)
I_EV_SOURCE = 17  # which section gave it: SOURCE_CYCLES or SOURCE_REVOLUTIONS
I_EV_LAG = 18  # sticking phases (or revolutions) per period of the cycle behind EV_REPEAT
I_EV_STEPS = 19  # section points behind the evidence
I_OBSERVE = 20  # 1: verdicts only on what the run shows, no extrapolation (numerics.evidence)
I_STRIBECK = 21  # 1: the friction law falls with the slip speed (Stribeck ratio r < 1)
I_BOUND = 22  # 1: the shakedown bound applies (kernel/shakedown_bound.py)
N_MI = 23

# Columns of the revolution ring rv (one row per completed revolution, newest at
# (I_NREV - 1) % REV_RING)
RV_T = 0  # end of the revolution [s]
RV_SLIP = 1  # net plastic slip of the mean contact, sum_i w_i int |w_i'| dt [m]
RV_DRIFT_R = 2  # |r(t) - r(t - T)|: drift of the slave centre in the master frame [m]
RV_DRIFT_PHI = 3  # phi(t) - phi(t - T) - omega_m T: drift of the spin phase [rad]
RV_SWITCHES = 4  # contact mode switches during the revolution
RV_ALL_STUCK = 5  # 1 if every contact stuck throughout the revolution
RV_ANY_STUCK = 6  # 1 if some contact stuck at every instant of the revolution
RV_EVER_ALL = 7  # 1 if every contact stuck at some instant of the revolution
RV_STILL = 8  # 1 if centre and spin phase repeated within the integrator's tolerance
RV_STICK_T = 9  # time with every contact stuck during the revolution [s]
# the state at the end of the revolution, all in metres (the revolution's section point):
RV_X = 10  # slave centre x [m]
RV_Y = 11  # slave centre y [m]
RV_U = 12  # x velocity / omega_m [m]
RV_V = 13  # y velocity / omega_m [m]
RV_W = 14  # spin rate x longest arm / omega_m [m] (0 for the pin)
# mu - shakedown demand / F_n at the end of the revolution [1] (kernel/shakedown_bound.py;
# braked disks with stick_rule corotation only, else NaN)
RV_RESERVE = 15
N_RV = 16
# Revolutions kept: enough for log-spaced extrapolation over the horizon budget
# (8 x 30 s at the fastest master of the studies, T = 2.5 s, is 96 revolutions).
REV_RING = 512

# corotation_verdict
VERDICT_NONE = 0
VERDICT_STICK = 1
VERDICT_CREEP = 2
VERDICT_SHAKEN = 3  # stick by the shakedown of the section's slip (kernel/sections.py)

# rows of each sticking-interval ring (ring_all, ring_any)
RING = 16384
# Columns of the sticking-interval rings: ring_any holds (start, end) of every phase with
# some contact stuck; ring_all holds, per whole-body sticking phase, also its section point
# (the slave centre at its onset) and the slip integral and step count at its onset.
RA_T0 = 0  # onset [s]
RA_T1 = 1  # end [s]
RA_X = 2  # slave centre x at the onset [m]
RA_Y = 3  # slave centre y at the onset [m]
RA_SLIP = 4  # slip integral at the onset [m] (NaN without the slip measure)
RA_STEPS = 5  # integrator steps before the onset
N_RA = 6

# Section evidence (kernel/sections.py): what the motion's own section shows
EV_NONE = 0  # nothing yet: the run must go on (or end undetermined)
EV_REPEAT = 1  # the section repeats within tolerance: a cycle reached (not stick)
EV_CONTRACT = 2  # the section contracts geometrically to a cycle with slip (not stick)
EV_DEPART = 3  # slip grows and sticking time shrinks step after step (not stick)
EV_SHAKEDOWN = 4  # slip per step falls to an extrapolated limit <= tolerance (stick)
EV_CANNOT = 5  # no co-rotating state can be held: mu F_n below the spring's or brake's pull
EV_SLIDING = 6  # slides as a whole, its slip per revolution not falling revolution by revolution
SOURCE_CYCLES = 1  # the onsets of whole-body sticking phases
SOURCE_REVOLUTIONS = 2  # the state at every whole master revolution
