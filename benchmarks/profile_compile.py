"""Where the first run's numba compile goes (issue 32): every compilation of a cold cache.

In a fresh process with NUMBA_CACHE_DIR pointing at an empty folder, it simulates a pin
(the first call compiles), then a disk and a recorded pin (which must compile nothing
more), and prints:

* the wall and CPU time of the first call, and how much of the wall time numba spent
  holding its LLVM lock (LLVM IR building, optimisation and machine code) against the
  rest (numba's own passes in Python: bytecode analysis, type inference, lowering);
* the entry points compiled from Python and their signatures;
* every numba function compiled more than once (its signatures): the needless
  specialisations kernel/jit.py removes (expected: none);
* every twin of a kernel function compiled for a call from Python (kernel/jit.py
  `KernelDispatcher`; expected: none, the package calls entry points only);
* the numba functions that take the most time of their own (exclusive of the functions
  they call), and the share of each module. The numba code is the kernel, the verdict's
  machine and evidence, and the step loop (kernel/jit.py NUMBA_SOURCES).

    python benchmarks/profile_compile.py

Times are wall times of the compile events, so a loaded machine inflates them; the CPU
time of the first call is the steadier number.
"""

from __future__ import annotations

import collections
import os
import sys
import tempfile
import time

os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="frictiondisk-cold-")

from numba.core import event  # noqa: E402


class Compiles(event.Listener):
    """Every numba:compile event: (depth, function, signature, inclusive s, exclusive s)."""

    def __init__(self):
        self.stack: list[list] = []  # [start, time in children]
        self.done: list[tuple[int, str, str, float, float]] = []

    def on_start(self, ev):
        self.stack.append([time.perf_counter(), 0.0])

    def on_end(self, ev):
        start, children = self.stack.pop()
        spent = time.perf_counter() - start
        if self.stack:
            self.stack[-1][1] += spent
        function = getattr(ev.data.get("dispatcher"), "py_func", None)
        name = f"{function.__module__}.{function.__qualname__}" if function else "?"
        self.done.append((len(self.stack), name, str(ev.data.get("args")), spent, spent - children))


class Held(event.Listener):
    """Total time a lock event was held [s] (outermost holds only)."""

    def __init__(self):
        self.depth = 0
        self.total = 0.0

    def on_start(self, ev):
        if self.depth == 0:
            self.t0 = time.perf_counter()
        self.depth += 1

    def on_end(self, ev):
        self.depth -= 1
        if self.depth == 0:
            self.total += time.perf_counter() - self.t0


def short(signature: str) -> str:
    for long, brief in (
        ("Array(float64, 1, 'C', False, aligned=True)", "f8[::1]"),
        ("Array(float64, 2, 'C', False, aligned=True)", "f8[:, ::1]"),
        ("Array(int64, 1, 'C', False, aligned=True)", "i8[::1]"),
        ("Array(int8, 1, 'C', False, aligned=True)", "i1[::1]"),
    ):
        signature = signature.replace(long, brief)
    return signature


def main() -> int:
    compiles, llvm = Compiles(), Held()
    event.register("numba:compile", compiles)
    event.register("numba:llvm_lock", llvm)
    from frictiondisk.model.scene import scene_from_dict
    from frictiondisk.simulation.simulate import simulate

    def scene(name: str):
        points = {"points": 2} if name == "disk" else {}
        return scene_from_dict({"scene": name, "contact": points, "numerics": {"t_decide": 0.5}})

    wall0, cpu0 = time.perf_counter(), time.process_time()
    simulate(scene("pin"))
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    first = len(compiles.done)
    simulate(scene("disk"))
    simulate(scene("pin"), record=True, dt_out=0.01)
    later = len(compiles.done) - first

    numba_code = ("frictiondisk.kernel.", "frictiondisk.verdict.", "frictiondisk.simulation.loop.")
    kernel = [c for c in compiles.done if c[1].startswith(numba_code)]
    print(f"first call: {wall:.1f} s wall, {cpu:.1f} s CPU; LLVM lock held {llvm.total:.1f} s")
    print(f"compilations: {len(compiles.done)} ({len(kernel)} of kernel functions)")
    print(f"compilations by a disk and a recorded run after it: {later} (expected 0)")
    print("entry points (compiled from Python):")
    for depth, name, signature, spent, _ in compiles.done:
        if depth == 0:
            print(f"  {spent:6.2f} s  {name}{short(signature)[:110]}")
    per_function = collections.defaultdict(list)
    for _, name, signature, _, _ in kernel:
        per_function[name].append(signature)
    repeated = {name: sigs for name, sigs in per_function.items() if len(sigs) > 1}
    print(f"kernel functions compiled more than once: {len(repeated)}")
    for name, signatures in repeated.items():
        for signature in signatures:
            print(f"  {name}{short(signature)[:120]}")
    twins = sorted({name for _, name, _, _, _ in kernel if name.endswith(".from_python")})
    print(f"twins compiled for calls from Python: {len(twins)} (expected 0)")
    for name in twins:
        print(f"  {name}")
    print("kernel functions by their own compile time (callees excluded), top 12:")
    for _, name, _, _, own in sorted(kernel, key=lambda c: -c[4])[:12]:
        print(f"  {own:6.2f} s  {name}")
    by_module = collections.Counter()
    for _, name, _, _, own in compiles.done:
        module = name.rsplit(".", 1)[0] if name.startswith("frictiondisk.") else "numba itself"
        by_module[module] += own
    total = sum(by_module.values())
    print("own compile time by module:")
    for module, own in by_module.most_common():
        print(f"  {own:6.2f} s  {own / total:4.0%}  {module}")
    return 0 if later == 0 and not repeated and not twins else 1


if __name__ == "__main__":
    sys.exit(main())
