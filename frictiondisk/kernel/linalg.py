"""Linear algebra of the Rosenbrock stages (numba): dense LU, and the O(N) arrow solver.

The stage matrix A = I/(gamma h) - J of a scene with r = 2 nq rigid-body coordinates
(4 pin, 6 disk) and N contacts is block-arrow shaped: contact i's 2x2 diagonal block
couples only to the rigid coordinates (kernel/model.py). Such a matrix is stored in
*arrow form*, an (n, 2 r + 2) array with n = r + 2 N:
    row k < r (rigid):       columns 0 .. r-1      A[k, 0:r]
    row k >= r (contact i,   columns 0 .. r-1      A[k, 0:r]
      k = r + 2 i + a):      columns r, r+1        A[k, r+2i : r+2i+2]   (diagonal block)
                             columns r+2 .. 2r+1   A[0:r, k]             (border, transposed)
and solved by block elimination of the contacts (Schur complement on the rigid block):
    S = A_rr - sum_i B_i D_i^-1 C_i   (r x r, LU with partial pivoting),
factored once per step in O(N r^2), each solve O(N r). The diagonal blocks D_i are
inverted explicitly (2x2); they are dominated by 1/(gamma h) + c_i/beta_i, so eliminating
them without pivoting is safe.

`stage_workspace` allocates (jac, lu, piv) for either path; the path is told by piv:
length n (dense) or r (arrow).
"""

import numpy as np

from .jit import kernel_jit, kernel_jit_allocating


@kernel_jit_allocating
def stage_workspace(n, nq, dense):
    """(jac, lu, piv) for an n-state scene: (n, n), (n, n), n if dense, else arrow form
    (n, 4 nq + 2), (n, 4 nq + 2), 2 nq."""
    if dense:
        return np.empty((n, n)), np.empty((n, n)), np.empty(n, dtype=np.int64)
    r = 2 * nq
    return np.empty((n, 2 * r + 2)), np.empty((n, 2 * r + 2)), np.empty(r, dtype=np.int64)


@kernel_jit
def copy_vector(src, dst):
    """dst[:] = src, element by element (a slice assignment needs numba's reference
    counting, which the kernel's functions run without, kernel/jit.py)."""
    for j in range(dst.shape[0]):
        dst[j] = src[j]


@kernel_jit
def is_dense(piv, n):
    """Whether a (jac, lu, piv) workspace of an n-state scene is the dense one."""
    return piv.shape[0] == n


@kernel_jit
def lu_factor(a, piv):
    """Factor `a` in place (L unit lower, U upper); piv receives row swaps. Returns False if singular."""
    n = a.shape[0]
    return _lu_factor_lead(a, piv, n)


@kernel_jit
def _lu_factor_lead(a, piv, n):
    """lu_factor of the leading n x n block of `a`."""
    for k in range(n):
        p = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                p = i
        piv[k] = p
        if big == 0.0 or not np.isfinite(big):
            return False
        if p != k:
            for j in range(n):
                tmp = a[k, j]
                a[k, j] = a[p, j]
                a[p, j] = tmp
        inv = 1.0 / a[k, k]
        for i in range(k + 1, n):
            lik = a[i, k] * inv
            a[i, k] = lik
            if lik != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= lik * a[k, j]
    return True


@kernel_jit
def lu_solve(lu, piv, b, x):
    """Solve lu x = b (b is not modified)."""
    n = lu.shape[0]
    for i in range(n):
        x[i] = b[i]
    _lu_solve_lead(lu, piv, x, n)


@kernel_jit
def _lu_solve_lead(lu, piv, x, n):
    """Overwrite x[0:n] with the solution of (leading n x n block of lu) x = x."""
    for k in range(n):
        p = piv[k]
        if p != k:
            tmp = x[k]
            x[k] = x[p]
            x[p] = tmp
    for i in range(n):
        s = x[i]
        for j in range(i):
            s -= lu[i, j] * x[j]
        x[i] = s
    for i in range(n - 1, -1, -1):
        s = x[i]
        for j in range(i + 1, n):
            s -= lu[i, j] * x[j]
        x[i] = s / lu[i, i]


@kernel_jit
def arrow_factor(a, lu, piv):
    """Factor the arrow-form matrix `a` (module docstring) into `lu`, r = piv.shape[0].

    lu rows of contact i: columns 0 .. r-1 hold X_i = D_i^-1 C_i, columns r, r+1 hold
    D_i^-1, columns r+2 .. 2r+1 the border B_i^T; rows 0 .. r-1 hold the LU factors of
    the Schur complement S. Returns False if some D_i or S is singular or not finite.
    """
    r = piv.shape[0]
    n = a.shape[0]
    for k in range(r):
        for j in range(r):
            lu[k, j] = a[k, j]
    for z in range(r, n, 2):
        d00 = a[z, r]
        d01 = a[z, r + 1]
        d10 = a[z + 1, r]
        d11 = a[z + 1, r + 1]
        det = d00 * d11 - d01 * d10
        if det == 0.0 or not np.isfinite(det):
            return False
        e00 = d11 / det
        e01 = -d01 / det
        e10 = -d10 / det
        e11 = d00 / det
        lu[z, r] = e00
        lu[z, r + 1] = e01
        lu[z + 1, r] = e10
        lu[z + 1, r + 1] = e11
        for j in range(r):
            c0 = a[z, j]
            c1 = a[z + 1, j]
            x0 = e00 * c0 + e01 * c1
            x1 = e10 * c0 + e11 * c1
            lu[z, j] = x0
            lu[z + 1, j] = x1
        for k in range(r):
            b0 = a[z, r + 2 + k]
            b1 = a[z + 1, r + 2 + k]
            lu[z, r + 2 + k] = b0
            lu[z + 1, r + 2 + k] = b1
            if b0 != 0.0 or b1 != 0.0:
                for j in range(r):
                    lu[k, j] -= b0 * lu[z, j] + b1 * lu[z + 1, j]
    return _lu_factor_lead(lu, piv, r)


@kernel_jit
def arrow_solve(lu, piv, b, x):
    """Solve A x = b with A factored by arrow_factor (b is not modified)."""
    r = piv.shape[0]
    n = lu.shape[0]
    for k in range(r):
        x[k] = b[k]
    # contacts: x_i = D_i^-1 b_i for now; fold B_i x_i into the rigid right-hand side
    for z in range(r, n, 2):
        b0 = b[z]
        b1 = b[z + 1]
        y0 = lu[z, r] * b0 + lu[z, r + 1] * b1
        y1 = lu[z + 1, r] * b0 + lu[z + 1, r + 1] * b1
        x[z] = y0
        x[z + 1] = y1
        for k in range(r):
            x[k] -= lu[z, r + 2 + k] * y0 + lu[z + 1, r + 2 + k] * y1
    _lu_solve_lead(lu, piv, x, r)
    for z in range(r, n, 2):
        s0 = x[z]
        s1 = x[z + 1]
        for j in range(r):
            s0 -= lu[z, j] * x[j]
            s1 -= lu[z + 1, j] * x[j]
        x[z] = s0
        x[z + 1] = s1


@kernel_jit
def stage_factor(jac, inv_gh, lu, piv):
    """Factor the stage matrix I * inv_gh - J, J in the form `jac` has (dense or arrow)."""
    n = jac.shape[0]
    if is_dense(piv, n):
        for i in range(n):
            for j in range(n):
                lu[i, j] = -jac[i, j]
            lu[i, i] += inv_gh
        return lu_factor(lu, piv)
    r = piv.shape[0]
    w = jac.shape[1]
    for i in range(n):
        for j in range(w):
            lu[i, j] = -jac[i, j]
    for k in range(r):
        lu[k, k] += inv_gh
    for z in range(r, n, 2):
        lu[z, r] += inv_gh
        lu[z + 1, r + 1] += inv_gh
    return arrow_factor(lu, lu, piv)  # in place: each entry is read before it is written


@kernel_jit
def stage_solve(lu, piv, b, x):
    """Solve with the factors of stage_factor (b is not modified)."""
    if is_dense(piv, lu.shape[0]):
        lu_solve(lu, piv, b, x)
    else:
        arrow_solve(lu, piv, b, x)
