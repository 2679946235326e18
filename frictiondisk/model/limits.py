"""What one machine can do: recording size and worker count, checked before work starts.

A recorded run keeps its trajectory in a preallocated buffer (simulate.py): at most
MAX_RECORD_ROWS rows and MAX_RECORD_BYTES bytes. `recording_problem` refuses a recording
interval that the horizon would overflow, naming the field and the smallest interval that
fits, instead of a run that stops recording half way. `workers_problem` refuses more
local Dask workers than the machine has cores and memory for.
"""

from __future__ import annotations

import math
import os

__all__ = [
    "MAX_RECORD_BYTES",
    "MAX_RECORD_ROWS",
    "RECORD_SWITCH_ROOM",
    "max_workers",
    "record_rows_limit",
    "recording_problem",
    "workers_problem",
]

MAX_RECORD_ROWS = 2_000_000
MAX_RECORD_BYTES = 1 << 30  # 1 GiB: a disk with 1000 contacts has 16 kB rows
RECORD_SWITCH_ROOM = 50_000  # rows kept for the extra samples at switching instants
WORKERS_PER_CORE = 4  # threads beyond the cores only queue; this leaves room for I/O waits
WORKER_MEMORY = 256 << 20  # [bytes] a Dask worker below this pauses (distributed's limits)


def record_rows_limit(n_state: int, n_contacts: int) -> int:
    """Rows a recording may hold: MAX_RECORD_ROWS, fewer if its rows are wide."""
    row_bytes = 8 * (1 + n_state) + n_contacts
    return max(RECORD_SWITCH_ROOM + 1000, min(MAX_RECORD_ROWS, MAX_RECORD_BYTES // row_bytes))


def recording_problem(config, dt_out: float, field: str) -> str | None:
    """A message naming `field` if samples every `dt_out` s over the run's horizon (plus one
    revolution for a final sticking phase) overflow the recording buffer, else None."""
    if not (dt_out > 0.0 and math.isfinite(dt_out)):
        return None  # the field's own validation says what is wrong
    num = config.numerics
    horizon = num.t_max if num.mode == "converge" else num.t_decide
    omega = config.params.omega_m
    t_span = horizon + (2.0 * math.pi / omega if omega > 0.0 else 2.0 * math.pi)
    nq = 3 if config.scene == "disk" else 2
    n = config.n_contacts
    room = record_rows_limit(2 * nq + 2 * n, n) - RECORD_SWITCH_ROOM
    if t_span / dt_out <= room:
        return None
    which = "numerics.t_max" if num.mode == "converge" else "numerics.t_decide"
    return (
        f"{field}: {dt_out:g} s is out of range: {t_span:.6g} s of simulated time "
        f"({which} plus one revolution) would need {t_span / dt_out:.3g} rows, and a "
        f"recording holds {room}: must be >= {t_span / room:.3g} s (or shorten {which})"
    )


def max_workers() -> int:
    """Local workers this machine can run: WORKERS_PER_CORE per core, each with at least
    WORKER_MEMORY of the physical memory."""
    cores = os.cpu_count() or 1
    try:
        memory = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError):
        memory = cores * WORKERS_PER_CORE * WORKER_MEMORY
    return max(1, min(WORKERS_PER_CORE * cores, memory // WORKER_MEMORY))


def workers_problem(workers: int) -> str | None:
    """A message naming --workers if `workers` exceeds `max_workers()`, else None."""
    top = max_workers()
    if workers <= top:
        return None
    cores = os.cpu_count() or 1
    return (
        f"--workers: {workers} is more than this machine can run: at most {top} "
        f"({WORKERS_PER_CORE} per CPU core, {cores} cores; each worker needs "
        f"{WORKER_MEMORY >> 20} MiB of memory)"
    )
