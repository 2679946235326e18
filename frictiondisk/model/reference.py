"""Every scene and campaign key with its unit, default and description, read from the schemas:
`reference_markdown()` is docs/reference.md, `annotated_scene()` and `annotated_task()` are
what `frictiondisk show-defaults` prints."""

from __future__ import annotations

from typing import Any

import yaml
from pydantic import BaseModel
from pydantic.fields import FieldInfo
from pydantic_core import PydanticUndefined

from frictiondisk.model.axes import Linspace
from frictiondisk.model.campaign_spec import TASKS, CampaignFile, Distribution
from frictiondisk.model.scene import SceneConfig, scene_from_dict
from frictiondisk.model.scene_keys import unused_keys
from frictiondisk.model.schema import _is_model, _strip, extra_of, requirement
from frictiondisk.model.yamlio import StrictDumper

__all__ = ["annotated_scene", "annotated_task", "reference_markdown"]

_DISK_ONLY = unused_keys("pin", "ring")  # the scene keys a pin refuses


def annotated_scene(scene: str) -> str:
    """The default scene `scene` as YAML, each key with a comment `# description [unit]`;
    a loadable scene file."""
    data = scene_from_dict({"scene": scene}).canonical()
    return "\n".join(_annotated(SceneConfig, data, 0))


def annotated_task(task: str) -> str:
    """The keys of a campaign task as YAML with their defaults and descriptions; keys
    without a default value (required, or not set: null or empty) are commented out and
    marked `required` or `optional`, so that the block loads once the required are filled."""
    model = TASKS[task]
    lines = [f"{task}:  # {CampaignFile.model_fields[task].description}"]
    for name, info in model.model_fields.items():
        default = _default(info)
        note = f"  # {_doc(info)}"
        if default is PydanticUndefined or default is None or default == {}:
            what = "required" if default is PydanticUndefined else "optional"
            lines.append(f"  # {name}: ({what}){note}; allowed: {requirement(info)}")
        elif _is_model(_strip(info.annotation)) and isinstance(default, BaseModel):
            lines.append(f"  {name}:{note}")
            lines += _annotated(type(default), default.model_dump(mode="json"), 4)
        else:
            lines.append(f"  {name}: {_scalar(_jsonable(default))}{note}")
    return "\n".join(lines)


def _annotated(model: type[BaseModel], data: dict[str, Any], indent: int) -> list[str]:
    lines = []
    pad = " " * indent
    for name in sorted(data):
        info = model.model_fields[name]
        inner = _strip(info.annotation)
        if _is_model(inner) and isinstance(data[name], dict):
            lines.append(f"{pad}{name}:  # {_doc(info)}")
            lines += _annotated(inner, data[name], indent + 2)
        else:
            lines.append(f"{pad}{name}: {_scalar(data[name])}  # {_doc(info)}")
    return lines


def reference_markdown() -> str:
    """docs/reference.md: a table of every scene and campaign key."""
    parts = [
        "# Reference: scene and campaign keys",
        "",
        "Generated from the schemas (frictiondisk/model/scene.py, campaign_spec.py) by",
        "`frictiondisk.model.reference.reference_markdown()`; do not edit by hand. Units are SI,",
        "`1` is dimensionless. `frictiondisk show-defaults` prints the same as YAML.",
        "",
        "## Scene keys",
        "",
        "A scene file, and the base scene of a campaign file. A scene takes only the keys it",
        "uses: a pin refuses the keys marked *disk only* (it has no spin and one contact, at",
        "its centre), and a disk refuses the keys of a `contact.layout` other than its own.",
        "",
        *_table(SceneConfig, ""),
        "",
        "## Campaign keys",
        "",
        "A campaign file holds `name`, the scene keys above and exactly one task.",
        "",
        *_table(CampaignFile, "", skip=("scene", "params", "contact", "numerics", *TASKS)),
    ]
    for task, model in TASKS.items():
        parts += ["", f"### `{task}`", "", _first_line(model), "", *_table(model, f"{task}.")]
    parts += [
        "",
        "### Values of a varied key",
        "",
        "A list of numbers, or a mapping (numpy.linspace):",
        "",
        *_table(Linspace, "<key>."),
        "",
        "### A sampled initial-state key (`basin.sample.<key>`)",
        "",
        "Exactly one of:",
        "",
        *_table(Distribution, "<key>."),
    ]
    return "\n".join(parts) + "\n"


def _table(model: type[BaseModel], prefix: str, skip: tuple[str, ...] = ()) -> list[str]:
    rows = ["| key | unit | default | description; allowed |", "| --- | --- | --- | --- |"]
    return rows + _rows(model, prefix, skip)


def _rows(model: type[BaseModel], prefix: str, skip: tuple[str, ...] = ()) -> list[str]:
    rows = []
    for name, info in model.model_fields.items():
        if name in skip:
            continue
        inner = _strip(info.annotation)
        if _is_model(inner) and inner not in (Distribution,) and prefix.count(".") < 3:
            if inner is not CampaignFile:
                rows += _rows(inner, f"{prefix}{name}.")
                continue
        default = _default(info)
        shown = "required" if default is PydanticUndefined else _scalar(_jsonable(default))
        unit = extra_of(info).get("unit") or ""
        doc = _doc(info).removesuffix(f" [{unit}]")  # the unit has its own column
        text = f"{doc}; {requirement(info)}".replace("|", "\\|")
        if model is not CampaignFile and f"{prefix}{name}" in _DISK_ONLY:
            text = f"*disk only*: {text}"
        rows.append(f"| `{prefix}{name}` | {unit} | `{shown}` | {text} |")
    return rows


def _default(info: FieldInfo) -> Any:
    if info.default_factory is not None:
        return info.default_factory()
    return info.default


def _jsonable(value: Any) -> Any:
    if isinstance(value, BaseModel):
        return value.model_dump(mode="json")
    if isinstance(value, tuple):
        return list(value)
    return value


def _doc(info: FieldInfo) -> str:
    return " ".join((info.description or "").split())


def _first_line(model: type[BaseModel]) -> str:
    return " ".join((model.__doc__ or "").strip().split("\n\n")[0].split())


def _scalar(value: Any) -> str:
    """`value` in flow-style strict YAML, on one line."""
    text = yaml.dump(value, Dumper=StrictDumper, default_flow_style=True, width=10**9)
    return text.removesuffix("\n").removesuffix("\n...").strip()
