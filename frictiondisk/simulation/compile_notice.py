"""The "compiling the kernel" notice.

numba compiles the kernel on the first run in a process whose on-disk cache is cold (a new
install, a new numba, an edited kernel), without output, which looks like a hang. The
commands print one line to stderr before that happens. Every command compiles the same
entry point (kernel/driver.py `run`), so one estimate serves them all: measured on the
2-core development machine (2026-11-25), `simulate` of a pin, of a disk, with --record and
a campaign's warm-up each took 22-24 s cold and about 1 s warm (process start included).
"""

from __future__ import annotations

import sys
from typing import Any, TextIO

COMPILE_S = 25  # seconds, rounded up from the measurements above
MESSAGE = (
    f"compiling the kernel (first run after an install or a kernel change, about {COMPILE_S} s)"
)


def needs_compiling(dispatcher: Any = None) -> bool:
    """Whether the first call of the kernel's entry point (kernel/driver.py `run`) will
    compile it: not yet compiled or loaded in this process, and no entry in numba's
    on-disk cache index (which numba itself empties for a changed source or numba)."""
    if dispatcher is None:
        from frictiondisk.kernel import driver

        dispatcher = driver.run
    signatures = getattr(dispatcher, "signatures", None)
    if signatures is None:  # NUMBA_DISABLE_JIT: plain Python, nothing compiles
        return False
    if signatures:
        return False
    try:
        index = dispatcher._cache._cache_file._load_index()  # numba internals: may change
    except (AttributeError, OSError):
        return True  # cannot tell: say it
    return not index


def announce_compile(stream: TextIO | None = None) -> None:
    """Print `MESSAGE` (to stderr by default) if the next kernel call will compile."""
    if needs_compiling():
        print(MESSAGE, file=stream or sys.stderr, flush=True)
