"""The schema of a whole campaign file (`campaign_file_model`): a `name`, the base scene's
keys and one section per registered task, of which a file gives exactly one. Built from
the registry, so a new task's section is known to the loader, the messages and
docs/reference.md without an edit here."""

from __future__ import annotations

from typing import Any

from pydantic import create_model

from frictiondisk.model.schema import Spec, field

SCENE_KEYS = ("scene", "params", "contact", "numerics")
_SCENE_DOC = "the base scene's {} (validated as in a scene file; see the scene keys)"


class CampaignFileBase(Spec):
    """A campaign file: a `name`, the base scene's keys and exactly one task."""

    name: str = field(
        ...,
        None,
        "the campaign's name",
        "text of letters, digits, _ and - only",
        pattern=r"^[A-Za-z0-9_-]+$",
    )
    scene: Any = field(None, None, _SCENE_DOC.format("scene, pin or disk"))
    params: Any = field(None, None, _SCENE_DOC.format("params"))
    contact: Any = field(None, None, _SCENE_DOC.format("contact"))
    numerics: Any = field(None, None, _SCENE_DOC.format("numerics"))


def campaign_file_model(entries) -> type[Spec]:
    """The campaign file's schema: CampaignFileBase plus one optional section per entry
    (its spec, described by the entry's summary), in the registry's order."""
    sections = {
        entry.name: (entry.spec, field(None, None, f"task: {entry.summary}")) for entry in entries
    }
    return create_model(
        "CampaignFile", __base__=CampaignFileBase, __doc__=CampaignFileBase.__doc__, **sections
    )
