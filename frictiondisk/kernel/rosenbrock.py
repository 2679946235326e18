"""One Rosenbrock step over a tableau, with embedded error estimate and dense output (numba).

The one stepper of the kernel (diffrax's `AbstractRosenbrock` with a `RosenbrockTableau`,
scipy's `rk_step` over tableau arrays): RODAS4 and RODAS5 are tableaux
(kernel/tableaux.py), not code: `make_rosenbrock_step(tableau)` compiles the one stage loop
for a tableau. The stepper knows nothing of contacts or events: it
advances y' = rhs(y) in fixed modes. Step-size control is kernel/controller.py; events and
switching are kernel/switching.py; the step loop (frictiondisk/simulation/loop.py) calls
them.

The transformed form of an autonomous system (Hairer & Wanner, Solving ODEs II, IV.7):
    (I / (gamma h) - J) k_i = f(y0 + sum_j a_ij k_j) + sum_j c_ij k_j / h.
Both methods are stiffly accurate: the stages after the last explicit row of `a` are
evaluated at the previous stage's point plus the previous stage, y1 is the last stage's
point plus the last stage, and the last stage is the embedded error estimate. Every sum
runs in stage order, so a tableau gives the same bits as the hand-unrolled step it
replaced.
"""

import math

from .jit import kernel_jit, kernel_jit_inline
from .linalg import is_dense, stage_factor, stage_solve
from .model import jacobian, jacobian_arrow, rhs

# Rows of the work array wk (shape (N_WORK_ROWS, n)): the stages k1 .. k8 (the last stage
# of a method is its error estimate), scratch for a stage's state, rate and right-hand
# side, and the dense-output coefficients q1, q2, q3 of the last step.
W_K1 = 0
MAX_STAGES = 8
W_Y, W_F, W_B = 8, 9, 10
W_Q1, W_Q2, W_Q3 = 11, 12, 13
N_WORK_ROWS = 14


@kernel_jit
def factor_stage_matrix(p, pts, modes, y0, gamma_h, jac, lu, piv, wk):
    """The Jacobian at y0 and the LU factors of I / gamma_h - J (a Rosenbrock method's
    stage matrix; gamma_h: its gamma times the step [s]). False if it is singular."""
    n = y0.shape[0]
    lin = wk[W_K1 + 1 : W_K1 + 5]  # stages k2 .. k5, not yet written: the Jacobian's scratch
    if is_dense(piv, n):
        jacobian(p, pts, modes, y0, jac, lin)
    else:
        jacobian_arrow(p, pts, modes, y0, jac, lin)
    return stage_factor(jac, 1.0 / gamma_h, lu, piv)


def make_rosenbrock_step(tableau):
    """The step of the method `tableau` (kernel/tableaux.py), compiled with its
    coefficients and stage counts as constants (numba freezes a closure's values; its
    cache tells the methods apart by them). Each stage is one call of the stage function
    with a constant stage index, inlined, so that its sums unroll as in a hand-written step.

    The step: rosenbrock_step(p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1) advances
    from y0 (with f0 = rhs(y0)) by h, writes y1 and the dense output rows, and leaves the
    error estimate in the last stage's row. jac, lu, piv come from linalg.stage_workspace:
    dense, or the O(N) arrow form. It returns False if the stage matrix is singular or a
    value is not finite.
    """
    gamma, a, c, d = tableau.gamma, tableau.a, tableau.c, tableau.dense
    stages, explicit_stages = tableau.stages, tableau.explicit_stages
    dense_rows, dense_stages = tableau.dense_rows, tableau.dense_stages

    @kernel_jit_inline
    def stage(s, p, pts, modes, y0, h, lu, piv, wk):
        """Stage s (0 < s < stages) from the stages before it."""
        if s >= stages:
            return
        n = y0.shape[0]
        ytmp = wk[W_Y]
        ftmp = wk[W_F]
        b = wk[W_B]
        if s < explicit_stages:
            for i in range(n):
                point = y0[i]
                for j in range(s):
                    point += a[s, j] * wk[W_K1 + j, i]
                ytmp[i] = point
        else:  # stiffly accurate: the previous stage's point plus the previous stage
            for i in range(n):
                ytmp[i] += wk[W_K1 + s - 1, i]
        rhs(p, pts, modes, ytmp, ftmp)
        for i in range(n):
            coupling = c[s, 0] * wk[W_K1, i]
            for j in range(1, s):
                coupling += c[s, j] * wk[W_K1 + j, i]
            b[i] = ftmp[i] + coupling / h
        stage_solve(lu, piv, b, wk[W_K1 + s])

    @kernel_jit
    def rosenbrock_step(p, pts, modes, y0, f0, h, jac, lu, piv, wk, y1):
        n = y0.shape[0]
        if not factor_stage_matrix(p, pts, modes, y0, gamma * h, jac, lu, piv, wk):
            return False
        stage_solve(lu, piv, f0, wk[W_K1])
        # one call a stage (MAX_STAGES in all), each with its index as a constant
        stage(1, p, pts, modes, y0, h, lu, piv, wk)
        stage(2, p, pts, modes, y0, h, lu, piv, wk)
        stage(3, p, pts, modes, y0, h, lu, piv, wk)
        stage(4, p, pts, modes, y0, h, lu, piv, wk)
        stage(5, p, pts, modes, y0, h, lu, piv, wk)
        stage(6, p, pts, modes, y0, h, lu, piv, wk)
        stage(7, p, pts, modes, y0, h, lu, piv, wk)
        ytmp = wk[W_Y]
        last = wk[W_K1 + stages - 1]
        for i in range(n):
            y1[i] = ytmp[i] + last[i]
            if not math.isfinite(y1[i]):
                return False
        # the dense-output rows q_m = sum_j d_mj k_j in stage order (unused rows are 0)
        for m in range(3):
            q = wk[W_Q1 + m]
            for i in range(n):
                value = 0.0
                if m < dense_rows:
                    value = d[m, 0] * wk[W_K1, i]
                    for j in range(1, dense_stages):
                        value += d[m, j] * wk[W_K1 + j, i]
                q[i] = value
        return True

    return rosenbrock_step


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
