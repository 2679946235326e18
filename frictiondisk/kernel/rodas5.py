"""One RODAS5 step with embedded error estimate and dense output (numba).

The 5th-order stepper beside RODAS4 (kernel/rodas.py), for runs that check another run:
certification re-runs a bracket's ends at stricter tolerances, where a higher order needs
fewer steps (docs/wellposed.md). It shares RODAS4's work array (the rows W_* of
kernel/rodas.py, with W_K7 and W_K8 for its last stages) and writes its order-4 dense
output into the same rows W_Q1 .. W_Q3, so every reader of dense output (events, energy,
sections, recording: rodas.dense_eval) serves both.
"""

import math

from . import coefficients_rodas5 as co
from .jit import kernel_jit
from .linalg import stage_solve
from .model import rhs
from .rodas import (
    W_B,
    W_F,
    W_K1,
    W_K2,
    W_K3,
    W_K4,
    W_K5,
    W_K6,
    W_K7,
    W_K8,
    W_Q1,
    W_Q2,
    W_Q3,
    W_Y,
    factor_stage_matrix,
)


@kernel_jit
def rodas5_step(p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1):
    """Advance from y0 (with f0 = rhs(y0)) by h. Writes y1 and the dense output rows; the
    error estimate is left in wk[W_K8] (order-5 minus order-4 solution). Returns False if
    the iteration matrix is singular or a value is not finite."""
    n = y0.shape[0]
    if not factor_stage_matrix(p, pts, modes, y0, co.GAMMA * h, jac, lu, piv, wk):
        return False
    ytmp = wk[W_Y]
    ftmp = wk[W_F]
    b = wk[W_B]
    k1 = wk[W_K1]
    k2 = wk[W_K2]
    k3 = wk[W_K3]
    k4 = wk[W_K4]
    k5 = wk[W_K5]
    k6 = wk[W_K6]
    k7 = wk[W_K7]
    k8 = wk[W_K8]
    stage_solve(lu, piv, f0, k1)

    for i in range(n):
        ytmp[i] = y0[i] + co.A21 * k1[i]
    rhs(p, pts, modes, ytmp, ftmp)
    for i in range(n):
        b[i] = ftmp[i] + co.C21 * k1[i] / h
    stage_solve(lu, piv, b, k2)

    for i in range(n):
        ytmp[i] = y0[i] + co.A31 * k1[i] + co.A32 * k2[i]
    rhs(p, pts, modes, ytmp, ftmp)
    for i in range(n):
        b[i] = ftmp[i] + (co.C31 * k1[i] + co.C32 * k2[i]) / h
    stage_solve(lu, piv, b, k3)

    for i in range(n):
        ytmp[i] = y0[i] + co.A41 * k1[i] + co.A42 * k2[i] + co.A43 * k3[i]
    rhs(p, pts, modes, ytmp, ftmp)
    for i in range(n):
        b[i] = ftmp[i] + (co.C41 * k1[i] + co.C42 * k2[i] + co.C43 * k3[i]) / h
    stage_solve(lu, piv, b, k4)

    for i in range(n):
        ytmp[i] = y0[i] + co.A51 * k1[i] + co.A52 * k2[i] + co.A53 * k3[i] + co.A54 * k4[i]
    rhs(p, pts, modes, ytmp, ftmp)
    for i in range(n):
        b[i] = ftmp[i] + (co.C51 * k1[i] + co.C52 * k2[i] + co.C53 * k3[i] + co.C54 * k4[i]) / h
    stage_solve(lu, piv, b, k5)

    for i in range(n):
        ytmp[i] = (
            y0[i]
            + co.A61 * k1[i] + co.A62 * k2[i] + co.A63 * k3[i] + co.A64 * k4[i] + co.A65 * k5[i]
        )  # fmt: skip
    rhs(p, pts, modes, ytmp, ftmp)
    for i in range(n):
        b[i] = (
            ftmp[i]
            + (co.C61 * k1[i] + co.C62 * k2[i] + co.C63 * k3[i] + co.C64 * k4[i] + co.C65 * k5[i])
            / h
        )
    stage_solve(lu, piv, b, k6)

    for i in range(n):
        ytmp[i] += k6[i]
    rhs(p, pts, modes, ytmp, ftmp)
    for i in range(n):
        b[i] = ftmp[i] + (
            co.C71 * k1[i] + co.C72 * k2[i] + co.C73 * k3[i] + co.C74 * k4[i]
            + co.C75 * k5[i] + co.C76 * k6[i]
        ) / h  # fmt: skip
    stage_solve(lu, piv, b, k7)

    for i in range(n):
        ytmp[i] += k7[i]
    rhs(p, pts, modes, ytmp, ftmp)
    for i in range(n):
        b[i] = ftmp[i] + (
            co.C81 * k1[i] + co.C82 * k2[i] + co.C83 * k3[i] + co.C84 * k4[i]
            + co.C85 * k5[i] + co.C86 * k6[i] + co.C87 * k7[i]
        ) / h  # fmt: skip
    stage_solve(lu, piv, b, k8)

    for i in range(n):
        y1[i] = ytmp[i] + k8[i]
        if not math.isfinite(y1[i]):
            return False
    dense_rows(wk, n)
    return True


@kernel_jit
def dense_rows(wk, n):
    """The dense-output rows W_Q1 .. W_Q3 of the last step from its stages k1 .. k8."""
    q1 = wk[W_Q1]
    q2 = wk[W_Q2]
    q3 = wk[W_Q3]
    for i in range(n):
        q1[i] = stage_sum(wk, i, co.H21, co.H22, co.H23, co.H24, co.H25, co.H26, co.H27, co.H28)
        q2[i] = stage_sum(wk, i, co.H31, co.H32, co.H33, co.H34, co.H35, co.H36, co.H37, co.H38)
        q3[i] = stage_sum(wk, i, co.H41, co.H42, co.H43, co.H44, co.H45, co.H46, co.H47, co.H48)


@kernel_jit
def stage_sum(wk, i, c1, c2, c3, c4, c5, c6, c7, c8):
    """sum_j c_j k_j[i] over the eight stages of the last step, summed in stage order."""
    return (
        c1 * wk[W_K1, i] + c2 * wk[W_K2, i] + c3 * wk[W_K3, i] + c4 * wk[W_K4, i]
        + c5 * wk[W_K5, i] + c6 * wk[W_K6, i] + c7 * wk[W_K7, i] + c8 * wk[W_K8, i]
    )  # fmt: skip
