"""The "compiling the kernel" notice.

numba compiles the kernel on the first run in a process whose on-disk cache is cold (a new
numba, an edited kernel, a cleaned cache; `make install` compiles it once itself),
without output, which looks like a hang. The commands print one line to stderr before
that happens. Every command compiles the same entry points (simulation/loop.py `run` and
the small functions the rodas4 method calls), so one estimate serves them all: on a
fresh numba cache of the 2-core development machine, a cold `simulate` of the pin took
46.8 s of CPU time (and 43.8 s in a second measurement), which is its wall time on an idle
core; on a busy machine the wall time is longer.
"""

from __future__ import annotations

import sys
from typing import Any, TextIO

COMPILE_S = 47  # seconds of CPU time, rounded up from the measurements above
MESSAGE = (
    "compiling the kernel (once after an install or a kernel change, "
    f"about {COMPILE_S} s on an idle core)"
)


def needs_compiling(dispatcher: Any = None) -> bool:
    """Whether the first call of the kernel's entry point (simulation/loop.py `run`) will
    compile it: not yet compiled or loaded in this process, and no entry in numba's
    on-disk cache index (which numba itself empties for a changed source or numba)."""
    if dispatcher is None:
        from frictiondisk.simulation import loop

        dispatcher = loop.run
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
