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
F_SLIP_TOL = 18  # slip per revolution that counts as none: atol + eps T [m]
F_S_INF = 19  # extrapolated limit of the slip per revolution [m]
N_MF = 20

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
N_MI = 16

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
N_RV = 10
REV_RING = 64

# corotation_verdict
VERDICT_NONE = 0
VERDICT_STICK = 1
VERDICT_CREEP = 2

# rows of each sticking-interval ring (ring_all, ring_any)
RING = 16384
