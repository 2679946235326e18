"""One RODAS4 step with embedded error estimate and dense output (numba).

The stepper knows nothing of contacts or events: it advances y' = rhs(y) in fixed
modes. Step-size control is kernel/controller.py; events and switching are
kernel/switching.py; the step loop (frictiondisk/simulation/loop.py) calls them.
"""

import math

from . import coefficients as co
from .jit import kernel_jit
from .linalg import is_dense, stage_factor, stage_solve
from .model import jacobian, jacobian_arrow, rhs

# Rows of the work array wk (shape (N_WORK_ROWS, n)): the stages k1 .. k6 (k6 is the
# error estimate), scratch for a stage's state, rate and right-hand side, the
# dense-output coefficients q1, q2, q3 of the last step (q3 = 0 here: RODAS4's dense output
# is cubic), and RODAS5's stages k7, k8 (kernel/rodas5.py).
W_K1, W_K2, W_K3, W_K4, W_K5, W_K6 = 0, 1, 2, 3, 4, 5
W_Y, W_F, W_B = 6, 7, 8
W_Q1, W_Q2, W_Q3 = 9, 10, 11
W_K7, W_K8 = 12, 13
N_WORK_ROWS = 14


@kernel_jit
def factor_stage_matrix(p, pts, modes, y0, gamma_h, jac, lu, piv, wk):
    """The Jacobian at y0 and the LU factors of I / gamma_h - J (a Rosenbrock method's
    stage matrix; gamma_h: its gamma times the step [s]). False if it is singular."""
    n = y0.shape[0]
    lin = wk[W_K2:W_K6]  # the stages k2 .. k5, not yet written: the Jacobian's scratch
    if is_dense(piv, n):
        jacobian(p, pts, modes, y0, jac, lin)
    else:
        jacobian_arrow(p, pts, modes, y0, jac, lin)
    return stage_factor(jac, 1.0 / gamma_h, lu, piv)


@kernel_jit
def rodas_step(p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1):
    """Advance from y0 (with f0 = rhs(y0)) by h. Writes y1 and the dense output rows.

    jac, lu, piv come from linalg.stage_workspace: dense, or the O(N) arrow form.
    Returns False if the iteration matrix is singular or a value is not finite. The error
    estimate is left in wk[W_K6] (order-4 minus order-3 solution).
    """
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
        ytmp[i] += k5[i]
    rhs(p, pts, modes, ytmp, ftmp)
    for i in range(n):
        b[i] = (
            ftmp[i]
            + (co.C61 * k1[i] + co.C62 * k2[i] + co.C63 * k3[i] + co.C64 * k4[i] + co.C65 * k5[i])
            / h
        )
    stage_solve(lu, piv, b, k6)

    q1 = wk[W_Q1]
    q2 = wk[W_Q2]
    q3 = wk[W_Q3]
    for i in range(n):
        y1[i] = ytmp[i] + k6[i]
        q1[i] = co.D21 * k1[i] + co.D22 * k2[i] + co.D23 * k3[i] + co.D24 * k4[i] + co.D25 * k5[i]
        q2[i] = co.D31 * k1[i] + co.D32 * k2[i] + co.D33 * k3[i] + co.D34 * k4[i] + co.D35 * k5[i]
        q3[i] = 0.0
        if not math.isfinite(y1[i]):
            return False
    return True


@kernel_jit
def error_norm(y0, y1, err, rtol, atol):
    """Scaled RMS norm of the error estimate (Hairer & Wanner IV.8, eq. 4.10 style)."""
    n = y0.shape[0]
    acc = 0.0
    for i in range(n):
        sk = atol + rtol * max(abs(y0[i]), abs(y1[i]))
        acc += (err[i] / sk) ** 2
    return math.sqrt(acc / n)


@kernel_jit
def dense_eval(y0, y1, wk, s, out):
    """Dense output at fraction s in [0, 1] of the last step (order 3 after a RODAS4 step,
    4 after a RODAS5 step)."""
    q1 = wk[W_Q1]
    q2 = wk[W_Q2]
    q3 = wk[W_Q3]
    s1 = 1.0 - s
    for i in range(y0.shape[0]):
        out[i] = s1 * y0[i] + s * (y1[i] + s1 * (q1[i] + s * (q2[i] + s * q3[i])))


@kernel_jit
def dense_eval_contact(y0, y1, wk, s, out, nq, i):
    """dense_eval of only what contact i's switching function reads: the rigid-body
    coordinates out[0:2nq] and Z_i (O(1) instead of O(N)); the rest of out is left as is."""
    q1 = wk[W_Q1]
    q2 = wk[W_Q2]
    q3 = wk[W_Q3]
    s1 = 1.0 - s
    zi = 2 * nq + 2 * i
    for k in range(2 * nq + 2):
        j = k if k < 2 * nq else zi + k - 2 * nq
        out[j] = s1 * y0[j] + s * (y1[j] + s1 * (q1[j] + s * (q2[j] + s * q3[j])))
