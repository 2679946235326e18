"""Recording a run's trajectory into the caller's buffers (numba): states at chosen
instants, and dense-output samples at multiples of dt_out. The buffers' fill and their
overflow flag are counters.recorded and counters.truncated (kernel/records.py COUNTERS).
The buffers: rec_t (cap) [s], rec_y (cap, n) states, rec_m (cap, N) contact modes."""

import math

from .jit import kernel_jit
from .linalg import copy_vector
from .rosenbrock import dense_eval


@kernel_jit
def record_state(recording, counters, t, y, modes):
    """Keep (t, y, modes) as the next row of recording = (rec_t, rec_y, rec_m); none once
    the buffers are full (counters.truncated)."""
    rec_t, rec_y, rec_m = recording
    k = counters.recorded
    if k >= rec_t.shape[0]:
        counters.truncated = True
        return
    rec_t[k] = t
    copy_vector(y, rec_y[k])
    for i in range(modes.shape[0]):  # int8 modes: copy_vector keeps one (float) signature
        rec_m[k, i] = modes[i]
    counters.recorded = k + 1


@kernel_jit
def record_dense(recording, counters, t0, h, s_end, y0, y1, wk, modes, dt_out, ybuf):
    """Record dense-output samples at multiples of dt_out in (t0, t0 + s_end h]; none once
    the buffers are full (counters.truncated), so a tiny dt_out cannot loop without bound."""
    t_end = t0 + s_end * h
    k = math.floor(t0 / dt_out) + 1
    while k * dt_out <= t_end and not counters.truncated:
        s = (k * dt_out - t0) / h
        dense_eval(y0, y1, wk, s, ybuf)
        record_state(recording, counters, k * dt_out, ybuf, modes)
        k += 1
