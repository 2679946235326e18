"""The step loop's choice of Rosenbrock method (numba): options.stepper names RODAS4
(numerics.method rodas4 and rodas4-fixed) or RODAS5 (numerics.method rodas5), two tableaux
(kernel/tableaux.py) of the one stepper (kernel/rosenbrock.py)."""

from .jit import kernel_jit
from .rosenbrock import W_K1, make_rosenbrock_step
from .tableaux import RODAS4 as RODAS4_TABLEAU
from .tableaux import RODAS5 as RODAS5_TABLEAU

RODAS4 = 0
RODAS5 = 1

rodas4_step = make_rosenbrock_step(RODAS4_TABLEAU)
rodas5_step = make_rosenbrock_step(RODAS5_TABLEAU)


@kernel_jit
def step(options, p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1):
    """One step of the chosen method (rosenbrock_step's arguments and result)."""
    if options.stepper == RODAS5:
        return rodas5_step(p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1)
    return rodas4_step(p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1)


@kernel_jit
def error_row(options):
    """The row of the work array that holds the last step's error estimate (the last
    stage of a stiffly accurate method)."""
    if options.stepper == RODAS5:
        return W_K1 + RODAS5_TABLEAU.stages - 1
    return W_K1 + RODAS4_TABLEAU.stages - 1


@kernel_jit
def error_exponent(options):
    """1 / (embedded order + 1): the step-size controller's exponent."""
    if options.stepper == RODAS5:
        return RODAS5_TABLEAU.error_exponent
    return RODAS4_TABLEAU.error_exponent
