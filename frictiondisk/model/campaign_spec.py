"""The campaign schema: pydantic models of a campaign file's keys, with units, defaults and
descriptions (docs/reference.md is generated from them). Validators that need the base scene
read it from the validation context (`context={"base": scene}`; None: an invalid scene, whose
values are not checked). Messages: `frictiondisk.model.schema`, list items as `path[i]`."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar, Literal

from pydantic import ValidationError, ValidationInfo, field_validator, model_validator

from frictiondisk.model.axes import (
    BRACKET_MUST,
    DIST_MUST,
    LIMITS_MUST,
    VALUES_MUST,
    Axes,
    Bracket,
    Limits,
    Normal,
    Uniform,
    Values,
    along_must,
    axes_problems,
    base_of,
    check_axes,
    check_mu,
    find_jump_problems,
)
from frictiondisk.model.schema import Spec, canonical, field, joined, merged, rule, within
from frictiondisk.model.search_settings import DEFAULT_MAX_RETRIES, Certify
from frictiondisk.model.trace_spec import Trace
from frictiondisk.model.varied import INITIAL_STATE_KEYS, initial_state_problem, value_problems

MAX_SPLIT = 64
MAX_BASIN_SAMPLES = 10_000_000
# find_jump defaults (docs/model.md section 7: the bisection stops at mu_hi - mu_lo <= 1e-4).
DEFAULT_TOL = 1.0e-4
DEFAULT_LIMITS = (1.0e-6, 10.0)  # the bracket may be widened within these
DEFAULT_HORIZON_FACTOR = 2.0  # each retry multiplies numerics.t_decide (or t_max) by this
DEFAULT_LANES = 2  # warm-start chains
DEFAULT_SPLIT = 2  # parts per bisection round: 2 = plain bisection (bisection.Bisection)
DEFAULT_CERTIFY = Certify()  # horizon x 4, rtol and atol x 0.1 per level, up to level 2
DEFAULT_ROOT_FINDER = "itp"  # interpolate on the friction reserve (bisection.Bisection)
DEFAULT_SCAN_MODE = "converge"  # a size curve needs the converged cycle (docs/model.md section 6)
DEFAULT_DT_OUT = 0.01  # [s] recording interval of a trajectory (switching instants are added)
DEFAULT_BASIN_BATCH = 100  # samples per adaptive batch (target_se): the stop rule's step
DEFAULT_BASIN_SEED = 0

BASIN_TEXT = {
    "sample": "give `sample` (fractions over sampled initial states) or `grid` (a basin map "
    "over 1 or 2 initial-state keys)",
    "both": "samples and target_se given: give one (a fixed count or a target)",
    "count": "no sample count: give samples (e.g. 400) or target_se with max_samples",
    "max": f"missing; must be an integer >= 1 and <= {MAX_BASIN_SAMPLES}",
    "map": "not used with basin.grid (a basin map runs each cell of the grid once, at the "
    "base scene's parameters); remove it or drop grid",
}


# --- find_jump ----------------------------------------------------------------------------


class Prescan(Spec):
    """Values of mu run at every point before bisecting, in numerics.mode `mode`; every
    change between neighbours is then bisected (frictiondisk.search.jumps.JumpSearch). `stride`:
    run every stride-th value first and refine where needed (frictiondisk.search.prescan); None
    picks `prescan.stride_of` (1, dense, for converge mode and stick_rule contacts). Every
    value below the headline is run in the end, and the headline must stick over `persist`
    tol above its bracket (docs/model.md section 7)."""

    mu: Values = field(..., "1", "values of mu run first, at least 2 (sorted)", VALUES_MUST)
    mode: Literal["decide", "converge"] = field("decide", None, "numerics.mode of these runs")
    stride: int = field(
        None,
        "1",
        "run every stride-th value first; not given: frictiondisk.search.prescan",
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


class FindJump(Spec):
    """Bisect `parameter` (mu) to the jump mu* at every point of `along`.

    `bracket` = (lo, hi) with lo expected not to stick and hi to stick; the bisection stops
    when hi - lo <= `tol`. The bracket may be widened within `limits`. An undetermined run is
    retried up to `max_retries` times, each with numerics.t_decide (or t_max) multiplied by
    `horizon_factor`. `lanes`: how many points of a row (the last dim) are in flight at
    once; the row runs coarse to fine and each inner point predicts its bracket from the
    two that bound it (engine/plan.py). `root_finder`: "itp" aims at the friction
    reserve's zero, "bisect" halves (frictiondisk.search.bisection). `along` maps 1 or 2 dotted
    scene keys, in file order, to their values.
    """

    kind: ClassVar[str] = "find_jump"
    # only when not the default in the canonical form: older campaigns keep their hash
    OMIT_DEFAULT: ClassVar[tuple[str, ...]] = ("split", "certify", "root_finder")

    parameter: Literal["mu"] = field("mu", None, "the bisected scene key: params.mu")
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

    @field_validator("along")
    @classmethod
    def _along(cls, along: Axes, info: ValidationInfo) -> Axes:
        taken = {"params.mu": "params.mu is the bisected parameter; it cannot also be varied"}
        return check_axes(along, base_of(info), (1, 2), taken)


# --- scan and trajectory ------------------------------------------------------------------


class Scan(Spec):
    """Run every point of the grid `mu` x `along` with numerics.mode = `mode`.

    `along` maps at most one dotted scene key to its values (empty: a line in mu).
    """

    kind: ClassVar[str] = "scan"

    mu: Values = field(..., "1", "values of mu (the first dim)", VALUES_MUST)
    along: Axes = field({}, None, "at most 1 dotted scene key to its values", along_must("0 or 1"))
    mode: Literal["decide", "converge"] = field(
        DEFAULT_SCAN_MODE, None, "numerics.mode of every run"
    )

    @field_validator("mu")
    @classmethod
    def _mu(cls, values: tuple[float, ...], info: ValidationInfo) -> tuple[float, ...]:
        return check_mu(values, info)

    @field_validator("along")
    @classmethod
    def _along(cls, along: Axes, info: ValidationInfo) -> Axes:
        taken = {"params.mu": "params.mu is the scan's own axis: give its values in scan.mu"}
        return check_axes(along, base_of(info), (0, 1), taken)


class Trajectory(Spec):
    """Record one run of the base scene every `dt_out` seconds (plus every switching
    instant) and show it `whole` (transient and cycle, paper Fig. 4) or only its last
    converged limit cycle, `cycle` (paper Fig. 5; needs numerics.mode converge)."""

    kind: ClassVar[str] = "trajectory"

    # validate_default: the default too must fit the base scene's recording capacity
    dt_out: float = field(DEFAULT_DT_OUT, "s", "recording interval", gt=0, validate_default=True)
    show: Literal["whole", "cycle"] = field(
        "whole", None, "whole: transient and cycle; cycle: the last converged limit cycle"
    )

    @field_validator("dt_out")
    @classmethod
    def _fits(cls, dt_out: float, info: ValidationInfo) -> float:
        from frictiondisk.model.limits import recording_problem

        base = base_of(info)
        problem = base and recording_problem(base, dt_out, "-")
        if problem:
            raise rule(problem.removeprefix("-: "))
        return dt_out

    @field_validator("show")
    @classmethod
    def _cycle(cls, show: str, info: ValidationInfo) -> str:
        base = base_of(info)
        if show == "cycle" and base is not None and base.numerics.mode != "converge":
            raise rule(
                "'cycle' needs the converged limit cycle: "
                f"set numerics.mode: converge (got {base.numerics.mode!r})"
            )
        return show

    @property
    def along(self) -> dict[str, tuple[float, ...]]:
        return {}


# --- basin ----------------------------------------------------------------------------------


class Distribution(Spec):
    """One sampled initial-state key: `uniform` on [a, b) or `normal` with mean a, sd b."""

    uniform: Uniform = field(
        None, None, "uniform on [low, high), in the key's unit", "a list [low, high], low < high"
    )
    normal: Normal = field(None, None, "normal, in the key's unit", "a list [mean, sd] with sd > 0")

    @model_validator(mode="wrap")
    @classmethod
    def _one(cls, data: Any, handler: Any) -> Any:
        """Exactly one key given (counted on the keys, also when a value is bad)."""
        if not isinstance(data, Mapping) or not set(data) <= set(cls.model_fields):
            return handler(data)  # unknown keys: reported as such
        text = f"{len(data)} distributions given: must be {DIST_MUST}"
        return merged(handler, data, [] if len(data) == 1 else [((), text)], list(cls.model_fields))

    @property
    def kind(self) -> str:
        """ "uniform" or "normal"."""
        return "uniform" if self.uniform is not None else "normal"

    @property
    def a(self) -> float:
        return (self.uniform or self.normal)[0]

    @property
    def b(self) -> float:
        return (self.uniform or self.normal)[1]


class Basin(Spec):
    """Basin stability (fractions of outcomes over sampled initial states) or a basin map.

    Sampling (`sample` non-empty): at each point of `along` (0, 1 or 2 scene keys) draw
    initial states from `sample` (dotted initial-state key -> Distribution); either
    `samples` of them, or batches of `batch` until the standard error of the not-stick
    fraction is <= `target_se` or `max_samples` are drawn. Draws are fixed by `seed` and
    the point's values (frictiondisk.engine.basin_plan).
    Map (`grid` non-empty): one run per cell of 1 or 2 initial-state keys; no sampling.
    """

    kind: ClassVar[str] = "basin"

    sample: dict[str, Distribution] = field(
        {},
        None,
        f"initial-state keys ({', '.join(INITIAL_STATE_KEYS)}) to a distribution",
        f"a mapping of initial-state keys to {DIST_MUST}",
    )
    samples: int = field(None, "1", "samples per point (or target_se)", ge=1, le=MAX_BASIN_SAMPLES)
    target_se: float = field(
        None, "1", "stop once the not-stick fraction's standard error is <= this", gt=0, le=0.5
    )
    max_samples: int = field(
        None, "1", "most samples per point, with target_se", ge=1, le=MAX_BASIN_SAMPLES
    )
    batch: int = field(
        DEFAULT_BASIN_BATCH, "1", "samples per batch, with target_se", ge=1, le=MAX_BASIN_SAMPLES
    )
    seed: int = field(DEFAULT_BASIN_SEED, "1", "seed of the draws", ge=0)
    along: Axes = field({}, None, "0 to 2 dotted scene keys to their values", along_must("0 to 2"))
    grid: Axes = field(
        {},
        None,
        "a basin map instead of sampling: 1 or 2 initial-state keys to their values",
        along_must("1 or 2"),
    )

    @model_validator(mode="wrap")
    @classmethod
    def _which(cls, data: Any, handler: Any) -> Any:
        """The keys given must make a sampling or a map (checked on the keys alone)."""
        if not isinstance(data, Mapping):
            return handler(data)
        given, problems = set(data), []
        if "grid" in given:
            unused = [key for key in cls.model_fields if key in given - {"grid"}]
            problems = [(key, BASIN_TEXT["map"]) for key in unused]
            data = {key: value for key, value in data.items() if key not in unused}  # once
        elif "sample" not in given:
            problems = [((), BASIN_TEXT["sample"])]
        elif {"samples", "target_se"} <= given:
            problems = [((), BASIN_TEXT["both"])]
        elif "samples" in given:
            used = "only used with basin.target_se; remove it"
            problems = [(key, used) for key in ("max_samples", "batch") if key in given]
        elif "target_se" not in given:
            problems = [((), BASIN_TEXT["count"])]
        elif "max_samples" not in given:
            problems = [("max_samples", BASIN_TEXT["max"])]
        return merged(handler, data, problems)

    @field_validator("sample")
    @classmethod
    def _sample(cls, sample: dict[str, Distribution], info: ValidationInfo) -> Any:
        base = base_of(info)
        if not sample:
            keys = ", ".join(INITIAL_STATE_KEYS)
            raise rule(f"no keys: map at least one of {keys} to a distribution")
        problems: list[tuple[Any, str]] = []
        for key, dist in sample.items():
            text = initial_state_problem(key, base)
            if text:
                problems.append((key, text))
            elif base is not None and dist.uniform is not None:
                for i, value in enumerate(dist.uniform):
                    problems += [((key, "uniform", i), p) for p in value_problems(base, key, value)]
        if problems:
            raise rule(*problems)
        return sample

    @field_validator("along")
    @classmethod
    def _along(cls, along: Axes, info: ValidationInfo) -> Axes:
        text = "{} is sampled (basin.sample); it cannot also be varied"
        taken = {key: text.format(key) for key in info.data.get("sample") or {}}
        return check_axes(along, base_of(info), (0, 2), taken)

    @field_validator("grid")
    @classmethod
    def _grid(cls, grid: Axes, info: ValidationInfo) -> Axes:
        base = base_of(info)
        problems = axes_problems(grid, base, (1, 2), {})
        if not problems:
            for key in grid:
                text = initial_state_problem(key, base)
                problems += [(key, text)] if text else []
        if problems:
            raise rule(*problems)
        return grid

    @property
    def is_map(self) -> bool:
        return bool(self.grid)

    @property
    def sample_limit(self) -> int:
        """Most samples a point can take (1 for a map: each cell is one run)."""
        if self.is_map:
            return 1
        return self.samples if self.samples is not None else self.max_samples

    def canonical(self) -> dict[str, Any]:
        """JSON-able dict, keys sorted except `along`/`grid`/`sample` (their file order):
        a map's grid only; a sampling's batch only with target_se."""
        if self.is_map:
            return {"grid": canonical(self)["grid"]}
        return canonical(self, ["grid", *(["batch"] if self.samples is not None else [])])


# --- the file -------------------------------------------------------------------------------

SCENE_KEYS = ("scene", "params", "contact", "numerics")
TASK_KEYS = ("find_jump", "scan", "trajectory", "basin", "trace")
TASKS = {
    "find_jump": FindJump,
    "scan": Scan,
    "trajectory": Trajectory,
    "basin": Basin,
    "trace": Trace,
}
_SCENE_DOC = "the base scene's {} (validated as in a scene file; see the scene keys)"


class CampaignFile(Spec):
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
    find_jump: FindJump = field(None, None, "task: bisect mu to the jump mu* at every point")
    scan: Scan = field(None, None, "task: run every point of a grid of mu")
    trajectory: Trajectory = field(None, None, "task: one recorded run of the base scene")
    basin: Basin = field(None, None, "task: basin stability or a basin map")
    trace: Trace = field(None, None, "task: follow every jump curve through a (key, mu) plane")

    @field_validator("trajectory", mode="before")
    @classmethod
    def _defaults(cls, value: Any) -> Any:
        return {} if value is None else value
