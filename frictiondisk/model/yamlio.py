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


class ConfigError(ValueError):
    """Invalid configuration. `problems` holds one message per problem; `str()` joins them."""

    def __init__(self, problems: str | Iterable[str], source: str | None = None) -> None:
        self.problems: list[str] = [problems] if isinstance(problems, str) else list(problems)
        self.source = source  # file name or other origin, if known
        super().__init__("\n".join(self.problems))


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
        problems = _duplicate_keys(node, (), set())
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
