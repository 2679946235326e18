"""Kernel functions without a CPython wrapper (kernel/jit.py `KernelDispatcher`): other
kernel functions call the function itself, a call from Python runs its twin with the
wrapper, and the package calls only entry points (`kernel_entry`) from Python,
so a simulation compiles no twin."""

from __future__ import annotations

import ast
import importlib
import importlib.util
from pathlib import Path

import numpy as np

from frictiondisk.kernel import jit
from frictiondisk.kernel.jit import KernelDispatcher, kernel_entry, kernel_jit

PACKAGE = Path(jit.__file__).resolve().parents[1]
# The independent integrator (simulation/radau.py) and its stop rules (verdict/
# segment_rules.py) step the monitor and the verdict's machine from Python; their twins
# compile on its first use, not on the default path.
CALLS_TWINS = {"frictiondisk.simulation.radau", "frictiondisk.verdict.segment_rules"}


@kernel_jit
def _scaled_sum(values, factor):
    total = 0.0
    for value in values:
        total += factor * value
    return total


@kernel_entry
def _twice_the_scaled_sum(values):
    return 2.0 * _scaled_sum(values, 1.5)


def test_an_internal_function_called_from_python_runs_its_twin():
    values = np.array([1.0, 2.0, 4.0])
    assert _scaled_sum(values, 2.0) == _scaled_sum.py_func(values, 2.0) == 14.0
    assert isinstance(_scaled_sum, KernelDispatcher)
    assert _scaled_sum.targetoptions["no_cpython_wrapper"]
    twin = _scaled_sum.from_python
    assert not isinstance(twin, KernelDispatcher)
    assert twin.py_func.__qualname__ == "_scaled_sum.from_python"
    assert twin.signatures  # the call from Python compiled (or loaded) the twin


def test_an_entry_point_calls_an_internal_function():
    values = np.array([1.0, 2.0])
    assert _twice_the_scaled_sum(values) == 9.0
    assert not isinstance(_twice_the_scaled_sum, KernelDispatcher)  # called directly
    assert not _twice_the_scaled_sum.targetoptions.get("no_cpython_wrapper")


def dotted_name(path: Path) -> str:
    """The module name of a source file of the package."""
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


NUMBA_MODULES = {dotted_name(source) for source in jit.numba_sources(PACKAGE)}


def python_calls_of_internal_functions(path: Path, name: str) -> list[str]:
    """Calls in module `name` (not numba code) of a kernel function that is no entry
    point, as 'module.function'."""
    bound: dict[str, object] = {}  # a local name -> the kernel module or function it names
    tree = ast.parse(path.read_text(), str(path))
    for node in ast.walk(tree):
        if not isinstance(node, ast.ImportFrom):
            continue
        source = node.module or ""
        if node.level:  # relative to the module's package (a package's own __init__: itself)
            package = name if path.name == "__init__.py" else name.rpartition(".")[0]
            source = importlib.util.resolve_name("." * node.level + source, package)
        for alias in node.names:
            full = f"{source}.{alias.name}"
            if full in NUMBA_MODULES:
                bound[alias.asname or alias.name] = importlib.import_module(full)
            elif source in NUMBA_MODULES:
                module = importlib.import_module(source)
                bound[alias.asname or alias.name] = getattr(module, alias.name, None)
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        target = node.func
        if isinstance(target, ast.Name):
            called = bound.get(target.id)
        elif isinstance(target, ast.Attribute) and isinstance(target.value, ast.Name):
            called = getattr(bound.get(target.value.id), target.attr, None)
        else:
            continue
        if isinstance(called, KernelDispatcher):
            found.append(f"{called.py_func.__module__}.{called.py_func.__name__}")
    return found


def test_the_package_calls_only_entry_points_from_python():
    offenders = {}
    checked = 0
    for path in sorted(PACKAGE.rglob("*.py")):
        name = dotted_name(path)
        if "@kernel_" in path.read_text() or name in CALLS_TWINS:
            continue  # numba code calls kernel functions without their wrapper
        checked += 1
        calls = python_calls_of_internal_functions(path, name)
        if calls:
            offenders[name] = sorted(set(calls))
    assert checked > 100
    assert not offenders, offenders


def test_the_rule_finds_a_call_of_an_internal_function(tmp_path):
    radau = PACKAGE / "simulation" / "radau.py"
    calls = python_calls_of_internal_functions(radau, "frictiondisk.simulation.radau")
    assert "frictiondisk.kernel.monitor.switch" in calls
    relative = tmp_path / "relative.py"  # as if it were frictiondisk/verdict/relative.py
    relative.write_text("from .sliding import steady_sliding\n\nsteady_sliding(1, 2)\n")
    calls = python_calls_of_internal_functions(relative, "frictiondisk.verdict.relative")
    assert calls == ["frictiondisk.verdict.sliding.steady_sliding"]
