"""A sampled initial-state key in a campaign file: its distribution, the default seed, and
the checks every task that samples starts makes of its `sample` mapping."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from pydantic import model_validator

from frictiondisk.model.axes import DIST_MUST, Normal, Uniform
from frictiondisk.model.schema import Spec, field, merged
from frictiondisk.model.varied import initial_state_problem, value_problems

DEFAULT_SEED = 0  # the seed of the draws when a campaign names none


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


def sample_problems(
    sample: dict[str, Distribution], base: Any, taken: Mapping[str, str] | None = None
) -> list[tuple[Any, str]]:
    """(path, text) for each bad sampled key: not an initial-state key of the scene `base`,
    one `taken` by the task (key -> why it cannot be sampled), or a uniform bound the scene
    refuses. [] when all are good."""
    taken = taken or {}
    problems: list[tuple[Any, str]] = []
    for key, dist in sample.items():
        text = taken.get(key) or initial_state_problem(key, base)
        if text:
            problems.append((key, text))
        elif base is not None and dist.uniform is not None:
            for i, value in enumerate(dist.uniform):
                problems += [((key, "uniform", i), p) for p in value_problems(base, key, value)]
    return problems
