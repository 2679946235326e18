"""Recording a run's trajectory into the caller's buffers (numba): states at chosen
instants, and dense-output samples at multiples of dt_out. The buffer's fill and its
overflow flag live in two slots of the driver's counters out_i."""

import math

from .jit import kernel_jit
from .rodas import dense_eval

C_RECORDED = 4  # out_i slot: rows recorded so far
C_TRUNCATED = 5  # out_i slot: 1 once the buffer was full


@kernel_jit
def record_state(rec_t, rec_y, rec_m, out_i, t, y, modes):
    """Keep (t, y, modes) as the next row; none once the buffer is full (C_TRUNCATED)."""
    k = out_i[C_RECORDED]
    if k >= rec_t.shape[0]:
        out_i[C_TRUNCATED] = 1
        return
    rec_t[k] = t
    rec_y[k, :] = y
    rec_m[k, :] = modes
    out_i[C_RECORDED] = k + 1


@kernel_jit
def record_dense(rec_t, rec_y, rec_m, out_i, t0, h, s_end, y0, y1, wk, modes, dt_out, ybuf):
    """Record dense-output samples at multiples of dt_out in (t0, t0 + s_end h]; none once
    the buffer is full (C_TRUNCATED), so a tiny dt_out cannot loop without bound."""
    t_end = t0 + s_end * h
    k = math.floor(t0 / dt_out) + 1
    while k * dt_out <= t_end and out_i[C_TRUNCATED] == 0:
        s = (k * dt_out - t0) / h
        dense_eval(y0, y1, wk, s, ybuf)
        record_state(rec_t, rec_y, rec_m, out_i, k * dt_out, ybuf, modes)
        k += 1
