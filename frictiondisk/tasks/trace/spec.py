"""The `trace` task's schema: follow every jump curve through a (key, mu) plane.

Same conventions as frictiondisk.tasks.find_jump.spec (units and descriptions on every
field, every problem reported at once, the base scene from the validation context). The
method is frictiondisk.tasks.trace.tracer; docs/trace.md explains it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, ClassVar, Literal

from pydantic import ValidationError, ValidationInfo, field_validator, model_validator

from frictiondisk.model.axes import LIMITS_MUST, Limits, base_of, check_mu, ordered, pair
from frictiondisk.model.schema import Spec, field, joined, rule, show
from frictiondisk.model.search_settings import DEFAULT_MAX_RETRIES, Certify
from frictiondisk.model.varied import key_problem, retry_problem, value_problems
from frictiondisk.tasks.jump_search.sides import (
    DEFAULT_BETWEEN,
    Between,
    BetweenPair,
    between_must,
)
from frictiondisk.tasks.spec import TaskSpec

RANGE_MUST = "a list [low, high] of two finite numbers with low < high, in the key's unit"
DEFAULT_RESOLUTION = 0.05  # largest step along a curve, scaled by the plane's ranges
DEFAULT_MAX_POINTS = 500
MIN_STEP_PARTS = 32  # min_step, unless given: resolution / MIN_STEP_PARTS (at least 4 tol)
Range = pair("low, high", RANGE_MUST, float, ordered(RANGE_MUST))


class FirstLook(Spec):
    """The coarse first look that finds the curves: `keys` values of the key, evenly from
    the plane's low to its high end, each prescanned at `mu` values of mu evenly over the
    plane (an adaptive prescan with `stride`, as find_jump.prescan) and every change bisected
    and certified. A curve that crosses none of these keys is not found."""

    keys: int = field(3, "1", "key values searched in mu, ends included", ge=1, le=1001)
    mu: int = field(31, "1", "prescan values of mu at each of them, ends included", ge=2, le=10000)
    stride: int | None = field(
        None,
        "1",
        "run every stride-th prescan value first; not given: about sqrt(mu)",
        "an integer >= 1",
        ge=1,
    )


class Trace(TaskSpec):
    """Follow every jump curve through the plane `key` x `mu` (over `range` x `mu`).

    A first look (`first_look`) finds the curves; each is then followed with steps along
    its arclength of at most `resolution` (in coordinates scaled by the plane's ranges),
    every point a certified bracket of width <= `tol` (in mu; in the key: the same scaled
    width). Where a curve turns back in the key, the tip (a fold) is located to tol in
    both coordinates. `max_retries`, `horizon_factor`, `split`, `certify` and `root_finder`
    act as in find_jump (frictiondisk.tasks.trace.tracer; docs/trace.md).
    """

    kind: ClassVar[str] = "trace"
    # only when not the default in the canonical form: older campaigns keep their hash
    OMIT_DEFAULT: ClassVar[tuple[str, ...]] = ("between",)

    key: str = field(
        ...,
        None,
        "the dotted scene key of the plane's first axis, e.g. params.x_ms",
        "a dotted numeric scene key other than params.mu",
    )
    range: Range = field(..., None, "[low, high] of the key", RANGE_MUST)
    mu: Limits = field(..., "1", "[low, high] of mu", LIMITS_MUST)
    tol: float = field(1.0e-4, "1", "largest bracket width of a curve point, in mu", gt=0)
    resolution: float = field(
        DEFAULT_RESOLUTION,
        "1",
        "largest step along a curve, scaled by the plane's ranges",
        gt=0,
        le=1,
    )
    min_step: float = field(
        None,
        "1",
        "smallest step (scaled); not given: resolution / 32, at least 4 tol scaled",
        "a finite number > 0 and <= resolution",
        gt=0,
    )
    first_look: FirstLook = field(FirstLook(), None, "how the curves are found")
    max_points: int = field(
        DEFAULT_MAX_POINTS, "1", "most points of one curve", ge=10, le=1_000_000
    )
    max_retries: int = field(
        DEFAULT_MAX_RETRIES, "1", "retries of an undetermined run", ge=0, le=10
    )
    horizon_factor: float = field(2.0, "1", "each retry multiplies the horizon by this", gt=1)
    split: int = field(2, "1", "parts per bisection round (split - 1 runs at once)", ge=2, le=64)
    certify: Certify = field(
        Certify(),
        None,
        "re-check of each point at stricter numerics: true, false or a mapping with keys "
        "horizon, rtol, levels",
    )
    root_finder: Literal["itp", "bisect"] = field(
        "itp", None, "itp: interpolate on the friction reserve; bisect: halve"
    )
    between: BetweenPair = field(
        DEFAULT_BETWEEN,
        None,
        "[A, B]: the boundary traced, A on the low-mu side of a rising jump and B on its high "
        "side; each an outcome or a class of outcomes (tasks/jump_search/sides.py)",
        between_must(),
    )

    @property
    def sides(self) -> Between:
        """The boundary's two sides (`between`)."""
        return Between(*self.between)

    @field_validator("key")
    @classmethod
    def _key(cls, key: str) -> str:
        if key == "params.mu":
            raise rule("params.mu is the plane's second axis (trace.mu): name another key")
        problem = key_problem(key)
        if problem:
            raise rule(problem)
        return key

    @field_validator("mu")
    @classmethod
    def _mu(cls, values: tuple[float, float], info: ValidationInfo) -> tuple[float, float]:
        return tuple(check_mu(values, info))

    @model_validator(mode="wrap")
    @classmethod
    def _whole(cls, data: Any, handler: Any, info: ValidationInfo) -> Any:
        """The rules across keys, checked whenever the keys they read are valid, also next
        to the problems of other keys."""
        if not isinstance(data, Mapping):
            return handler(data)
        try:
            spec = handler(data)
        except ValidationError as err:
            bad = {error["loc"][0] for error in err.errors() if error["loc"]}
            fields = cls.model_fields
            valid = {name: data.get(name, fields[name].default) for name in fields.keys() - bad}
            problems = trace_problems(valid, base_of(info), raw=True)
            raise joined(err, data, problems, list(fields)) from None
        problems = trace_problems(dict(spec), base_of(info))
        if problems:
            raise rule(*problems)
        return spec

    @property
    def first_step(self) -> float:
        """The step from a seed, whose curve's slope is not known yet (scaled)."""
        return 0.5 * self.resolution

    @property
    def smallest_step(self) -> float:
        """min_step, or its default."""
        if self.min_step is not None:
            return self.min_step
        scaled_tol = self.tol / (self.mu[1] - self.mu[0])
        return min(self.resolution, max(self.resolution / MIN_STEP_PARTS, 4.0 * scaled_tol))


def trace_problems(valid: Mapping[str, Any], base: Any, raw: bool = False) -> list[tuple[str, str]]:
    """The rules across trace keys whose keys are all in `valid` (name -> valid value; with
    `raw`, values as given, not all validated)."""
    problems: list[tuple[Any, str]] = []
    key, span, mu = valid.get("key"), valid.get("range"), valid.get("mu")
    if raw:  # only keys that validated on their own are in `valid`: their values are sound
        span = tuple(span) if isinstance(span, list | tuple) and len(span) == 2 else None
        mu = tuple(mu) if isinstance(mu, list | tuple) and len(mu) == 2 else None
    if base is not None and isinstance(key, str) and span is not None and not key_problem(key):
        for i, value in enumerate(span):
            problems += [(("range", i), p) for p in value_problems(base, key, value)]
    tol = valid.get("tol")
    if mu is not None and isinstance(tol, float | int) and tol >= mu[1] - mu[0]:
        width = f"< high - low = {mu[1] - mu[0]:.6g} (the plane's width in mu)"
        problems.append(("tol", f"{show(tol)} is out of range: must be > 0 and {width}"))
    resolution, min_step = valid.get("resolution"), valid.get("min_step")
    if isinstance(resolution, float | int) and isinstance(min_step, float | int):
        if min_step > resolution:
            problems.append(
                (
                    "min_step",
                    f"{show(min_step)} is out of range: must be > 0 and <= resolution "
                    f"= {show(resolution)}",
                )
            )
    retries, factor = valid.get("max_retries"), valid.get("horizon_factor")
    if base is not None and isinstance(retries, int) and isinstance(factor, float | int):
        if retries and math.isfinite(factor) and factor > 1:
            text = retry_problem(base, set(), retries, factor)
            problems += [("horizon_factor", text)] if text else []
    return problems
