"""`--set KEY=VALUE` overrides of a scene: parsing and setting dotted keys in plain data."""

from __future__ import annotations

import re
import reprlib
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from frictiondisk.model.schema import kind_of as _kind
from frictiondisk.model.schema import show as _show
from frictiondisk.model.yamlio import ConfigError, load_yaml_text

MAX_KEY_PARTS = 8  # parts of a dotted --set key (the deepest scene key has 3)

_repr = reprlib.Repr()
_repr.maxstring = _repr.maxother = 40
_short = _repr.repr

DOTTED_KEY = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z_][A-Za-z0-9_]*)*")


def parse_override(text: str, source: str) -> tuple[str, Any]:
    """`"params.mu=0.13"` -> ("params.mu", 0.13); VALUE is read as strict YAML."""
    key, sep, value = text.partition("=")
    key = key.strip()
    if key.count(".") >= MAX_KEY_PARTS:
        raise ConfigError(
            f"--set {_short(text)}: key has {key.count('.') + 1} dotted parts: "
            f"allowed at most {MAX_KEY_PARTS} (scene keys have 2 or 3, e.g. params.mu)",
            source,
        )
    if not sep or not DOTTED_KEY.fullmatch(key):
        raise ConfigError(
            f"--set {text!r}: malformed override: expected KEY=VALUE with a dotted KEY, "
            "e.g. params.mu=0.13",
            source,
        )
    shown = text if len(text) <= 80 else text[:60] + "..."
    return key, load_yaml_text(value, source=f"--set {shown}")


def apply_overrides(data: Any, pairs: Iterable[tuple[str, Any]], source: str) -> Any:
    """Copy of `data` with each dotted key set to its value."""
    for key, value in pairs:
        if isinstance(key, str) and key.count(".") >= MAX_KEY_PARTS:
            raise ConfigError(
                f"{_short(key)}: override key has more than {MAX_KEY_PARTS} dotted parts",
                source,
            )
        if not isinstance(key, str) or not DOTTED_KEY.fullmatch(key):
            raise ConfigError(
                f"{key!r}: malformed override key: expected a dotted key, e.g. params.mu", source
            )
        data = _set_dotted(data, key.split("."), value, (), source)
    return data


def _set_dotted(
    data: Any, keys: Sequence[str], value: Any, done: tuple[str, ...], source: str
) -> dict[str, Any]:
    """Copy of mapping `data` with data[k0][k1]... = value; a null section becomes {}."""
    data = {} if data is None else data
    if not isinstance(data, Mapping):
        target = ".".join((*done, *keys))
        raise ConfigError(
            f"{_dotted(done)}: cannot set {target}: expected a mapping, "
            f"got {_kind(data)} {_show(data)}",
            source,
        )
    head, *rest = keys
    out = dict(data)
    out[head] = _set_dotted(out.get(head), rest, value, (*done, head), source) if rest else value
    return out


def _dotted(loc: tuple[str, ...]) -> str:
    return ".".join(loc) or "(top level)"
