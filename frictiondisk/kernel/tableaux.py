"""The Rosenbrock methods of the kernel as tableaux for kernel/rosenbrock.py.

RODAS4 (kernel/coefficients.py) and RODAS5 (kernel/coefficients_rodas5.py) in the
transformed form of rosenbrock.py. A tableau is a named tuple that numba freezes as a
constant: gamma, the rows a (explicit stages only) and c of the stages, the dense-output
rows d, and their sizes.
"""

from typing import NamedTuple

import numpy as np

from . import coefficients as co4
from . import coefficients_rodas5 as co5
from .rosenbrock import MAX_STAGES


class Tableau(NamedTuple):
    """One stiffly accurate Rosenbrock method (kernel/rosenbrock.py's form)."""

    gamma: float
    a: np.ndarray  # (stages, stages): a[i, j] of the explicit stages i < explicit_stages
    c: np.ndarray  # (stages, stages): c[i, j], j < i
    dense: np.ndarray  # (3, stages): the dense-output rows q_m = sum_j dense[m, j] k_j
    stages: int
    explicit_stages: int  # stages evaluated at y0 + sum_j a_ij k_j; the rest are stiffly accurate
    dense_rows: int  # rows of `dense` in use (the rest of q is 0)
    dense_stages: int  # stages the dense output reads
    error_exponent: float  # 1 / (embedded order + 1): the step-size controller's exponent


def _table(module, prefix: str, rows: range, columns: int) -> np.ndarray:
    """The coefficients `module.<prefix><i><j>` (1-based, as in the literature) as an
    array of MAX_STAGES columns; absent ones are 0."""
    table = np.zeros((MAX_STAGES, MAX_STAGES))
    for i in rows:
        for j in range(1, columns + 1):
            table[i - 1, j - 1] = getattr(module, f"{prefix}{i}{j}", 0.0)
    return table


def _tableau(module, stages, explicit, dense_prefix, dense_rows, dense_stages) -> Tableau:
    dense = _table(module, dense_prefix, range(2, 2 + dense_rows), dense_stages)[1 : 1 + 3]
    return Tableau(
        gamma=module.GAMMA,
        a=_table(module, "A", range(2, explicit + 1), explicit),
        c=_table(module, "C", range(2, stages + 1), stages),
        dense=np.ascontiguousarray(dense),
        stages=stages,
        explicit_stages=explicit,
        dense_rows=dense_rows,
        dense_stages=dense_stages,
        error_exponent=module.ERROR_EXPONENT,
    )


# RODAS4: 6 stages, 5 explicit, cubic dense output from k1 .. k5
RODAS4 = _tableau(co4, stages=6, explicit=5, dense_prefix="D", dense_rows=2, dense_stages=5)
# RODAS5: 8 stages, 6 explicit, quartic dense output from k1 .. k8
RODAS5 = _tableau(co5, stages=8, explicit=6, dense_prefix="H", dense_rows=3, dense_stages=8)
