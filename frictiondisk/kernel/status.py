"""Status codes of the step loop's own failures (numba returns them; the label words them).

A run the verdict ends returns the verdict's final state instead (1 ... 8,
frictiondisk/verdict/records.py); these codes start at 10 so the two never meet.
"""

RUNNING = 0  # the loop goes on (a step was taken or rejected); never returned
MAX_STEPS = 10  # work budget: step limit
MAX_EVENTS = 11  # work budget: event limit
STEP_TOO_SMALL = 12  # step size underflow
NONFINITE = 13  # a state or rate became NaN or infinite
ZENO = 14  # too many switches at one instant
