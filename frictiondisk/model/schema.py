"""Shared by the scene and campaign schemas: the field helper (default, unit, description,
bounds) and the translation of pydantic errors into the house message format,
`dotted.path: what is wrong; what is allowed`, one line per problem.

A validator reports a rule that no field type states with `rule(...)`: one or more
problems, each at a path relative to where the validator runs.
"""

from __future__ import annotations

import difflib
import json
import reprlib
import types
from collections.abc import Mapping, Sequence
from typing import Annotated, Any, Literal, Union, get_args, get_origin

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError
from pydantic.fields import FieldInfo
from pydantic_core import ErrorDetails, InitErrorDetails, PydanticCustomError

INT64_MAX = 2**63 - 1
HERE = "\x00here\x00"  # in a rule's text: the dotted path where the validator runs
FLOAT_MAX = 1.7976931348623157e308

# strict: no "0.1" -> 0.1, no true -> 1.0, no 1.5 -> int; allow_inf_nan: reject inf/nan.
MODEL_CONFIG = ConfigDict(extra="forbid", frozen=True, strict=True, allow_inf_nan=False)

_BOUNDS = {"gt": ">", "ge": ">=", "lt": "<", "le": "<="}
_TYPE_NOUNS = {
    "float_type": "a number",
    "int_type": "an integer",
    "bool_type": "a boolean",
    "string_type": "text",
}
_NOT_ALLOWED = ("finite_number", "literal_error", "string_pattern_mismatch")
_repr = reprlib.Repr()
_repr.maxstring = _repr.maxother = 40
_repr.maxlevel = 2  # a nested value shows its first two levels, a few items each
_repr.maxlist = _repr.maxtuple = _repr.maxset = 6
_repr.maxdict = 4
SHOW_CHARS = 80  # the most a value takes in a message


def field(
    default: Any, unit: str | None, doc: str, must: str | None = None, **constraints: Any
) -> Any:
    """Field with default (`...`: required), unit ("1" = dimensionless, None = not a
    quantity), description and bounds; `must` says what it accepts where the type cannot."""
    extra = {"unit": unit} if unit else {}
    if must:
        extra["must"] = must
    return Field(
        default,
        description=f"{doc} [{unit}]" if unit else doc,
        json_schema_extra=extra or None,
        **constraints,
    )


def extra_of(info: FieldInfo) -> dict[str, Any]:
    return info.json_schema_extra if isinstance(info.json_schema_extra, dict) else {}


def rule(*problems: tuple[Any, str] | str) -> PydanticCustomError:
    """An error of one or more problems, each `text` or `(at, text)`; `at` is a key, an
    index or a tuple of them, under the location of the validator that raises it."""
    pairs = [(((),) + (p,)) if isinstance(p, str) else p for p in problems]
    return PydanticCustomError("rule", "rule", {"problems": pairs})


def merged(
    handler: Any, data: Any, problems: Sequence[tuple[Any, str]], order: Sequence[str] = ()
) -> Any:
    """`handler(data)` (a wrap validator's), with `problems` reported next to its errors
    (sorted as `joined` sorts them)."""
    try:
        out = handler(data)
    except ValidationError as err:
        raise joined(err, data, problems, order) from None
    if problems:
        raise joined(None, data, problems)
    return out


def joined(
    err: ValidationError | None,
    data: Any,
    problems: Sequence[tuple[Any, str]],
    order: Sequence[str] = (),
) -> ValidationError:
    """The errors of `err` (None: none) and `problems` (`(at, text)`, or `(at, error)`
    with a PydanticCustomError of its own) as one error; with `order` (field names) sorted
    by the field each is under, unknown keys first."""
    details = [_init_details(error) for error in err.errors(include_url=False)] if err else []
    for at, text in problems:
        at = at if isinstance(at, tuple) else (at,)
        kind = text if isinstance(text, PydanticCustomError) else rule(text)
        details.append(InitErrorDetails(type=kind, loc=at, input=data))
    rank = {name: i for i, name in enumerate(order)}
    details.sort(key=lambda detail: rank.get(detail["loc"][0], -1) if detail["loc"] else -1)
    return ValidationError.from_exception_data(err.title if err else "rule", details)


def _init_details(error: ErrorDetails) -> InitErrorDetails:
    kind, ctx = error["type"], error.get("ctx")
    if kind in ("rule", "scene_rule", "layout_rule"):
        kind = PydanticCustomError(kind, error["msg"].replace("{", "(").replace("}", ")"), ctx)
    details = InitErrorDetails(type=kind, loc=error["loc"], input=error.get("input"))
    if ctx is not None and not isinstance(kind, PydanticCustomError):
        details["ctx"] = ctx
    return details


def within(handler: Any, value: Any, annotation: Any, **limits: Any) -> Any:
    """`handler(value)` (a wrap field validator's) also within `limits` (ge=, le=, ...) known
    only while validating, e.g. from another field; every problem states these limits."""
    info = FieldInfo.from_annotated_attribute(annotation, Field(**limits))
    try:
        out = handler(value)
        TypeAdapter(Annotated[annotation, Field(**limits)]).validate_python(out)
    except ValidationError as err:
        lines = [field_problem(e["type"], value, info, e["msg"]) for e in err.errors()]
        raise rule(*lines) from None
    return out


# --- messages ---------------------------------------------------------------------------


# spellings a user may write for the house ones (British -ise/-tre words, long names)
_SPELLINGS = (("centering", "centring"), ("centered", "centred"), ("center", "centre"))


def did_you_mean(word: Any, names: Sequence[str]) -> str:
    """` (did you mean 'x'?)` for the name in `names` closest to `word` ("" if none is
    close): a close spelling, an American one of a house word (self_centering), or a name
    that starts `word` or that `word` starts (tolerance: tol)."""
    if not isinstance(word, str) or not names:
        return ""
    respelled = word
    for theirs, ours in _SPELLINGS:
        respelled = respelled.replace(theirs, ours)
    close = [respelled] if respelled in names else []
    close = close or difflib.get_close_matches(word, names, n=1)
    close = close or [
        name
        for name in names
        if min(len(name), len(word)) >= 3 and (word.startswith(name) or name.startswith(word))
    ]
    return f" (did you mean {close[0]!r}?)" if close else ""


def problems_of(
    err: ValidationError,
    root: type[BaseModel],
    origins: Mapping[str, str] | None = None,
    brackets: bool = False,
    unused: Sequence[str] = (),
) -> list[str]:
    """The house lines of a ValidationError of `root`; list items are written `path[i]`
    with `brackets`, else `path.i`; `origins` tags problems under a dotted key; `unused`:
    dotted keys the scene does not take, left out of the allowed keys listed."""
    lines = []
    for error in err.errors(include_url=False):
        lines += error_lines(error, root, origins, brackets, unused)
    return lines


def error_lines(
    error: ErrorDetails,
    root: Any,
    origins: Mapping[str, str] | None = None,
    brackets: bool = False,
    unused: Sequence[str] = (),
) -> list[str]:
    """The house lines of one pydantic error of `root` (a rule may hold several); `unused`
    as in problems_of."""
    origins = origins or {}
    kind, loc, value = error["type"], error["loc"], error.get("input")
    ctx = error.get("ctx") or {}
    parts, info, here = _walk(root, loc)
    if kind == "rule":
        lines = []
        for at, text in ctx["problems"]:
            at = at if isinstance(at, tuple) else (at,)
            text = text.replace(HERE, dotted(parts, brackets))
            lines.append(f"{dotted((*parts, *at), brackets)}: {text}")
        return lines
    if kind == "scene_rule":
        path = ctx["path"]
        text = f"{show(ctx['value'])} is not allowed for scene {ctx['scene']!r}: {error['msg']}"
    elif kind == "layout_rule":
        path = ctx["path"]
        text = f"{show(ctx['value'])} is not allowed: {error['msg']}"
    elif loc and loc[-1] == "[key]":
        path = dotted(parts[:-1], brackets)
        text = f"key {show(value)} is not text; allowed: text keys"
    elif kind in ("extra_forbidden", "invalid_key"):
        parent, _, model = _walk(root, loc[:-1])
        path = dotted(parts if kind == "extra_forbidden" else parent, brackets)
        under = f"under {dotted(parent, brackets)}" if parent else "at top level"
        what = "unknown key" if kind == "extra_forbidden" else f"key {show(value)} is not text"
        names = list(model.model_fields) if is_model(model) else []
        names = [n for n in names if dotted((*parent, n), brackets) not in unused]
        text = f"{what}; allowed keys {under}: {', '.join(names)}"
        text += did_you_mean(str(loc[-1]), names)
    elif kind in ("model_type", "model_attributes_type", "dict_type") and is_model(here):
        path = dotted(parts, brackets)
        got = kind_of(value) if value is None else f"{kind_of(value)} {show(value)}"
        text = f"expected a mapping with keys {', '.join(here.model_fields)}; got {got}"
    else:
        path = dotted(parts, brackets)
        text = field_problem(kind, value, info, error["msg"])
    for key, origin in origins.items():
        if path == key or path.startswith(key + "."):
            text += f" (from {origin})"
    return [f"{path}: {text}"]


def field_problem(kind: str, value: Any, info: FieldInfo | None, msg: str) -> str:
    if info is None:
        return f"{show(value)}: {msg}"
    must = f"must be {requirement(info)}"
    if kind == "missing":
        return f"missing; {must}"
    if kind in _NOT_ALLOWED:
        choices = _choices(info.annotation) if kind == "literal_error" else []
        return f"{show(value)} is not allowed: {must}{did_you_mean(value, choices)}"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        return f"{show(value)} is out of range: must be {bounds(info, value)}"
    if value is None:
        return f"missing value (null); {must}"
    if kind == "float_type" and type(value) is int:  # a huge YAML integer: no float holds it
        return f"{show(value)} is out of range: {must}, |x| <= {FLOAT_MAX}"
    if kind in _TYPE_NOUNS:
        number = kind in ("float_type", "int_type")
        hint = " (write numbers without quotes)" if number and isinstance(value, str) else ""
        return f"{show(value)} is {kind_of(value)}, not {_TYPE_NOUNS[kind]}: {must}{hint}"
    if kind in ("dict_type", "list_type", "tuple_type"):
        got = kind_of(value) if value is None else f"{kind_of(value)} {show(value)}"
        return f"expected {'a mapping' if kind == 'dict_type' else 'a list'}; got {got}: {must}"
    return f"{show(value)}: {msg}; {must}"


def _choices(annotation: Any) -> list[str]:
    """The text values of a Literal (inside Optional or Annotated), else []."""
    base = plain_annotation(annotation)
    if get_origin(base) is not Literal:
        return []
    return [choice for choice in get_args(base) if isinstance(choice, str)]


def requirement(info: FieldInfo) -> str:
    """What a field accepts, e.g. "a finite number > 0 kg", "one of 'a', 'b', 'c'"."""
    if "must" in extra_of(info):
        return extra_of(info)["must"]
    annotation = info.annotation
    args = get_args(annotation) if get_origin(annotation) in (Union, types.UnionType) else ()
    nullable = type(None) in args
    base = next(a for a in args if a is not type(None)) if args else annotation
    if get_origin(base) is list:
        item = get_args(base)[0]
        text = "a list of pairs [x, y]" if get_origin(item) is list else "a list of numbers"
    elif get_origin(base) is Literal:
        choices = [repr(choice) for choice in get_args(base)]
        text = " or ".join(choices) if len(choices) <= 2 else "one of " + ", ".join(choices)
    elif is_model(base):
        text = f"a mapping with keys {', '.join(base.model_fields)}"
    else:
        noun = {bool: "true or false", int: "an integer", float: "a finite number"}
        text = f"{noun.get(base, 'valid')} {bounds(info)}".strip()
    return f"null or {text}" if nullable else text


def bounds(info: FieldInfo, value: Any = None) -> str:
    """The field's bounds and unit, e.g. "> 0 and < 1", ">= 0 rad/s"; "" if unbounded.

    The int64 limit of integer fields is shown only to a `value` beyond it."""
    beyond_int64 = isinstance(value, int) and value > INT64_MAX
    parts = [
        f"{symbol} {getattr(item, name)}"
        for item in info.metadata
        for name, symbol in _BOUNDS.items()
        if getattr(item, name, None) is not None
        and (getattr(item, name) != INT64_MAX or beyond_int64)
    ]
    unit = extra_of(info).get("unit")
    if not parts:
        return ""
    return " and ".join(parts) + (f" {unit}" if unit and unit != "1" else "")


# --- locations --------------------------------------------------------------------------


def _walk(root: Any, loc: Sequence[int | str]) -> tuple[list[Any], FieldInfo | None, Any]:
    """The user-facing path parts of `loc` under `root` (union tags and dict-key markers
    dropped), the FieldInfo that validates it (None if unknown) and its type."""
    parts: list[Any] = []
    info: FieldInfo | None = None
    here = root
    for part in loc:
        here = plain_annotation(here)
        if part == "[key]":
            continue
        if is_model(here) and part in here.model_fields:
            info = here.model_fields[part]
            here = info.annotation
        elif get_origin(here) in (Union, types.UnionType):
            tagged = {_tag(member): member for member in get_args(here)}
            if part in tagged:
                here = tagged[part]
                continue
            here, info = None, None
        elif get_origin(here) is dict:
            here = get_args(here)[1]
            info = FieldInfo.from_annotation(here)
        elif get_origin(here) in (list, tuple) and isinstance(part, int):
            args = [a for a in get_args(here) if a is not Ellipsis]
            here = args[min(part, len(args) - 1)]
            info = FieldInfo.from_annotation(here)
        else:
            here, info = None, None
        parts.append(part)
    return parts, info, plain_annotation(here)


def plain_annotation(annotation: Any) -> Any:
    """`annotation` without Annotated and without None in a union of one other type."""
    while get_origin(annotation) is Annotated:
        annotation = get_args(annotation)[0]
    args = get_args(annotation) if get_origin(annotation) in (Union, types.UnionType) else ()
    others = [a for a in args if a is not type(None)]
    if len(args) == 2 and len(others) == 1:
        return plain_annotation(others[0])
    return annotation


def _tag(annotation: Any) -> str | None:
    if get_origin(annotation) is Annotated:
        return next((m.tag for m in annotation.__metadata__ if hasattr(m, "tag")), None)
    return None


def field_at(root: type[BaseModel], loc: Sequence[int | str]) -> FieldInfo | None:
    """The FieldInfo of a (dotted key's) location under `root`, None if there is none."""
    try:
        parts, info, _ = _walk(root, loc)
    except (KeyError, AttributeError, IndexError, TypeError):
        return None
    return info if len(parts) == len(loc) and info is not None else None


def is_model(annotation: Any) -> bool:
    return isinstance(annotation, type) and issubclass(annotation, BaseModel)


def dotted(loc: Sequence[int | str], brackets: bool = False) -> str:
    """ "a.b.c", list items `a.b[0]` with `brackets`; "(top level)" for none."""
    text = ""
    for part in loc:
        if brackets and isinstance(part, int):
            text += f"[{part}]"
        else:
            text += f".{part}" if text else str(part)
    return text or "(top level)"


def show(value: Any) -> str:
    """A value as the user wrote it: YAML words for true/false/null, else a short repr."""
    if value is None or isinstance(value, bool):
        return json.dumps(value)
    text = _repr.repr(value)
    return text if len(text) <= SHOW_CHARS else f"{text[: SHOW_CHARS - 4]} ..."


def kind_of(value: Any) -> str:
    if value is None:
        return "null"
    kinds = {
        bool: "a boolean",
        int: "an integer",
        float: "a float",
        str: "a string",
        list: "a list",
        dict: "a mapping",
    }
    return next(
        (text for cls, text in kinds.items() if isinstance(value, cls)), f"a {type(value).__name__}"
    )


class Spec(BaseModel):
    """A part of a configuration file; `canonical()`: a JSON-able dict, keys sorted
    (mappings inside, such as a campaign's `along`, keep their order)."""

    model_config = MODEL_CONFIG

    def canonical(self) -> dict[str, Any]:
        return canonical(self)


def canonical(model: BaseModel, skip: Sequence[str] = ()) -> dict[str, Any]:
    """A model as a JSON-able dict, keys sorted (mappings inside keep their order), without
    `skip`, null fields and the fields of `model.OMIT_DEFAULT` that hold their default (so
    that a key added later keeps the content hash of files that do not give it)."""
    omit = getattr(model, "OMIT_DEFAULT", ())
    out = {}
    for name, info in type(model).model_fields.items():
        value = getattr(model, name)
        if name in skip or value is None or (name in omit and value == info.default):
            continue
        out[name] = _plain(value)
    return {key: out[key] for key in sorted(out)}


def _plain(value: Any) -> Any:
    if isinstance(value, BaseModel):
        return value.canonical() if hasattr(value, "canonical") else canonical(value)
    if isinstance(value, Mapping):
        return {key: _plain(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(item) for item in value]
    return value
