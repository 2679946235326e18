"""The numba decorators of the kernel: `kernel_jit`, `kernel_jit_allocating` for the few
functions that allocate the run's scratch (see "No reference counting" below), and
`kernel_entry` / `kernel_entry_allocating` for the few the package calls from Python (see
"No CPython wrapper").

cache=True: compiled code is stored next to the sources, so only the first process pays
the compile time. nogil=True: runs release the GIL, so threads run them in parallel.
error_model="numpy": a division by zero yields inf/nan (caught by the
driver's finiteness checks and reported as a status) instead of raising inside a kernel.
NUMBA_DISABLE_JIT=1 leaves every kernel function plain Python, but a simulation does not
run so: the kernel reads its records (kernel/records.py) by attribute, which numba allows
and a numpy structured scalar does not.

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

No reference counting: numba counts the references of every array a function holds,
with an atomic increment and decrement of its owner for each array argument of each
call, each view and each tuple element taken. In the step loop, whose functions are
small and called millions of times, that counting cost more than the arithmetic (about
60 % of a pin run's time, docs/benchmarks.md). `kernel_jit` compiles a function without
it (numba's `_nrt=False`): such a function may take, index, slice and pass arrays, but
may not allocate one (numba refuses to compile it: "NRT required but not enabled") nor
return one (its caller would count the returned reference as a new one; `plain_types`
refuses that at compile time). The few functions that allocate the run's scratch, or
return it, are `kernel_jit_allocating`, with the counting on.

No CPython wrapper: numba builds, optimises and emits for every function it compiles a
wrapper that unboxes the arguments of a call from Python, and links it into the module of
every kernel function above it, though only Python ever calls it. `kernel_jit` functions
have none (a `KernelDispatcher`); the few the package calls from Python are
`kernel_entry` (`kernel_entry_allocating`), and tests/test_kernel_entry.py checks that the
package calls no other from Python. A call from Python to any other kernel function (a
test, a study, the Radau integrator) runs its twin with the wrapper, compiled and cached
on the first such call. That cut the cold compile by about a fifth (docs/benchmarks.md).
"""

import functools
import hashlib
import os
import pathlib
import types as pytypes

import numba as nb
from numba.core import types
from numba.core.registry import CPUDispatcher
from numba.core.targetconfig import ConfigStack

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

_OPTIONS = {"nopython": True, "nogil": True, "error_model": "numpy"}
_INTERNAL = {"no_cpython_wrapper": True, "no_cfunc_wrapper": True}


class KernelDispatcher(CPUDispatcher):
    """A kernel function compiled without a CPython wrapper, for calls from other kernel
    functions; a call from Python runs its twin `from_python` (module docstring)."""

    def __call__(self, *args, **kwargs):
        return self.from_python(*args, **kwargs)

    @functools.cached_property
    def from_python(self):
        """The twin of this function with a CPython wrapper (cached under its own name)."""
        original = self.py_func
        twin = pytypes.FunctionType(
            original.__code__,
            original.__globals__,
            original.__name__,
            original.__defaults__,
            original.__closure__,
        )
        twin.__qualname__ = f"{original.__qualname__}.from_python"
        twin.__module__ = original.__module__
        counted = self.targetoptions["_nrt"]
        return _compile(twin, counted, internal=False)


def _compile(function, counted: bool, internal: bool, inline: bool = False):
    """`function` compiled by numba with the kernel's options, cached (`_nrt` explicitly:
    numba lets a callee inherit its caller's unset flag)."""
    if nb.config.DISABLE_JIT:  # NUMBA_DISABLE_JIT: the plain function
        return function
    options = {**_OPTIONS, "_nrt": counted, **(_INTERNAL if internal else {})}
    if inline:
        options["inline"] = "always"
    dispatcher_class = KernelDispatcher if internal else CPUDispatcher
    dispatcher = dispatcher_class(py_func=function, locals={}, targetoptions=options)
    dispatcher.enable_caching()
    return plain_types(dispatcher, counted=counted)


def kernel_jit(function):
    """The kernel's numba decorator: no reference counting, no CPython wrapper (a
    `KernelDispatcher`), and the arguments of calls from other kernel functions typed
    without literals."""
    return _compile(function, counted=False, internal=True)


def kernel_jit_inline(function):
    """`kernel_jit` for a function numba inlines where it is called (its IR, before
    typing): a constant argument of the call (a Rosenbrock stage's index) is then a
    constant in its body, and the loops it bounds unroll."""
    return _compile(function, counted=False, internal=True, inline=True)


def kernel_jit_allocating(function):
    """`kernel_jit` with numba's reference counting, for a function that allocates arrays
    or returns them."""
    return _compile(function, counted=True, internal=True)


def kernel_entry(function):
    """`kernel_jit` for a function the package calls from Python: with its CPython
    wrapper."""
    return _compile(function, counted=False, internal=False)


def kernel_entry_allocating(function):
    """`kernel_jit_allocating` for a function the package calls from Python."""
    return _compile(function, counted=True, internal=False)


def holds_array(numba_type) -> bool:
    """Whether a numba type is an array or a tuple (or optional) holding one."""
    if isinstance(numba_type, types.Buffer):
        return True
    if isinstance(numba_type, types.BaseTuple):
        return any(holds_array(member) for member in numba_type.types)
    if isinstance(numba_type, types.Optional):
        return holds_array(numba_type.type)
    return False


def plain_types(dispatcher, counted: bool = True):
    """`dispatcher`, compiled for the plain type of each argument a jitted caller passes
    (Literal[int](0) -> int64): one signature where numba would add one per literal.

    And the rule of the counting, checked where a caller first types a call: an array may
    be returned only from a counted function (counted=True) to a counted caller; else the
    returned reference would be freed too early or never."""
    typing = getattr(dispatcher, "get_call_template", None)
    if typing is None:  # NUMBA_DISABLE_JIT: the plain function
        return dispatcher

    def get_call_template(args, kws):
        plain = tuple(types.unliteral(arg) for arg in args)
        template = typing(plain, {name: types.unliteral(arg) for name, arg in kws.items()})
        # numba keeps the flags of the function being compiled (the caller) on this stack
        caller = ConfigStack.top_or_none()
        caller_counted = caller is None or caller.nrt
        for compiled in dispatcher.overloads.values():
            if holds_array(compiled.signature.return_type) and not (counted and caller_counted):
                raise TypeError(
                    f"{dispatcher.py_func.__qualname__} returns an array to a caller, or "
                    "from a function, without reference counting: both must be "
                    "kernel_jit_allocating (frictiondisk/kernel/jit.py)"
                )
        return template

    dispatcher.get_call_template = get_call_template  # numba's typing of a call asks this
    return dispatcher
