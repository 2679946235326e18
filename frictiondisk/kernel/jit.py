"""The one numba decorator of the kernel.

cache=True: compiled code is stored next to the sources, so only the first process pays
the compile time. nogil=True: runs release the GIL, so threads run them in parallel.
error_model="numpy": a division by zero yields inf/nan (caught by the
driver's finiteness checks and reported as a status) instead of raising inside a kernel.
Set NUMBA_DISABLE_JIT=1 to run the kernel as plain Python for debugging.

One signature per function: numba types a constant argument of a call inside the kernel
(`_row(mi, 0)`, a module constant such as KIND_SWITCH, a counter's first value `0`) as a
literal, and compiles the callee once for every literal it meets besides its plain type:
9 extra compilations of 8 functions in a cold compile (benchmarks/profile_compile.py,
docs/benchmarks.md). `kernel_jit` types every argument of a call between kernel functions
by its plain type (int64, bool, float64), so each compiles once.

numba checks only the timestamp of a function's own file, so a cached step loop would
keep calling a stale copy of an edited monitor.py. The cache therefore lives in a folder
named by a hash of every numba source (NUMBA_SOURCES: the kernel, the verdict and the
step loop, frictiondisk/simulation/loop.py): any edit to any of them compiles afresh.
"""

import hashlib
import os
import pathlib

import numba as nb
from numba.core import types

KERNEL_SOURCES = pathlib.Path(__file__).resolve().parent
PACKAGE = KERNEL_SOURCES.parent
# Every source numba compiles, relative to the package folder: a whole folder ("kernel")
# or one file ("simulation/loop.py"). tests/test_kernel_cache.py checks that every module
# using kernel_jit lies in one of them.
NUMBA_SOURCES = ("kernel", "verdict", "simulation/loop.py")


def numba_sources(package: pathlib.Path = PACKAGE) -> list[pathlib.Path]:
    """The numba source files under `package` (NUMBA_SOURCES), sorted."""
    files: list[pathlib.Path] = []
    for entry in NUMBA_SOURCES:
        path = package / entry
        files.extend(sorted(path.glob("*.py")) if path.is_dir() else [path])
    return files


def kernel_cache_dir(package: pathlib.Path = PACKAGE) -> str:
    """A numba cache folder unique to the numba sources under `package` (under
    NUMBA_CACHE_DIR, or under the kernel's __pycache__)."""
    digest = hashlib.sha256()
    for source in numba_sources(package):
        digest.update(source.relative_to(package).as_posix().encode())
        digest.update(source.read_bytes())
    root = os.environ.get("NUMBA_CACHE_DIR") or str(package / "kernel" / "__pycache__")
    return os.path.join(root, f"kernel-{digest.hexdigest()[:16]}")


nb.config.CACHE_DIR = kernel_cache_dir()

_njit = nb.njit(cache=True, nogil=True, error_model="numpy")


def kernel_jit(function):
    """The kernel's numba decorator: `_njit`, typing the arguments of calls from other
    kernel functions without literals."""
    return plain_types(_njit(function))


def plain_types(dispatcher):
    """`dispatcher`, compiled for the plain type of each argument a jitted caller passes
    (Literal[int](0) -> int64): one signature where numba would add one per literal."""
    typing = getattr(dispatcher, "get_call_template", None)
    if typing is None:  # NUMBA_DISABLE_JIT: the plain function
        return dispatcher

    def get_call_template(args, kws):
        plain = tuple(types.unliteral(arg) for arg in args)
        return typing(plain, {name: types.unliteral(arg) for name, arg in kws.items()})

    dispatcher.get_call_template = get_call_template  # numba's typing of a call asks this
    return dispatcher
