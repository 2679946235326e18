"""The `basin` task's schema: basin stability over sampled initial states, or a basin map.

Conventions of frictiondisk.tasks.find_jump.spec."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar

from pydantic import ValidationInfo, field_validator, model_validator

from frictiondisk.model.axes import (
    DIST_MUST,
    Axes,
    along_must,
    axes_problems,
    base_of,
    check_axes,
)
from frictiondisk.model.schema import canonical, field, merged, rule
from frictiondisk.model.varied import INITIAL_STATE_KEYS, initial_state_problem
from frictiondisk.tasks.sampling.distribution import DEFAULT_SEED, Distribution, sample_problems
from frictiondisk.tasks.spec import TaskSpec

MAX_BASIN_SAMPLES = 10_000_000
DEFAULT_BASIN_BATCH = 100  # samples per adaptive batch (target_se): the stop rule's step

BASIN_TEXT = {
    "sample": "give `sample` (fractions over sampled initial states) or `grid` (a basin map "
    "over 1 or 2 initial-state keys)",
    "both": "samples and target_se given: give one (a fixed count or a target)",
    "count": "no sample count: give samples (e.g. 400) or target_se with max_samples",
    "max": f"missing; must be an integer >= 1 and <= {MAX_BASIN_SAMPLES}",
    "map": "not used with basin.grid (a basin map runs each cell of the grid once, at the "
    "base scene's parameters); remove it or drop grid",
}


class Basin(TaskSpec):
    """Basin stability (fractions of outcomes over sampled initial states) or a basin map.

    Sampling (`sample` non-empty): at each point of `along` (0, 1 or 2 scene keys) draw
    initial states from `sample` (dotted initial-state key -> Distribution); either
    `samples` of them, or batches of `batch` until the standard error of the not-stick
    fraction is <= `target_se` or `max_samples` are drawn. Draws are fixed by `seed` and
    the point's values (frictiondisk.tasks.sampling.draws).
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
    seed: int = field(DEFAULT_SEED, "1", "seed of the draws", ge=0)
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
        problems = sample_problems(sample, base)
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

    def axes(self) -> dict[str, tuple[float, ...]]:
        return {**self.along, **self.grid}

    def unfixed_keys(self) -> set[str]:
        return set(self.sample)  # the sampled initial-state keys
