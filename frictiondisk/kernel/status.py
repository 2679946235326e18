"""Status codes returned by the kernel, and what they mean (messages live in simulate.py)."""

STICK_HELD = 1  # every contact stuck for the hold time: outcome `stick`
HORIZON_REACHED = 2  # decision horizon reached: classify by the final window
CYCLE_CONVERGED = 3  # limit cycle converged (section-point test)
TMAX_REACHED = 4  # convergence mode reached t_max without convergence
COROTATING = 5  # co-rotation without net slip (stick_rule corotation): outcome `stick`
CREEPING = 6  # steady slip per revolution on the small orbit: outcome `creep`
SHAKEN_DOWN = 7  # slip per cycle or revolution falls to nothing (kernel/sections.py): `stick`
BOUND_DECIDED = 8  # Melan or Koiter decides on the small orbit (kernel/shakedown_bound.py)
MAX_STEPS = 10  # work budget: step limit
MAX_EVENTS = 11  # work budget: event limit
STEP_TOO_SMALL = 12  # step size underflow
NONFINITE = 13  # a state or rate became NaN or infinite
ZENO = 14  # too many switches at one instant
