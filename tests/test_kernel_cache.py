"""The numba cache follows every numba source (issue 22): numba itself checks only the
timestamp of a function's own file, so an edit to monitor.py could run with a stale
compiled step loop. kernel/jit.py names the cache folder by a hash of all of them: the
kernel, the verdict and the step loop (jit.NUMBA_SOURCES)."""

from __future__ import annotations

import shutil
from pathlib import Path

import numba
import numpy as np

from frictiondisk.kernel import jit

PACKAGE = Path(jit.__file__).resolve().parents[1]


def _copy(tmp_path: Path) -> Path:
    """A copy of the package's numba sources under tmp_path (as jit.numba_sources reads)."""
    package = tmp_path / "frictiondisk"
    for source in jit.numba_sources(PACKAGE):
        target = package / source.relative_to(PACKAGE)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(source, target)
    return package


def test_the_cache_in_use_is_named_by_the_current_sources():
    assert numba.config.CACHE_DIR == jit.kernel_cache_dir(PACKAGE)


def test_an_edit_to_any_numba_file_moves_the_cache(tmp_path, monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    package = _copy(tmp_path)
    before = jit.kernel_cache_dir(package)
    assert jit.kernel_cache_dir(package) == before  # same sources, same folder
    edited = ("kernel/monitor.py", "verdict/machine.py", "verdict/params.py", "simulation/loop.py")
    for name in edited:  # none of them the dispatcher's own file
        with (package / name).open("a") as file:
            file.write("\n# edited\n")
        after = jit.kernel_cache_dir(package)
        assert after != before, name
        before = after


def test_a_new_numba_file_moves_the_cache(tmp_path, monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    package = _copy(tmp_path)
    before = jit.kernel_cache_dir(package)
    (package / "verdict" / "helpers.py").write_text("X = 1\n")
    assert jit.kernel_cache_dir(package) != before


def test_every_module_numba_compiles_is_hashed():
    """A module that uses the kernel's decorator outside NUMBA_SOURCES would keep a stale
    cache after an edit."""
    hashed = set(jit.numba_sources(PACKAGE))
    users = {
        path
        for path in PACKAGE.rglob("*.py")
        if "@kernel_" in path.read_text() and path.name != "jit.py"
    }
    assert users and users <= hashed, sorted(str(p) for p in users - hashed)


def test_a_constant_argument_compiles_the_callee_once():
    """numba compiles a callee once per literal a jitted caller passes it (Literal[int](0),
    a module constant) besides its plain type; the kernel's decorator types calls by their
    plain types, so each kernel function has one signature."""

    def pick(a, k):
        return a[k]

    def caller(pick):
        @numba.njit
        def total(a, n):
            s = pick(a, 0) + pick(a, n) + pick(a, FIRST)
            count = 0  # typed Literal[int](0) on its first pass
            for _ in range(n):
                s += pick(a, count)
                count += 1
            return s

        return total

    values = np.arange(4.0)
    plain = jit.plain_types(numba.njit(pick))
    assert caller(plain)(values, 2) == 3.0
    assert len(plain.signatures) == 1, plain.signatures
    literal = numba.njit(pick)  # numba on its own: the specialisations this removes
    assert caller(literal)(values, 2) == 3.0
    assert len(literal.signatures) > 1


FIRST = 0


SIGNATURES = """
import importlib, json, pathlib
import numba
from frictiondisk.kernel import jit
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.simulate import simulate

for scene in ("pin", "disk"):
    config = scene_from_dict({"scene": scene, "numerics": {"t_decide": 0.5}})
    simulate(config)
    simulate(config, record=True, dt_out=0.01)
several = {}
package = pathlib.Path(jit.__file__).parents[1]
for source in jit.numba_sources(package):
    name = ".".join(source.relative_to(package.parent).with_suffix("").parts)
    module = importlib.import_module(name)
    for attr, value in vars(module).items():
        if isinstance(value, numba.core.dispatcher.Dispatcher) and len(value.signatures) > 1:
            several[f"{name}.{attr}"] = [str(s) for s in value.signatures]
from frictiondisk.kernel import model
print(json.dumps({"several": several, "mode": str(model.switch_value.signatures[0][-1])}))
"""


def test_every_kernel_function_keeps_one_signature():
    """A pin, a disk and a recorded run call the kernel from Python with one set of
    argument types (e.g. a mode as int8, as the kernel holds it): one compiled (or loaded)
    signature per kernel function. In a process of its own: tests call kernel functions
    directly with other types."""
    import json
    import subprocess
    import sys

    done = subprocess.run(
        [sys.executable, "-c", SIGNATURES], capture_output=True, text=True, check=True
    )
    seen = json.loads(done.stdout.splitlines()[-1])
    assert seen["several"] == {}
    assert seen["mode"] == "int8"  # as the kernel holds modes: its own calls compile no other
