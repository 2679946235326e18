"""Values of the scene keys a campaign varies (`along`, `grid`, `scan.mu`, ...): a list of
numbers or `{start, stop, num}`, and pairs such as `[lo, hi]` (with find_jump's rules across
its bracket, tol, limits and retries: `find_jump_problems`); each varied key and value is
checked against the scene schema and, with the base scene in the validation context,
against that scene (every value must give a valid scene)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Annotated, Any

import numpy as np
from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    Discriminator,
    Field,
    Tag,
    ValidationInfo,
    model_validator,
)

from frictiondisk.model.schema import HERE, MODEL_CONFIG, field, kind_of, rule, show
from frictiondisk.model.varied import key_problem, retry_problem, value_problems

MAX_AXIS_VALUES = 10_000  # values of one varied key (each is validated as a scene)
VALUES_MUST = "a list of numbers or a mapping with keys start, stop, num"
PAIR_MUST = "a list [{0}] of two finite numbers with 0 < {1}"
DIST_MUST = "{uniform: [low, high]} with low < high, or {normal: [mean, sd]} with sd > 0"


def base_of(info: ValidationInfo) -> Any:
    """The base scene of the validation context (None: unknown or invalid)."""
    return (info.context or {}).get("base")


# --- values of a varied key -------------------------------------------------------------


class Linspace(BaseModel):
    """`num` values evenly from `start` to `stop` (numpy.linspace), in the varied key's unit."""

    model_config = MODEL_CONFIG

    start: float = field(..., None, "first value")
    stop: float = field(..., None, "last value")
    num: int = field(..., "1", "number of values", ge=1, le=MAX_AXIS_VALUES)

    @model_validator(mode="after")
    def _distinct(self) -> Linspace:
        if self.num > 1 and self.start == self.stop:
            raise rule(
                f"start = stop = {show(self.start)} with num {self.num} repeats one value: "
                "use num: 1 or different start and stop"
            )
        return self


def _values_shape(value: Any) -> Any:
    if isinstance(value, tuple):
        value = list(value)
    if isinstance(value, Mapping):
        return value
    if not isinstance(value, list):
        got = kind_of(value) if value is None else f"{kind_of(value)} {show(value)}"
        raise rule(f"expected a list or a mapping; got {got}: must be {VALUES_MUST}")
    if not value:
        raise rule("empty list: give at least one number")
    if len(value) > MAX_AXIS_VALUES:
        raise rule(f"{len(value)} values: allowed at most {MAX_AXIS_VALUES}")
    return value


def _values_tuple(value: Linspace | list[float]) -> tuple[float, ...]:
    if isinstance(value, Linspace):
        return tuple(float(x) for x in np.linspace(value.start, value.stop, value.num))
    first: dict[float, int] = {}
    repeats = []
    for i, item in enumerate(value):
        if item in first:
            repeats.append((i, f"{show(item)} repeats {HERE}[{first[item]}]: values must differ"))
        first.setdefault(item, i)
    if repeats:
        raise rule(*repeats)
    return tuple(value)


Values = Annotated[
    Annotated[Linspace, Tag("linspace")] | Annotated[list[float], Tag("list")],
    Discriminator(lambda v: "linspace" if isinstance(v, Mapping) else "list"),
    BeforeValidator(_values_shape),
    AfterValidator(_values_tuple),
]
Axes = dict[str, Values]


def pair(names: str, must: str, item: Any, check: Any = None) -> Any:
    """`[a, b]` as a tuple of two `item`s; `check(a, b)` adds a rule on both."""

    def shape(value: Any) -> Any:
        if isinstance(value, list | tuple) and len(value) == 2:
            return tuple(value)
        got = kind_of(value) if value is None else f"{kind_of(value)} {show(value)}"
        raise rule(f"expected a list [{names}]; got {got}: must be {must}")

    after = [AfterValidator(check)] if check else []
    return Annotated[tuple[item, item], BeforeValidator(shape), *after]


def ordered(must: str) -> Any:
    def check(pair: tuple[float, float]) -> tuple[float, float]:
        if not pair[0] < pair[1]:
            raise rule(f"{show(list(pair))} is not allowed: must be {must}")
        return pair

    return check


BRACKET_MUST = PAIR_MUST.format("lo, hi", "lo < hi")
LIMITS_MUST = PAIR_MUST.format("low, high", "low < high")
Positive = Annotated[float, Field(gt=0)]
Bracket = pair("lo, hi", BRACKET_MUST, Positive, ordered(BRACKET_MUST))
Limits = pair("low, high", LIMITS_MUST, Positive, ordered(LIMITS_MUST))


def axes_problems(
    axes: Axes, base: Any, counts: tuple[int, int], taken: Mapping[str, str]
) -> list[tuple[Any, str]]:
    """Problems of the varied keys `axes`: their number, each key, each value's scene."""
    least, most = counts
    allowed = f"{least} or {most}" if least else f"at most {most}"
    noun = "scene key" if most == 1 else "scene keys"
    problems: list[tuple[Any, str]] = []
    if not least <= len(axes) <= most:
        got = f"{len(axes)} keys ({', '.join(axes)})" if axes else "no keys"
        problems.append(((), f"{got} given: vary {allowed} {noun}"))
    for key, values in axes.items():
        text = taken.get(key) or key_problem(key, base)
        if text:
            problems.append((key, text))
        elif base is not None:
            for i, value in enumerate(values):
                problems += [((key, i), p) for p in value_problems(base, key, value)]
    return problems


def check_axes(axes: Axes, base: Any, counts: tuple[int, int], taken: Mapping[str, str]) -> Axes:
    problems = axes_problems(axes, base, counts, taken)
    if problems:
        raise rule(*problems)
    return axes


def check_mu(values: tuple[float, ...], info: ValidationInfo) -> tuple[float, ...]:
    """Each value of mu must give a valid scene."""
    base = base_of(info)
    problems = [
        (i, p) for i, mu in enumerate(values) if base for p in value_problems(base, "params.mu", mu)
    ]
    if problems:
        raise rule(*problems)
    return values


def along_must(counts: str) -> str:
    return f"a mapping of {counts} dotted scene keys to values ({VALUES_MUST})"


def _sd(pair: tuple[float, float]) -> tuple[float, float]:
    if not pair[1] > 0:
        raise rule((1, f"{show(pair[1])} is out of range: the sd must be > 0"))
    return pair


def _low_high(pair: tuple[float, float]) -> tuple[float, float]:
    if not pair[0] < pair[1]:
        raise rule(f"{show(list(pair))} is not allowed: low < high needed")
    return pair


Uniform = pair("low, high", DIST_MUST, float, _low_high)
Normal = pair("mean, sd", DIST_MUST, float, _sd)


def find_jump_problems(valid: Mapping[str, Any], base: Any) -> list[tuple[str, str]]:
    """The rules across find_jump keys whose keys are all in `valid` (name -> valid value)."""
    problems = []
    lo, hi = valid.get("bracket") or (None, None)
    tol, limits, prescan = valid.get("tol"), valid.get("limits"), valid.get("prescan")
    if lo is not None and tol is not None and tol >= hi - lo:
        width = f"< hi - lo = {hi - lo:.6g} (the bracket's width)"
        problems.append(("tol", f"{show(tol)} is out of range: must be > 0 and {width}"))
    if lo is not None and limits is not None and not (limits[0] <= lo and hi <= limits[1]):
        must = "must have limits[0] <= lo and hi <= limits[1]"
        text = f"does not contain the bracket {show([lo, hi])}: {must}"
        problems.append(("limits", f"{show(list(limits))} {text}"))
    retries, factor = valid.get("max_retries"), valid.get("horizon_factor")
    if base is not None and retries and factor is not None and "prescan" in valid:
        raw = isinstance(prescan, Mapping)  # valid, not yet validated
        mode = prescan.get("mode", "decide") if raw else getattr(prescan, "mode", None)
        text = retry_problem(base, {mode} - {None}, retries, factor)
        problems += [("horizon_factor", text)] if text else []
    return problems
