"""The step loop's choice of Rosenbrock stepper (numba): options.stepper names RODAS4
(kernel/rodas.py, numerics.method rodas4 and rodas4-fixed) or RODAS5 (kernel/rodas5.py,
numerics.method rodas5). Each call here passes through to the chosen one."""

from . import coefficients as co4
from . import coefficients_rodas5 as co5
from .jit import kernel_jit
from .rodas import W_K6, W_K8, rodas_step
from .rodas5 import rodas5_step

RODAS4 = 0
RODAS5 = 1


@kernel_jit
def step(options, p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1):
    """One step of the chosen stepper (rodas_step's arguments and result)."""
    if options.stepper == RODAS5:
        return rodas5_step(p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1)
    return rodas_step(p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1)


@kernel_jit
def error_row(options):
    """The row of the work array that holds the last step's error estimate."""
    return W_K8 if options.stepper == RODAS5 else W_K6


@kernel_jit
def error_exponent(options):
    """1 / (embedded order + 1): the step-size controller's exponent."""
    return co5.ERROR_EXPONENT if options.stepper == RODAS5 else co4.ERROR_EXPONENT
