"""The package's import graph and its cohesion: no cycles, no upward imports, numba code
free of orchestration, no cross-module import of a private name, no function over 100
lines.

Read from the source with `ast` (nothing is imported), so every import counts, also the
ones inside functions that only run later: a lazy import hides a cycle from the
interpreter, not from a reader.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "frictiondisk"
KERNEL_FORBIDDEN = ("dask", "distributed", "xarray", "click", "matplotlib")
# Cohesion instead of a line cap (issue 47, item 5): every module of the package is held to
# it, no module imports another's private name and no function runs over 100 lines.
LONGEST_FUNCTION = 100  # lines, docstring included


def module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imported_names(name: str, path: Path) -> set[str]:
    """Every module `name` imports, absolute and relative; `from pkg import x` counts as an
    import of the submodule pkg.x when x is one, else of pkg."""
    is_package = path.name == "__init__.py"
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = name.split(".")
                if not is_package:
                    base = base[:-1]
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                found.add(sub if sub in MODULES else target)
    return found


def import_graph() -> dict[str, set[str]]:
    return {
        name: {m for m in imported_names(name, path) if m in MODULES and m != name}
        for name, path in MODULES.items()
    }


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


# The packages in data-flow order (docs/architecture.md): a module may import its own
# package and those before it, never one after it. version.py sits below all of them and
# the package root (the public API) above them.
LAYERS = (
    "version",
    "model",
    "kernel",
    "verdict",
    "simulation",
    "store",
    "figures",
    "tasks",
    "engine",
    "studies",
    "cli",
)


def layer_of(module: str) -> int:
    """The rank of a module's package in LAYERS; the package root ranks above them all."""
    parts = module.split(".")
    if len(parts) == 1:
        return len(LAYERS)
    return LAYERS.index(parts[1])


def test_the_graph_is_read():
    graph = import_graph()
    assert "frictiondisk.verdict.machine" in graph["frictiondisk.simulation.loop"]
    assert "frictiondisk.engine.runner" in MODULES
    stepper = MODULES["frictiondisk.kernel.rosenbrock"]  # `from .linalg import`: relative
    assert "frictiondisk.kernel.linalg" in imported_names("frictiondisk.kernel.rosenbrock", stepper)


def test_every_module_lies_in_a_layer():
    for name in MODULES:
        assert 0 <= layer_of(name) <= len(LAYERS), name


def test_an_upward_import_is_found():
    assert layer_of("frictiondisk.model.scene") < layer_of("frictiondisk.engine.runner")
    assert layer_of("frictiondisk") > layer_of("frictiondisk.cli.main")


def test_imports_point_down_the_layers():
    upward = [
        f"{name} ({LAYERS[layer_of(name)]}) imports {dep}"
        for name, deps in import_graph().items()
        for dep in sorted(deps)
        if layer_of(dep) > layer_of(name)
    ]
    assert not upward, "\n".join(upward)


@pytest.mark.parametrize("package", [p for p in LAYERS if p != "version"])
def test_every_package_says_what_it_holds_in_two_lines(package):
    doc = ast.get_docstring(ast.parse((PACKAGE / package / "__init__.py").read_text()))
    assert doc and len(doc.strip().splitlines()) == 2, package


def test_a_cycle_is_detected():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


def test_no_import_cycles():
    assert cycles(import_graph()) == []


def numba_modules() -> list[str]:
    """Every module numba compiles: the kernel, and any module that uses the kernel's
    decorator (the verdict's machine and evidence, the step loop)."""
    found = []
    for name, path in MODULES.items():
        if name.startswith("frictiondisk.kernel"):
            found.append(name)
            continue
        names = {
            alias.name
            for node in ast.walk(ast.parse(path.read_text(), str(path)))
            if isinstance(node, ast.ImportFrom)
            for alias in node.names
        }
        if names & {"kernel_jit", "kernel_entry"}:
            found.append(name)
    return sorted(found)


def test_the_numba_modules_are_found():
    found = numba_modules()
    assert "frictiondisk.simulation.loop" in found
    assert "frictiondisk.verdict.machine" in found
    assert "frictiondisk.verdict.label" not in found


@pytest.mark.parametrize("name", numba_modules())
def test_numba_code_never_imports_orchestration(name):
    """numba modules import numba, numpy and the kernel's and the verdict's numba modules
    (the kernel: only its own); never dask, xarray, click, matplotlib or a later stage."""
    own = ("frictiondisk.kernel",) if name.startswith("frictiondisk.kernel") else None
    allowed = own or ("frictiondisk.kernel", "frictiondisk.verdict")
    bad = {
        m
        for m in imported_names(name, MODULES[name])
        if m.split(".")[0] in KERNEL_FORBIDDEN
        or (m.startswith("frictiondisk.") and not m.startswith(allowed))
    }
    assert not bad, f"{name} imports {sorted(bad)}"


def cohesive(name: str) -> bool:
    return name.startswith("frictiondisk")


def private_imports(name: str, path: Path) -> list[str]:
    """The private names (`_x`, not dunders) `name` takes from another frictiondisk module:
    imported (`from m import _x`) or read off an imported module (`m._x`)."""
    tree = ast.parse(path.read_text(), str(path))
    modules: set[str] = set()  # local names bound to frictiondisk modules
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = _resolved(name, path, node)
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                if sub in MODULES:
                    modules.add(alias.asname or alias.name)
                elif _private(alias.name) and base.startswith("frictiondisk") and base != name:
                    found.append(f"{name}: from {base} import {alias.name}")
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in MODULES:
                    modules.add(alias.asname or alias.name)
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Attribute)
            and isinstance(node.value, ast.Name)
            and node.value.id in modules
            and _private(node.attr)
        ):
            found.append(f"{name}: {node.value.id}.{node.attr}")
    return found


def _private(attr: str) -> bool:
    return attr.startswith("_") and not attr.startswith("__")


def _resolved(name: str, path: Path, node: ast.ImportFrom) -> str:
    """The absolute module an ImportFrom node reads from."""
    if not node.level:
        return node.module or ""
    base = name.split(".")
    if path.name != "__init__.py":
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def test_a_private_import_is_found(tmp_path):
    source = tmp_path / "x.py"
    source.write_text(
        "from frictiondisk.kernel.monitor import _radius\n"
        "from frictiondisk.kernel import monitor\n"
        "monitor._overlap\n"
    )
    found = private_imports("frictiondisk.simulation.x", source)
    assert len(found) == 2, found


def test_no_module_imports_a_private_name_of_another():
    found = [
        line
        for name, path in MODULES.items()
        if cohesive(name)
        for line in private_imports(name, path)
    ]
    assert not found, "\n".join(found)


def long_functions(path: Path, limit: int = LONGEST_FUNCTION) -> list[str]:
    """Functions (and methods) in `path` longer than `limit` lines, docstring included."""
    tree = ast.parse(path.read_text(), str(path))
    return [
        f"{path.name}:{node.lineno} {node.name} ({node.end_lineno - node.lineno + 1} lines)"
        for node in ast.walk(tree)
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
        and node.end_lineno - node.lineno + 1 > limit
    ]


def test_no_function_is_over_100_lines():
    long = [f for name, path in MODULES.items() if cohesive(name) for f in long_functions(path)]
    assert not long, "\n".join(long)
