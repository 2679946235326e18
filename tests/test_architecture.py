"""The package's import graph and its cohesion: no cycles, no upward imports, numba code
free of orchestration, no cross-module import of a private name, no function over 100
lines; tasks that reach each other only through shared modules and the registry; no module
of tasks/ or verdict/ over 400 lines, no class over 20 methods, an outcome's name spelled
in verdict/outcomes.py only, and no issue numbers in the package's text.

Read from the source with `ast` (nothing is imported but the task registry, which says
which packages are tasks), so every import counts, also the ones inside functions that only
run later: a lazy import hides a cycle from the interpreter, not from a reader.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "frictiondisk"
KERNEL_FORBIDDEN = ("dask", "distributed", "xarray", "click", "matplotlib")
# Cohesion: every module of the package is held to it, no module imports another's private
# name and no function runs over 100 lines.
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


# ---- tasks reach each other only through shared modules -------------------------------


def task_packages() -> set[str]:
    """The packages of the registered tasks (frictiondisk.tasks.<name>), from the registry."""
    from frictiondisk.tasks.registry import TASKS

    return {type(entry).__module__.rsplit(".", 1)[0] for entry in TASKS.values()}


def package_of(module: str, packages: set[str]) -> str | None:
    """The task package `module` lies in, None for a module of no task."""
    return next((p for p in packages if module == p or module.startswith(p + ".")), None)


def test_the_task_packages_are_found():
    packages = task_packages()
    assert {"frictiondisk.tasks.find_jump", "frictiondisk.tasks.map"} <= packages
    assert "frictiondisk.tasks.jump_search" not in packages  # shared search machinery
    assert package_of("frictiondisk.tasks.map.cells", packages) == "frictiondisk.tasks.map"


def test_no_task_imports_another_task():
    """A task uses shared modules (tasks/jump_search/, tasks/sampling/, figures/, store/,
    ...), never another task's package."""
    packages = task_packages()
    crossing = [
        f"{name} imports {dep}"
        for name, deps in import_graph().items()
        if package_of(name, packages)
        for dep in sorted(deps)
        if package_of(dep, packages) not in (None, package_of(name, packages))
    ]
    assert not crossing, "\n".join(crossing)


def test_shared_machinery_reaches_a_task_through_the_registry():
    """Below the studies (engine/, tasks/' shared modules, figures/, store/, ...) only the
    registry names a task; studies/ and cli/ sit above the tasks and may import them."""
    packages = task_packages()
    above = {"frictiondisk.studies", "frictiondisk.cli"}
    naming = [
        f"{name} imports {dep}"
        for name, deps in import_graph().items()
        if name != "frictiondisk.tasks.registry"
        and name != "frictiondisk"
        and not package_of(name, packages)
        and not any(name == a or name.startswith(a + ".") for a in above)
        for dep in sorted(deps)
        if package_of(dep, packages)
    ]
    assert not naming, "\n".join(naming)


# ---- size: one job a module, a class of few methods ----------------------------------

LONGEST_MODULE = 400  # lines, in tasks/ and verdict/
# One record of every threshold, by design (a field a threshold, each with unit, default,
# range and reason): its length is the number of thresholds, not a module doing two jobs.
ONE_RECORD_MODULES = frozenset({"frictiondisk/verdict/params.py"})
# Modules over the cap, to be split at their seams (none today): an entry leaves once its
# module is short (test_every_module_being_split_is_still_long says when).
LONG_MODULES_BEING_SPLIT: frozenset[str] = frozenset()
MOST_METHODS = 20
# Classes over the cap, to be split at their seams (none today).
LARGE_CLASSES_BEING_SPLIT: frozenset[str] = frozenset()


def module_path(path: Path) -> str:
    return path.relative_to(PACKAGE.parent).as_posix()


def test_no_module_of_tasks_or_verdict_is_over_400_lines():
    long = [
        f"{module_path(path)} ({n} lines)"
        for path in MODULES.values()
        if path.relative_to(PACKAGE).parts[0] in ("tasks", "verdict")
        and (n := len(path.read_text().splitlines())) > LONGEST_MODULE
        and module_path(path) not in LONG_MODULES_BEING_SPLIT
        and module_path(path) not in ONE_RECORD_MODULES
    ]
    assert not long, "\n".join(long)


def test_every_module_being_split_is_still_long():
    """An entry leaves LONG_MODULES_BEING_SPLIT once its module is short (the list only
    shrinks)."""
    short = [
        name
        for name in sorted(LONG_MODULES_BEING_SPLIT)
        if not (PACKAGE.parent / name).exists()
        or len((PACKAGE.parent / name).read_text().splitlines()) <= LONGEST_MODULE
    ]
    assert not short, f"short now: remove from LONG_MODULES_BEING_SPLIT: {short}"


def large_classes(path: Path, limit: int = MOST_METHODS) -> list[tuple[str, int]]:
    """(name, methods) of each class in `path` defining more than `limit` methods."""
    tree = ast.parse(path.read_text(), str(path))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            methods = [
                b for b in node.body if isinstance(b, (ast.FunctionDef, ast.AsyncFunctionDef))
            ]
            if len(methods) > limit:
                found.append((node.name, len(methods)))
    return found


def test_a_large_class_is_found(tmp_path):
    source = tmp_path / "x.py"
    source.write_text("class A:\n" + "".join(f"    def m{i}(self): ...\n" for i in range(21)))
    assert large_classes(source) == [("A", 21)]
    assert large_classes(source, 21) == []


def test_no_class_has_over_20_methods():
    large = [
        f"{module_path(path)}: {name} ({n} methods)"
        for path in MODULES.values()
        for name, n in large_classes(path)
        if name not in LARGE_CLASSES_BEING_SPLIT
    ]
    assert not large, "\n".join(large)
    found = {name for path in MODULES.values() for name, _ in large_classes(path)}
    small = sorted(LARGE_CLASSES_BEING_SPLIT - found)
    assert not small, f"20 methods or fewer now: remove from LARGE_CLASSES_BEING_SPLIT: {small}"


# ---- an outcome's name lives in verdict/outcomes.py -----------------------------------

OUTCOMES_MODULE = "frictiondisk/verdict/outcomes.py"
# Modules that spell an outcome's name instead of importing it from verdict/outcomes.py
# (none today; the list only shrinks).
SPELLING_OUTCOMES_TODAY: frozenset[str] = frozenset()


def test_every_module_spelling_outcomes_still_does():
    """An entry leaves SPELLING_OUTCOMES_TODAY once its module imports the names (the list
    only shrinks)."""
    names = outcome_names()
    clean = [
        name
        for name in sorted(SPELLING_OUTCOMES_TODAY)
        if not (PACKAGE.parent / name).exists()
        or not spelled_outcomes(PACKAGE.parent / name, names)
    ]
    assert not clean, f"no outcome spelled now: remove from SPELLING_OUTCOMES_TODAY: {clean}"


def outcome_names() -> frozenset[str]:
    """The outcome names: every string constant of verdict/outcomes.py that names one."""
    from frictiondisk.verdict.outcomes import OUTCOMES

    return frozenset(OUTCOMES)


def spelled_outcomes(path: Path, names: frozenset[str]) -> list[str]:
    """Each string literal in `path` that is an outcome's name, with its line."""
    tree = ast.parse(path.read_text(), str(path))
    return [
        f"{path.name}:{node.lineno} {node.value!r}"
        for node in ast.walk(tree)
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value in names
    ]


def test_a_spelled_outcome_is_found(tmp_path):
    source = tmp_path / "x.py"
    source.write_text('"""stick or not."""\nA = "stick"\nB = f"{A} stick"\n')
    assert spelled_outcomes(source, frozenset({"stick"})) == ["x.py:2 'stick'"]


def test_no_outcome_name_is_spelled_outside_verdict_outcomes():
    names = outcome_names()
    spelled = [
        line
        for path in MODULES.values()
        if module_path(path) not in SPELLING_OUTCOMES_TODAY | {OUTCOMES_MODULE}
        for line in spelled_outcomes(path, names)
    ]
    assert not spelled, "\n".join(spelled)


# ---- the package's text says what the code does, not which ticket made it --------------

ISSUE_REFERENCE = re.compile(r"\b[Ii]ssues? #?\d")


def test_an_issue_reference_is_found():
    assert ISSUE_REFERENCE.search("the pin (issue 14): a bound")
    assert ISSUE_REFERENCE.search("issues 5 and 12")
    assert not ISSUE_REFERENCE.search("an issue of units; tissue 3")


def test_no_issue_number_in_the_package():
    found = [
        f"{module_path(path)}:{k} {line.strip()}"
        for path in sorted(PACKAGE.rglob("*"))
        if path.is_file() and path.suffix in (".py", ".json", ".csv", ".md", ".txt")
        for k, line in enumerate(path.read_text().splitlines(), 1)
        if ISSUE_REFERENCE.search(line)
    ]
    assert not found, "\n".join(found)
