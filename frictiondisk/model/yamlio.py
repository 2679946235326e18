"""Strict YAML for configuration files: YAML 1.2 scalars, no duplicate keys, clear errors.

PyYAML implements YAML 1.1, where `1e-4` is a string, `no` is False, `010` is 8 and a
repeated key silently overwrites the first one. `StrictLoader` fixes all of these so
that what a user writes is what the validator sees.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from os import PathLike
from typing import Any

import yaml

__all__ = [
    "ConfigError",
    "StrictDumper",
    "StrictLoader",
    "dump_yaml",
    "load_yaml_file",
    "load_yaml_text",
]


# What an error may say, whatever the input: at most MAX_PROBLEMS lines (the rest counted)
# of at most MAX_PROBLEM_CHARS each (a huge key or value cut in its middle).
MAX_PROBLEMS = 12
MAX_PROBLEM_CHARS = 300


class ConfigError(ValueError):
    """Invalid configuration. `problems` holds one message per problem, at most
    MAX_PROBLEMS (a last line counts the rest) of at most MAX_PROBLEM_CHARS each; `str()`
    joins them."""

    def __init__(self, problems: str | Iterable[str], source: str | None = None) -> None:
        problems = [problems] if isinstance(problems, str) else list(problems)
        self.problems: list[str] = bounded(problems)
        self.source = source  # file name or other origin, if known
        super().__init__("\n".join(self.problems))


def bounded(problems: list[str]) -> list[str]:
    """`problems` cut to MAX_PROBLEMS lines (the last one says how many more there are) of
    at most MAX_PROBLEM_CHARS each, one line each."""
    shown = [_short(" ".join(str(problem).split("\n"))) for problem in problems]
    if len(shown) > MAX_PROBLEMS:
        more = len(shown) - (MAX_PROBLEMS - 1)
        shown = [*shown[: MAX_PROBLEMS - 1], f"... and {more} more problems"]
    return shown


def _short(text: str) -> str:
    if len(text) <= MAX_PROBLEM_CHARS:
        return text
    half = (MAX_PROBLEM_CHARS - 25) // 2
    return f"{text[:half]} ...({len(text) - 2 * half} characters)... {text[-half:]}"


# YAML 1.2 core schema (https://yaml.org/spec/1.2.2/#1032-tag-resolution), plus the plain
# words inf/nan in any case so that the validator can reject them as non-finite.
_RESOLVERS = (
    ("tag:yaml.org,2002:null", r"^(?:~|null|Null|NULL|)$", ["~", "n", "N", ""]),
    ("tag:yaml.org,2002:bool", r"^(?:true|True|TRUE|false|False|FALSE)$", list("tTfF")),
    ("tag:yaml.org,2002:int", r"^[-+]?[0-9]+$", list("-+0123456789")),
    (
        "tag:yaml.org,2002:float",
        r"""^(?:[-+]?(?:[0-9]+\.[0-9]*(?:[eE][-+]?[0-9]+)?
                      |\.[0-9]+(?:[eE][-+]?[0-9]+)?
                      |[0-9]+[eE][-+]?[0-9]+)
               |[-+]?\.?(?i:inf|nan))$""",
        list("-+.0123456789iInN"),
    ),
)


class _TooDeep(ConfigError):
    """Nesting beyond MAX_DEPTH (load_yaml_text prefixes the source)."""


# Bounds on what a configuration file may be: a scene or campaign needs a depth
# of 4 and a few kB; these stop a hostile file long before recursion or memory run out.
MAX_DEPTH = 32  # nested mappings/lists
MAX_FILE_BYTES = 4 * 1024 * 1024
# values that aliases (*name) may add to a file by repeating anchored ones: a campaign
# needs none or a few dozen; an "alias bomb" of a few lines adds billions
MAX_ALIAS_VALUES = 100_000


class StrictLoader(yaml.SafeLoader):
    """SafeLoader with YAML 1.2 core-schema scalars that rejects duplicate mapping keys.

    Booleans are only true/false, integers are decimal, floats include exponent forms
    (`1e-4`) and inf/nan words; YAML 1.1 timestamps, sexagesimals and `<<` merges are
    plain strings. Nesting deeper than MAX_DEPTH is a ConfigError, raised while composing
    (PyYAML's composer recurses once per level).
    """

    yaml_implicit_resolvers: dict = {}
    _depth = 0

    def compose_node(self, parent: yaml.Node | None, index: Any) -> yaml.Node:
        self._depth += 1
        try:
            if self._depth > MAX_DEPTH:
                mark = self.peek_event().start_mark
                raise _TooDeep(
                    f"line {mark.line + 1}, column {mark.column + 1}: nested more than "
                    f"{MAX_DEPTH} levels deep; a configuration needs at most a few"
                )
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1

    def construct_document(self, node: yaml.Node) -> Any:
        problems = _alias_problems(node) or _duplicate_keys(node, (), set())
        if problems:
            raise ConfigError(problems)
        return super().construct_document(node)

    def construct_yaml_int(self, node: yaml.ScalarNode) -> int:
        """Decimal only: YAML 1.2 reads `010` as 10, not octal 8."""
        return int(self.construct_scalar(node))


class StrictDumper(yaml.SafeDumper):
    """SafeDumper that quotes every string `StrictLoader` would read as something else."""

    yaml_implicit_resolvers: dict = {}


for _tag, _regexp, _first in _RESOLVERS:
    for _cls in (StrictLoader, StrictDumper):
        _cls.add_implicit_resolver(_tag, re.compile(_regexp, re.X), _first)
StrictLoader.add_constructor("tag:yaml.org,2002:int", StrictLoader.construct_yaml_int)


def _alias_problems(root: yaml.Node) -> list[str]:
    """A message if aliases repeat more than MAX_ALIAS_VALUES values, or one refers to a
    node that holds it (a recursive alias); [] otherwise. Counts without expanding."""
    size: dict[int, int] = {}  # values in a node's expansion, itself included
    distinct: set[int] = set()
    stack: list[tuple[yaml.Node, bool]] = [(root, False)]
    open_nodes: set[int] = set()
    while stack:
        node, children_done = stack.pop()
        if children_done:
            open_nodes.discard(id(node))
            size[id(node)] = 1 + sum(size[id(child)] for child in _children(node))
            continue
        if id(node) in size:
            continue
        if id(node) in open_nodes:
            mark = node.start_mark
            return [
                f"line {mark.line + 1}, column {mark.column + 1}: an alias refers to a node "
                "that holds it (a recursive alias)"
            ]
        open_nodes.add(id(node))
        distinct.add(id(node))
        stack.append((node, True))
        stack += [(child, False) for child in _children(node) if id(child) not in size]
    repeated = size[id(root)] - len(distinct)
    if repeated <= MAX_ALIAS_VALUES:
        return []
    path, node = [], root  # down the mappings to the key whose value holds the most
    while isinstance(node, yaml.MappingNode) and node.value:
        key, node = max(node.value, key=lambda pair: size[id(pair[1])])
        path.append(str(key.value) if isinstance(key, yaml.ScalarNode) else "?")
    mark = node.start_mark
    return [
        f"{'.'.join(path) or '(top level)'} (line {mark.line + 1}): aliases (*name) repeat "
        f"more than {MAX_ALIAS_VALUES} values ({repeated:.3g}): not a configuration file"
    ]


def _children(node: yaml.Node) -> list[yaml.Node]:
    if isinstance(node, yaml.MappingNode):
        return [item for pair in node.value for item in pair]
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    return []


def _duplicate_keys(node: yaml.Node, path: tuple[str, ...], seen: set[int]) -> list[str]:
    """Messages `a.b: duplicate key (lines 3 and 5)` for every repeated key under `node`."""
    if id(node) in seen:  # an alias: already checked
        return []
    seen.add(id(node))
    problems: list[str] = []
    if isinstance(node, yaml.MappingNode):
        first_line: dict[tuple[str, Any], int] = {}
        for key_node, value_node in node.value:
            name = str(key_node.value) if isinstance(key_node, yaml.ScalarNode) else "?"
            if isinstance(key_node, yaml.ScalarNode):
                key = (key_node.tag, key_node.value)
                line = key_node.start_mark.line + 1
                if key in first_line:
                    dotted = ".".join((*path, name))
                    problems.append(f"{dotted}: duplicate key (lines {first_line[key]} and {line})")
                else:
                    first_line[key] = line
            problems += _duplicate_keys(value_node, (*path, name), seen)
    elif isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            problems += _duplicate_keys(item, (*path, str(index)), seen)
    return problems


def load_yaml_text(text: str, source: str = "<string>") -> Any:
    """Parse one YAML document with `StrictLoader`; any problem is a `ConfigError`."""
    try:
        return yaml.load(text, Loader=StrictLoader)
    except _TooDeep as err:
        raise ConfigError([f"{source}, {problem}" for problem in err.problems], source) from None
    except ConfigError as err:
        raise ConfigError(err.problems, source) from None
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        where = f"{source}, line {mark.line + 1}, column {mark.column + 1}" if mark else source
        what = "; ".join(p for p in (err.context, err.problem) if p)
        raise ConfigError(f"{where}: invalid YAML: {what}", source) from None
    except yaml.YAMLError as err:
        raise ConfigError(f"{source}: YAML error: {err}", source) from None


def read_text_file(path: str | PathLike[str]) -> str:
    """The UTF-8 text of a configuration file; an unreadable file is a `ConfigError`."""
    try:
        with open(path, encoding="utf-8") as stream:
            text = stream.read(MAX_FILE_BYTES + 1)
    except (OSError, UnicodeDecodeError) as err:
        raise ConfigError(f"{path}: cannot read: {err}", str(path)) from None
    if len(text) > MAX_FILE_BYTES:
        raise ConfigError(
            f"{path}: larger than {MAX_FILE_BYTES // (1024 * 1024)} MiB: not a configuration file",
            str(path),
        )
    return text


def load_yaml_file(path: str | PathLike[str]) -> Any:
    """Read a UTF-8 YAML file with `load_yaml_text`; unreadable files are a `ConfigError`."""
    return load_yaml_text(read_text_file(path), source=str(path))


def dump_yaml(data: Any) -> str:
    """Block-style YAML, keys sorted, that `load_yaml_text` reads back to `data`."""
    return yaml.dump(data, Dumper=StrictDumper, sort_keys=True, default_flow_style=False)
