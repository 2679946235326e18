"""Which keys each scene uses (docs/model.md section 5), so that a key given to a scene that
does nothing with it is refused, naming the key and the scene, instead of passing silently.

A pin is a point mass on one contact at its centre: it has no spin (params.J_s, beta_b,
phidot0) and no contact layout (contact.ring_radius, inner_radius, outer_radius,
positions, weights). A disk uses the layout keys of its own `contact.layout` only. A null
value counts as not given. Plain data in, plain data out: scene.py validates with it.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

from pydantic_core import PydanticCustomError

SPIN_KEYS = ("params.J_s", "params.beta_b", "params.phidot0")
LAYOUT_KEYS = {
    "ring": ("contact.ring_radius",),
    "annulus": ("contact.inner_radius", "contact.outer_radius"),
    "points": ("contact.positions", "contact.weights"),
}
_PIN_HAS_NO_SPIN = (
    "a pin has no spin (J_s, beta_b and phidot0 are a slave disk's keys); remove it, "
    "or use scene: disk"
)
_PIN_HAS_NO_LAYOUT = (
    "a pin has one contact, at its centre (ring_radius, inner_radius, outer_radius, "
    "positions and weights place a disk's contacts); remove it, or use scene: disk"
)
_PIN_LAYOUT = "a pin has exactly one contact, at its centre; use layout 'ring'"


# What unused_keys answers, made once (read-only): a scene's validation, its canonical form
# and every override ask.
_PIN_UNUSED: Mapping[str, str] = MappingProxyType(
    dict.fromkeys(SPIN_KEYS, _PIN_HAS_NO_SPIN)
    | {key: _PIN_HAS_NO_LAYOUT for keys in LAYOUT_KEYS.values() for key in keys}
)
_DISK_UNUSED: dict[str, Mapping[str, str]] = {
    layout: MappingProxyType(
        {
            key: f"only used by layout {owner!r}"
            for owner, keys in LAYOUT_KEYS.items()
            if owner != layout
            for key in keys
        }
    )
    for layout in LAYOUT_KEYS
}
_NONE: Mapping[str, str] = MappingProxyType({})
_PARTS = {key: tuple(key.split(".")) for key in _PIN_UNUSED}  # (section, name) of each


def unused_keys(scene: Any, layout: Any) -> Mapping[str, str]:
    """The dotted keys that scene `scene` with contact.layout `layout` does not use, each
    with why (read-only); none for an unknown scene, and no layout keys of a disk with an
    unknown layout (field validation reports those)."""
    if scene == "pin":
        return _PIN_UNUSED
    if scene == "disk":
        return _DISK_UNUSED.get(layout, _NONE)
    return _NONE


def unused_key_problem(key: str, scene: Any, layout: Any) -> str | None:
    """What is wrong with naming `key` (varying, sampling or mapping it) in a campaign on
    the scene `scene`; None if the scene uses it."""
    why = unused_keys(scene, layout).get(key)
    if why is None:
        return None
    if scene == "pin":
        return f"not allowed for scene {scene!r}: {why}"
    return f"not allowed with contact.layout {layout!r}: {why}"


def without_unused(
    data: Mapping[str, Any],
) -> tuple[Mapping[str, Any], list[tuple[tuple[str, str], PydanticCustomError]]]:
    """`data` (a scene as given) without the keys its scene does not use, and one error
    per key removed (`(loc, error)`, as `schema.merged` takes them). A pin's layout other
    than 'ring' is one of them, so that its annulus or points keys are not also asked for."""
    scene = data.get("scene")
    contact = data.get("contact")
    layout = contact.get("layout", "ring") if isinstance(contact, Mapping) else "ring"
    problems = []
    if scene == "pin" and layout in LAYOUT_KEYS and layout != "ring":
        problems.append(
            (("contact", "layout"), _error("contact.layout", layout, scene, _PIN_LAYOUT))
        )
        data = _without(data, "contact.layout")
    for key, why in unused_keys(scene, layout).items():
        section, name = _PARTS[key]
        given = data.get(section)
        # a dict first: the Mapping check alone costs more than the rest of the loop
        if (type(given) is dict or isinstance(given, Mapping)) and given.get(name) is not None:
            problems.append(((section, name), _error(key, given[name], scene, why)))
            data = _without(data, key)
    return data, problems


def drop_unused(data: dict[str, Any], scene: Any, layout: Any) -> dict[str, Any]:
    """`data` (a full model dump) without the keys `scene` and `layout` do not use, in place."""
    for key in unused_keys(scene, layout):
        section, name = _PARTS[key]
        data[section].pop(name, None)
    return data


def _without(data: Mapping[str, Any], key: str) -> dict[str, Any]:
    section, name = key.split(".")
    return {**data, section: {k: v for k, v in data[section].items() if k != name}}


def _error(key: str, value: Any, scene: Any, why: str) -> PydanticCustomError:
    """The error of one unused key: a scene rule on a pin, a layout rule on a disk (the
    messages of frictiondisk.model.schema.error_lines)."""
    if scene == "pin":
        return PydanticCustomError("scene_rule", why, {"path": key, "value": value, "scene": scene})
    return PydanticCustomError("layout_rule", why, {"path": key, "value": value})
