"""The `find_jump` task's schema: bisect mu to the jump mu* at every point of a line or grid.

Pydantic models with units, defaults and descriptions (docs/reference.md is generated from
them). Validators that need the base scene read it from the validation context
(`context={"base": scene}`; None: an invalid scene, whose values are not checked).
Messages: `frictiondisk.model.schema`, list items as `path[i]`."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar, Literal

from pydantic import ValidationError, ValidationInfo, field_validator, model_validator

from frictiondisk.model.auto_numerics import NumericsChoice, for_campaign
from frictiondisk.model.axes import (
    BRACKET_MUST,
    LIMITS_MUST,
    VALUES_MUST,
    Axes,
    Bracket,
    Limits,
    Values,
    along_must,
    base_of,
    check_axes,
    check_mu,
    find_jump_problems,
)
from frictiondisk.model.schema import Spec, field, joined, rule, within
from frictiondisk.model.search_settings import DEFAULT_MAX_RETRIES, Certify
from frictiondisk.model.varied import key_problem
from frictiondisk.tasks.jump_search.sides import (
    DEFAULT_BETWEEN,
    Between,
    BetweenPair,
    between_must,
)
from frictiondisk.tasks.spec import TaskSpec

MAX_SPLIT = 64
# find_jump defaults (docs/model.md section 7: the bisection stops at mu_hi - mu_lo <= 1e-4).
DEFAULT_TOL = 1.0e-4
DEFAULT_LIMITS = (1.0e-6, 10.0)  # the bracket may be widened within these
DEFAULT_HORIZON_FACTOR = 2.0  # each retry multiplies numerics.t_decide (or t_max) by this
DEFAULT_LANES = 2  # warm-start chains
DEFAULT_SPLIT = 2  # parts per bisection round: 2 = plain bisection (bisection.Bisection)
DEFAULT_CERTIFY = Certify()  # horizon x 4, rtol and atol x 0.1 per level, up to level 2
DEFAULT_ROOT_FINDER = "itp"  # interpolate on the friction reserve (bisection.Bisection)


def parameter_key(parameter: str) -> str:
    """The dotted scene key of a find_jump `parameter` ("mu" is params.mu)."""
    return "params.mu" if parameter == "mu" else parameter


class Prescan(Spec):
    """Values of mu run at every point before bisecting, in numerics.mode `mode`; every
    change between neighbours is then bisected (tasks/jump_search/jumps.py, JumpSearch).
    `stride`: run every stride-th value first and refine where needed
    (tasks/jump_search/prescan.py); None picks `prescan.stride_of` (1, dense, for converge
    mode and stick_rule contacts). Every value below the headline is run in the end, and
    the headline must stick over `persist` tol above its bracket (docs/model.md section 7)."""

    mu: Values = field(..., "1", "values of mu run first, at least 2 (sorted)", VALUES_MUST)
    mode: Literal["decide", "converge"] = field("decide", None, "numerics.mode of these runs")
    stride: int = field(
        None,
        "1",
        "run every stride-th value first; not given: frictiondisk.tasks.jump_search.prescan",
        "an integer >= 1 and <= len(mu) - 1",
        ge=1,
    )
    persist: float = field(
        3.0,
        "1",
        "width above a rising jump's mu_hi, in units of tol, over which it must stick to be "
        "the headline (else it is a window)",
        gt=0,
        le=1000,
    )

    @field_validator("mu")
    @classmethod
    def _mu(cls, values: tuple[float, ...], info: ValidationInfo) -> tuple[float, ...]:
        if len(values) < 2:
            raise rule("one value given: give at least 2")
        return tuple(sorted(check_mu(values, info)))

    @field_validator("stride", mode="wrap")
    @classmethod
    def _stride(cls, value: Any, handler: Any, info: ValidationInfo) -> int:
        """At most len(mu) - 1 (no upper bound while mu is invalid)."""
        mu = info.data.get("mu")
        return within(handler, value, int, ge=1, le=max(1, len(mu) - 1) if mu else None)


class FindJump(TaskSpec):
    """Bisect `parameter` (mu) to the jump mu* at every point of `along`.

    `bracket` = (lo, hi) with lo expected not to stick and hi to stick; the bisection stops
    when hi - lo <= `tol`. The bracket may be widened within `limits`. An undetermined run is
    retried up to `max_retries` times, each with numerics.t_decide (or t_max) multiplied by
    `horizon_factor`. `lanes`: how many points of a row (the last dim) are in flight at
    once; the row runs coarse to fine and each inner point predicts its bracket from the
    two that bound it (tasks/find_jump/planner.py). `root_finder`: "itp" aims at the
    friction reserve's zero, "bisect" halves (tasks/jump_search/bisection.py). `along`
    maps 1 or 2 dotted scene keys, in file order, to their values.
    """

    kind: ClassVar[str] = "find_jump"
    # only when not the default in the canonical form: older campaigns keep their hash
    OMIT_DEFAULT: ClassVar[tuple[str, ...]] = ("split", "certify", "root_finder", "between")

    parameter: str = field(
        "mu",
        None,
        "the bisected scene key: mu (params.mu), or a dotted numeric scene key such as "
        "params.J_s (bracket, limits, tol and prescan.mu then hold its values)",
        "mu or a dotted numeric scene key, e.g. params.J_s",
    )
    bracket: Bracket = field(
        ...,
        "1",
        "[lo, hi]: lo not expected to stick, hi to stick; default with prescan: its range of mu",
        BRACKET_MUST,
    )
    tol: float = field(DEFAULT_TOL, "1", "bisection stops at hi - lo <= tol", gt=0)
    limits: Limits = field(
        DEFAULT_LIMITS, "1", "[low, high]: the bracket may be widened within these", LIMITS_MUST
    )
    max_retries: int = field(
        DEFAULT_MAX_RETRIES, "1", "retries of an undetermined run", ge=0, le=10
    )
    horizon_factor: float = field(
        DEFAULT_HORIZON_FACTOR, "1", "each retry multiplies the horizon by this", gt=1
    )
    lanes: int = field(DEFAULT_LANES, "1", "points of a row in flight at once", ge=1, le=64)
    along: Axes = field(..., None, "1 or 2 dotted scene keys to their values", along_must("1 or 2"))
    prescan: Prescan = field(None, None, "values of mu run at every point first")
    split: int = field(
        DEFAULT_SPLIT, "1", "parts per bisection round (split - 1 runs at once)", ge=2, le=MAX_SPLIT
    )
    certify: Certify = field(
        DEFAULT_CERTIFY,
        None,
        "re-check of each jump at stricter numerics: true, false or "
        "a mapping with keys horizon, rtol, levels",
    )
    root_finder: Literal["itp", "bisect"] = field(
        DEFAULT_ROOT_FINDER, None, "itp: interpolate on the friction reserve; bisect: halve"
    )
    between: BetweenPair = field(
        DEFAULT_BETWEEN,
        None,
        "[A, B]: the boundary located, A expected below (bracket lo) and B above (bracket hi); "
        "each an outcome or a class of outcomes (tasks/jump_search/sides.py)",
        between_must(),
    )

    @property
    def sides(self) -> Between:
        """The boundary's two sides (`between`); the friction reserve guides only a search
        in mu."""
        return Between(*self.between, reserve=self.parameter == "mu")

    @model_validator(mode="wrap")
    @classmethod
    def _whole(cls, data: Any, handler: Any, info: ValidationInfo) -> Any:
        """Without a bracket, a prescan's range of mu is the bracket. The rules across keys
        (`find_jump_problems`) are checked whenever the keys they read are valid, also next to
        the problems of other keys."""
        if not isinstance(data, Mapping):
            return handler(data)
        bad = set()
        if "bracket" not in data and "prescan" in data:
            try:
                mu = Prescan.model_validate(data["prescan"], context=info.context).mu
            except ValidationError:  # reported at prescan; a stand-in, not checked across
                mu, bad = DEFAULT_LIMITS, {"bracket"}
            data = {**data, "bracket": [min(mu), max(mu)]}
        try:
            spec = handler(data)
        except ValidationError as err:
            bad |= {error["loc"][0] for error in err.errors() if error["loc"]}
            fields = cls.model_fields
            valid = {name: data.get(name, fields[name].default) for name in fields.keys() - bad}
            problems = find_jump_problems(valid, base_of(info))
            raise joined(err, data, problems, list(cls.model_fields)) from None
        problems = find_jump_problems(dict(spec), base_of(info))
        if problems:
            raise rule(*problems)
        return spec

    @field_validator("parameter")
    @classmethod
    def _parameter(cls, parameter: str, info: ValidationInfo) -> str:
        if parameter in ("mu", "params.mu"):
            return "mu"
        text = key_problem(parameter, base_of(info))
        if text:
            raise rule(
                f"{parameter!r} is not allowed: must be mu or a dotted numeric scene key, "
                f"e.g. params.J_s ({text})"
            )
        return parameter

    @field_validator("along")
    @classmethod
    def _along(cls, along: Axes, info: ValidationInfo) -> Axes:
        key = parameter_key(info.data.get("parameter") or "mu")
        taken = {key: f"{key} is the bisected parameter; it cannot also be varied"}
        return check_axes(along, base_of(info), (1, 2), taken)

    @property
    def parameter_key(self) -> str:
        """The dotted scene key bisected (params.mu unless `parameter` names another)."""
        return parameter_key(self.parameter)

    def axes(self) -> dict[str, tuple[float, ...]]:
        return dict(self.along)

    def unfixed_keys(self) -> set[str]:
        return {self.parameter_key}  # the bisected parameter

    def numerics_choice(self, base: Any, given: Any) -> NumericsChoice:
        """numerics auto: chosen from the tol (frictiondisk.model.auto_numerics)."""
        return for_campaign(base, self.along, self.tol, given)
