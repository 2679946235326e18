"""Scene keys a campaign varies: checked against the scene schema (a numeric key) and,
value by value, against the base scene (each value must give a valid scene)."""

from __future__ import annotations

import difflib
import functools
import math
import types
from typing import Any, Union, get_args, get_origin

from pydantic.fields import FieldInfo

from frictiondisk.model.overrides import DOTTED_KEY
from frictiondisk.model.scene import MAX_HORIZON, ConfigError, SceneConfig
from frictiondisk.model.scene_keys import unused_key_problem
from frictiondisk.model.schema import is_model, requirement
from frictiondisk.model.schema import show as _show

# Initial-state keys a basin samples or maps (params.phidot0: disk only, scene_keys.py).
INITIAL_STATE_KEYS = ("params.x0", "params.y0", "params.vx0", "params.vy0", "params.phidot0")


def key_problem(key: str, base: SceneConfig | None = None) -> str | None:
    """What is wrong with varying dotted scene `key` (None: a numeric scene key that the
    scene `base` uses, if given)."""
    if not DOTTED_KEY.fullmatch(key):
        return "not a dotted scene key, e.g. params.x_ms"
    model: Any = SceneConfig
    parts = key.split(".")
    for depth, part in enumerate(parts):
        section = ".".join(parts[:depth])
        if not is_model(model):
            return f"unknown scene key; {section} is a value, not a section"
        fields = model.model_fields
        if part not in fields:
            under = f"under {section}" if section else "at top level"
            text = f"unknown scene key; allowed keys {under}: {', '.join(fields)}"
            close = difflib.get_close_matches(part, list(fields), n=1)
            return text + (f" (did you mean {close[0]!r}?)" if close else "")
        model = fields[part].annotation
    if is_model(model):
        keys = ", ".join(model.model_fields)
        return f"a section, not a number: vary one of its keys: {keys}"
    info = _scene_field(key)
    if not _field_types(info) <= {int, float}:
        return (
            f"not a numeric scene key (it must be {requirement(info)}); only numbers can be varied"
        )
    return None if base is None else unused_key_problem(key, base.scene, base.contact.layout)


def value_problems(base: SceneConfig, key: str, value: float) -> list[str]:
    """Problems of the scene `base` with `key` = `value` (without the key's path)."""
    try:
        base.with_overrides({key: scene_value(key, value)})
    except ConfigError as err:
        return [
            p.removesuffix(f" (from override {key})").removeprefix(f"{key}: ") for p in err.problems
        ]
    return []


def scene_value(key: str, value: float) -> float | int:
    """`value` as the scene field `key` takes it: a whole float becomes an int for int keys."""
    if _int_key(key) and float(value).is_integer():
        return int(value)
    return value


@functools.cache
def _int_key(key: str) -> bool:
    """Whether the scene field `key` takes integers only (the schema's: fixed)."""
    return _field_types(_scene_field(key)) == {int}


def initial_state_problem(key: str, base: SceneConfig | None) -> str | None:
    """What is wrong with sampling or mapping `key` (None: an initial-state key)."""
    if key not in INITIAL_STATE_KEYS:
        return f"not an initial-state key; allowed: {', '.join(INITIAL_STATE_KEYS)}"
    return None if base is None else unused_key_problem(key, base.scene, base.contact.layout)


def retry_problem(base: SceneConfig, modes: set[str], retries: int, factor: float) -> str | None:
    """The last retry's horizon, horizon * factor**retries (horizon: the longest of the base
    scene's numerics.mode and `modes`), must stay finite and <= MAX_HORIZON (compared in
    logs: the power itself may overflow)."""
    num = base.numerics
    horizon = max(num.t_max if mode == "converge" else num.t_decide for mode in modes | {num.mode})
    if math.log(horizon) + retries * math.log(factor) <= math.log(MAX_HORIZON):
        return None
    top = (MAX_HORIZON / horizon) ** (1.0 / retries)
    return (
        f"{_show(factor)} is out of range: with max_retries {retries} the last retry would run "
        f"{horizon:g} s x {_show(factor)}^{retries}, beyond the largest horizon "
        f"{MAX_HORIZON:g} s: must be > 1 and <= {top:.6g}"
    )


def _scene_field(key: str) -> FieldInfo:
    """The SceneConfig field of an existing dotted key."""
    model: Any = SceneConfig
    *sections, leaf = key.split(".")
    for part in sections:
        model = model.model_fields[part].annotation
    return model.model_fields[leaf]


def _field_types(info: FieldInfo) -> set[Any]:
    """The types a field accepts besides null, e.g. {float} for `float | None`."""
    annotation = info.annotation
    union = get_origin(annotation) in (Union, types.UnionType)
    kinds = set(get_args(annotation)) if union else {annotation}
    return {kind for kind in kinds if kind is not type(None)}
