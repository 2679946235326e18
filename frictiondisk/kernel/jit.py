"""The one numba decorator of the kernel.

cache=True: compiled code is stored next to the sources, so only the first process pays
the compile time. nogil=True: runs release the GIL, so threads run them in parallel.
error_model="numpy": a division by zero yields inf/nan (caught by the
driver's finiteness checks and reported as a status) instead of raising inside a kernel.
Set NUMBA_DISABLE_JIT=1 to run the kernel as plain Python for debugging.

numba checks only the timestamp of a function's own file, so a cached driver.run would
keep calling a stale copy of an edited monitor.py. The cache therefore lives in a folder
named by a hash of every kernel source: any edit to any of them compiles afresh.
"""

import hashlib
import os
import pathlib

import numba as nb

KERNEL_SOURCES = pathlib.Path(__file__).resolve().parent


def kernel_cache_dir(sources: pathlib.Path = KERNEL_SOURCES) -> str:
    """A numba cache folder unique to the kernel sources in `sources` (under
    NUMBA_CACHE_DIR, or under that folder's __pycache__)."""
    digest = hashlib.sha256()
    for source in sorted(sources.glob("*.py")):
        digest.update(source.name.encode())
        digest.update(source.read_bytes())
    root = os.environ.get("NUMBA_CACHE_DIR") or str(sources / "__pycache__")
    return os.path.join(root, f"kernel-{digest.hexdigest()[:16]}")


nb.config.CACHE_DIR = kernel_cache_dir()

kernel_jit = nb.njit(cache=True, nogil=True, error_model="numpy")
