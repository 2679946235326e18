"""The step-size controller of the step loop (numba): the controller's memory lives in
the STEPPER record (kernel/records.py: h, err, err_old, h_old, first).

Adaptive RODAS4 and RODAS5: Gustafsson's predictive controller on the scaled error of the
embedded estimate (Hairer & Wanner IV.8), with the stepper's exponent (kernel/steppers.py),
factors clipped to [FAC_MIN, FAC_MAX] (kernel/coefficients.py). rodas4-fixed: steps of
options.dt, no error control.
"""

import math

from . import coefficients as co
from .jit import kernel_jit
from .rosenbrock import error_norm
from .steppers import error_exponent

FIRST_STEP = 1e-4  # [s] the adaptive controller's first step (at most h_max)
ERR_FLOOR = 1e-10  # a scaled error below this counts as this (no division by ~0)
ERR_OLD_FLOOR = 1e-2  # the remembered error is at least this (no wild predictions)

ACCEPT = 0
REJECT = 1
FAIL = 2  # a fixed step that produced a singular stage matrix or a non-finite value


@kernel_jit
def start(stepper, options):
    """The controller's state at the start of a run."""
    stepper.h = options.dt if options.fixed_step else min(options.h_max, FIRST_STEP)
    stepper.err = 1.0
    stepper.err_old = 0.0
    stepper.h_old = stepper.h
    stepper.first = True


@kernel_jit
def judge(stepper, options, ok, y0, y1, error_estimate, counters):
    """ACCEPT, REJECT (the step shrunk for a retry) or FAIL for a step of stepper.h from
    y0 to y1 (ok: the stepper's own success flag)."""
    if options.fixed_step:
        return ACCEPT if ok else FAIL
    stepper.err = error_norm(y0, y1, error_estimate, options.rtol, options.atol) if ok else math.inf
    if not (stepper.err <= 1.0):
        counters.rejected += 1
        stepper.h *= reject_factor(stepper.err, error_exponent(options))
        return REJECT
    return ACCEPT


@kernel_jit
def accepted(stepper, options, h_free):
    """The next step after a whole accepted step of stepper.h; h_free: the controller's own
    step before it was cut short to land on a target (a cut step does not shrink the
    next)."""
    if options.fixed_step:
        stepper.h = options.dt
    elif stepper.h < 0.5 * h_free:
        stepper.h = h_free
    else:
        err_safe = max(stepper.err, ERR_FLOOR)
        fac = next_step_factor(
            err_safe, stepper.err_old, stepper.h, stepper.h_old, stepper.first,
            error_exponent(options),
        )  # fmt: skip
        stepper.h_old = stepper.h
        stepper.err_old = max(err_safe, ERR_OLD_FLOOR)
        stepper.first = False
        stepper.h *= fac


@kernel_jit
def switched(stepper, options):
    """After a mode switch: the dynamics changed, so no step-size prediction across it."""
    stepper.first = True
    if options.fixed_step:
        stepper.h = options.dt


@kernel_jit
def next_step_factor(err, err_old, h, h_old, first, exponent):
    """Step-size factor h_new / h after an accepted step (Gustafsson predictive controller;
    exponent: 1 / (embedded order + 1))."""
    fac = max(co.FAC_MIN, min(co.FAC_MAX, err**exponent / co.SAFETY))
    if not first and err_old > 0.0:
        facpred = (h_old / h) * (err * err / err_old) ** exponent / co.SAFETY
        facpred = max(co.FAC_MIN, min(co.FAC_MAX, facpred))
        fac = max(fac, facpred)
    return 1.0 / fac


@kernel_jit
def reject_factor(err, exponent):
    """Step-size factor after a rejected step (at most a 5x shrink, also for a non-finite
    error estimate)."""
    if not math.isfinite(err):
        return 1.0 / co.FAC_MAX
    return 1.0 / max(co.FAC_MIN, min(co.FAC_MAX, err**exponent / co.SAFETY))
