"""Every campaign key with its unit, default and description, read from the task specs the
registry lists: `reference_markdown()` is docs/reference.md (scene keys first), and
`annotated_task()` is what `frictiondisk show-defaults --task` prints."""

from __future__ import annotations

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from frictiondisk.model.axes import Linspace
from frictiondisk.model.reference import (
    annotated,
    default_of,
    described,
    first_line,
    jsonable,
    scalar,
    scene_table,
    table,
)
from frictiondisk.model.schema import is_model, plain_annotation, requirement
from frictiondisk.tasks.campaign import CampaignFile
from frictiondisk.tasks.campaign_file import SCENE_KEYS
from frictiondisk.tasks.registry import TASKS

__all__ = ["annotated_task", "reference_markdown"]


def annotated_task(task: str) -> str:
    """The keys of a campaign task as YAML with their defaults and descriptions; keys
    without a default value (required, or not set: null or empty) are commented out and
    marked `required` or `optional`, so that the block loads once the required are filled."""
    model = TASKS[task].spec
    lines = [f"{task}:  # {CampaignFile.model_fields[task].description}"]
    for name, info in model.model_fields.items():
        default = default_of(info)
        note = f"  # {described(info)}"
        if default is PydanticUndefined or default is None or default == {}:
            what = "required" if default is PydanticUndefined else "optional"
            lines.append(f"  # {name}: ({what}){note}; allowed: {requirement(info)}")
        elif is_model(plain_annotation(info.annotation)) and isinstance(default, BaseModel):
            lines.append(f"  {name}:{note}")
            lines += annotated(type(default), default.model_dump(mode="json"), 4)
        else:
            lines.append(f"  {name}: {scalar(jsonable(default))}{note}")
    return "\n".join(lines)


def reference_markdown() -> str:
    """docs/reference.md: a table of every scene and campaign key."""
    leaves = tuple(model for entry in TASKS.values() for _, _, model in entry.reference_tables)
    parts = [
        "# Reference: scene and campaign keys",
        "",
        "Generated from the schemas (frictiondisk/model/scene.py, frictiondisk/tasks/*/spec.py)",
        "by `frictiondisk.tasks.reference.reference_markdown()`; do not edit by hand. Units are",
        "SI, `1` is dimensionless. `frictiondisk show-defaults` prints the same as YAML.",
        "",
        "## Scene keys",
        "",
        "A scene file, and the base scene of a campaign file. A scene takes only the keys it",
        "uses: a pin refuses the keys marked *disk only* (it has no spin and one contact, at",
        "its centre), and a disk refuses the keys of a `contact.layout` other than its own.",
        "",
        *scene_table(),
        "",
        "## Campaign keys",
        "",
        "A campaign file holds `name`, the scene keys above and exactly one task.",
        "",
        *table(CampaignFile, "", skip=(*SCENE_KEYS, *TASKS)),
    ]
    for task, entry in TASKS.items():
        model = entry.spec
        parts += [
            "",
            f"### `{task}`",
            "",
            first_line(model),
            "",
            *table(model, f"{task}.", (), leaves),
        ]
    parts += [
        "",
        "### Values of a varied key",
        "",
        "A list of numbers, or a mapping (numpy.linspace):",
        "",
        *table(Linspace, "<key>."),
    ]
    for entry in TASKS.values():
        for title, intro, model in entry.reference_tables:
            parts += ["", f"### {title}", "", intro, "", *table(model, "<key>.", (), leaves)]
    return "\n".join(parts) + "\n"
