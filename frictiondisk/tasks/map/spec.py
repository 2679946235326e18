"""The `map` task's schema: the motion of every cell of a plane of two scene keys.

Conventions of frictiondisk.tasks.find_jump.spec; a sampled start is drawn as the basin task
draws its samples (frictiondisk.tasks.sampling: Distribution, draws)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar, Literal

from pydantic import ValidationInfo, field_validator, model_validator

from frictiondisk.model.axes import DIST_MUST, Axes, along_must, base_of, check_axes
from frictiondisk.model.schema import canonical, field, merged, rule
from frictiondisk.model.varied import INITIAL_STATE_KEYS
from frictiondisk.tasks.sampling.distribution import DEFAULT_SEED, Distribution, sample_problems
from frictiondisk.tasks.spec import TaskSpec

DEFAULT_MAP_MODE = "converge"  # the motion is named (and measured) once it has settled
MAX_MAP_SAMPLES = 1000  # sampled starts per cell

MAP_TEXT = {
    "samples": "missing; give samples (sampled starts per cell) with map.sample",
    "unused": "only used with map.sample; remove it or give sample",
}


class MotionMap(TaskSpec):
    """The motion of every cell of `over` (1 or 2 dotted scene keys), one run per cell in
    numerics.mode `mode`, from the scene's own initial state (rest unless its params say
    otherwise: a given state), or from `samples` starts drawn from `sample` (as the basin
    task draws them, fixed by `seed`), with each cell's fractions per motion.

    `stride` (per map, or per key): run every stride-th value of each key first, then
    refine where neighbouring cells differ (tasks/map/cells.py); not given: about the
    square root of the key's values (1, dense, below 6 values)."""

    kind: ClassVar[str] = "map"

    over: Axes = field(..., None, "1 or 2 dotted scene keys to their values", along_must("1 or 2"))
    mode: Literal["decide", "converge"] = field(
        DEFAULT_MAP_MODE, None, "numerics.mode of every run (converge: the motion is named)"
    )
    stride: int = field(
        None,
        "1",
        "run every stride-th value of each key first, refine where neighbours differ; not "
        "given: about sqrt(values) per key, 1 below 6 values",
        ge=1,
    )
    sample: dict[str, Distribution] = field(
        {},
        None,
        f"a sampled start instead of the scene's: initial-state keys ({', '.join(INITIAL_STATE_KEYS)}) "
        "to a distribution",
        f"a mapping of initial-state keys to {DIST_MUST}",
    )
    samples: int = field(None, "1", "sampled starts per cell", ge=1, le=MAX_MAP_SAMPLES)
    seed: int = field(DEFAULT_SEED, "1", "seed of the draws (with sample)", ge=0)

    @model_validator(mode="wrap")
    @classmethod
    def _sampling(cls, data: Any, handler: Any) -> Any:
        """samples goes with sample; seed only with it."""
        if not isinstance(data, Mapping):
            return handler(data)
        problems: list[tuple[Any, str]] = []
        if data.get("sample") and "samples" not in data:
            problems.append(("samples", MAP_TEXT["samples"]))
        if not data.get("sample"):
            problems += [(key, MAP_TEXT["unused"]) for key in ("samples", "seed") if key in data]
        return merged(handler, data, problems, list(cls.model_fields))

    @field_validator("over")
    @classmethod
    def _over(cls, over: Axes, info: ValidationInfo) -> Axes:
        return check_axes(over, base_of(info), (1, 2), {})

    @field_validator("sample")
    @classmethod
    def _sample(cls, sample: dict[str, Distribution], info: ValidationInfo) -> Any:
        text = "{} is a key of the map (map.over); it cannot also be sampled"
        taken = {key: text.format(key) for key in info.data.get("over") or {}}
        problems = sample_problems(sample, base_of(info), taken)
        if problems:
            raise rule(*problems)
        return sample

    @property
    def sampled(self) -> bool:
        return bool(self.sample)

    @property
    def runs_per_cell(self) -> int:
        return self.samples if self.sampled else 1

    def strides(self) -> tuple[int, ...]:
        """The coarse stride of each key: `stride`, capped at values - 1, else the default."""
        return tuple(
            max(1, min(self.stride, len(v) - 1)) if self.stride else default_stride(len(v))
            for v in self.over.values()
        )

    def canonical(self) -> dict[str, Any]:
        """JSON-able dict, keys sorted except `over`/`sample` (their file order); seed only
        with a sample."""
        return canonical(self, [] if self.sampled else ["seed"])

    def axes(self) -> dict[str, tuple[float, ...]]:
        return dict(self.over)

    def point_overrides(self) -> dict[str, Any]:
        return {"numerics.mode": self.mode}

    def unfixed_keys(self) -> set[str]:
        return set(self.sample)


def default_stride(n_values: int) -> int:
    """About sqrt(n) (the coarse lattice and one boundary's refinement stay small
    together, as in a find_jump prescan); 1 below 6 values."""
    return 1 if n_values < 6 else round(n_values**0.5)
