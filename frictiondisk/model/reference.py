"""Every scene key with its unit, default and description, read from the schema, and the
helpers that turn any schema into those lines: `annotated_scene()` is what `frictiondisk
show-defaults` prints, `scene_table()` the scene part of docs/reference.md (the campaign
part, and the whole file, are frictiondisk.tasks.reference)."""

from __future__ import annotations

from typing import Any

import yaml
from pydantic import BaseModel
from pydantic.fields import FieldInfo
from pydantic_core import PydanticUndefined

from frictiondisk.model.scene import SceneConfig, scene_from_dict
from frictiondisk.model.scene_keys import unused_keys
from frictiondisk.model.schema import extra_of, is_model, plain_annotation, requirement
from frictiondisk.model.yamlio import StrictDumper

__all__ = [
    "annotated",
    "annotated_scene",
    "default_of",
    "described",
    "first_line",
    "jsonable",
    "scalar",
    "table",
]

_DISK_ONLY = unused_keys("pin", "ring")  # the scene keys a pin refuses


def annotated_scene(scene: str) -> str:
    """The default scene `scene` as YAML, each key with a comment `# description [unit]`;
    a loadable scene file."""
    data = scene_from_dict({"scene": scene}).canonical()
    return "\n".join(annotated(SceneConfig, data, 0))


def scene_table() -> list[str]:
    """The table of every scene key (docs/reference.md), disk-only keys marked."""
    return table(SceneConfig, "", disk_only=_DISK_ONLY)


def annotated(model: type[BaseModel], data: dict[str, Any], indent: int) -> list[str]:
    """`data` (a canonical dict of `model`) as YAML lines, each key commented with its
    description and unit."""
    lines = []
    pad = " " * indent
    for name in sorted(data):
        info = model.model_fields[name]
        inner = plain_annotation(info.annotation)
        if is_model(inner) and isinstance(data[name], dict):
            lines.append(f"{pad}{name}:  # {described(info)}")
            lines += annotated(inner, data[name], indent + 2)
        else:
            lines.append(f"{pad}{name}: {scalar(data[name])}  # {described(info)}")
    return lines


def table(
    model: type[BaseModel],
    prefix: str,
    skip: tuple[str, ...] = (),
    leaves: tuple[type, ...] = (),
    disk_only: frozenset[str] | set[str] = frozenset(),
) -> list[str]:
    """A markdown table of `model`'s keys under `prefix`: nested models expanded (up to
    three levels), except `skip` (not listed) and `leaves` (one row each)."""
    rows = ["| key | unit | default | description; allowed |", "| --- | --- | --- | --- |"]
    return rows + _rows(model, prefix, skip, leaves, disk_only)


def _rows(model, prefix, skip, leaves, disk_only) -> list[str]:
    rows = []
    for name, info in model.model_fields.items():
        if name in skip:
            continue
        inner = plain_annotation(info.annotation)
        if is_model(inner) and inner not in leaves and prefix.count(".") < 3:
            rows += _rows(inner, f"{prefix}{name}.", (), leaves, disk_only)
            continue
        default = default_of(info)
        shown = "required" if default is PydanticUndefined else scalar(jsonable(default))
        unit = extra_of(info).get("unit") or ""
        doc = described(info).removesuffix(f" [{unit}]")  # the unit has its own column
        text = f"{doc}; {requirement(info)}".replace("|", "\\|")
        if f"{prefix}{name}" in disk_only:
            text = f"*disk only*: {text}"
        rows.append(f"| `{prefix}{name}` | {unit} | `{shown}` | {text} |")
    return rows


def default_of(info: FieldInfo) -> Any:
    """A field's default value (its factory's, if it has one)."""
    if info.default_factory is not None:
        return info.default_factory()
    return info.default


def jsonable(value: Any) -> Any:
    if isinstance(value, BaseModel):
        return value.model_dump(mode="json")
    if isinstance(value, tuple):
        return list(value)
    return value


def described(info: FieldInfo) -> str:
    """A field's description on one line."""
    return " ".join((info.description or "").split())


def first_line(model: type[BaseModel]) -> str:
    """The first paragraph of a model's docstring, on one line."""
    return " ".join((model.__doc__ or "").strip().split("\n\n")[0].split())


def scalar(value: Any) -> str:
    """`value` in flow-style strict YAML, on one line."""
    text = yaml.dump(value, Dumper=StrictDumper, default_flow_style=True, width=10**9)
    return text.removesuffix("\n").removesuffix("\n...").strip()
