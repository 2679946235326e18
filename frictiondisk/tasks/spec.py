"""The base schema of a campaign file's task section (`TaskSpec`): beside its own keys, what
the rest of a campaign reads of every task, so that no code outside the task names it: the
grid it spans, the values it fixes at each point, the scene keys it leaves without one value
in the files, and the numerics chosen from it."""

from __future__ import annotations

from typing import Any, ClassVar

from frictiondisk.model.schema import Spec


class TaskSpec(Spec):
    """A task section of a campaign file (pydantic; conventions of frictiondisk.model.schema)."""

    kind: ClassVar[str]  # its key in a campaign file: the task's name in the registry

    def axes(self) -> dict[str, tuple[float, ...]]:
        """The varied scene keys to their values, in file order: the campaign's dims."""
        return {}

    def point_overrides(self) -> dict[str, Any]:
        """Scene values the task sets at every point of its grid (dotted key -> value)."""
        return {}

    def unfixed_keys(self) -> set[str]:
        """Scene keys besides the dims that have no single value in the files (a searched
        or a sampled key)."""
        return set()

    def numerics_choice(self, base: Any, given: Any) -> Any:
        """The numerics chosen from the task's own keys (a NumericsChoice), or None: the
        base scene's. `given`: the file's `numerics` mapping as written."""
        return None
