"""The `scan` task's schema: run every point of a grid of mu (and at most one more key).

Conventions of frictiondisk.tasks.find_jump.spec."""

from __future__ import annotations

from typing import Any, ClassVar, Literal

from pydantic import ValidationInfo, field_validator

from frictiondisk.model.axes import (
    VALUES_MUST,
    Axes,
    Values,
    along_must,
    base_of,
    check_axes,
    check_mu,
)
from frictiondisk.model.schema import field
from frictiondisk.tasks.spec import TaskSpec

DEFAULT_SCAN_MODE = "converge"  # a size curve needs the converged cycle (docs/model.md section 6)


class Scan(TaskSpec):
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

    def axes(self) -> dict[str, tuple[float, ...]]:
        """mu first, then the key of `along`."""
        return {"params.mu": self.mu, **self.along}

    def point_overrides(self) -> dict[str, Any]:
        return {"numerics.mode": self.mode}
