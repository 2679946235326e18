"""The `trajectory` task's schema: one recorded run of the base scene (paper Figs 4-5).

Conventions of frictiondisk.tasks.find_jump.spec."""

from __future__ import annotations

from typing import Any, ClassVar, Literal

from pydantic import ValidationInfo, field_validator, model_validator

from frictiondisk.model.axes import base_of
from frictiondisk.model.schema import field, rule
from frictiondisk.tasks.spec import TaskSpec

DEFAULT_DT_OUT = 0.01  # [s] recording interval of a trajectory (switching instants are added)


class Trajectory(TaskSpec):
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

    @model_validator(mode="before")
    @classmethod
    def _empty(cls, value: Any) -> Any:
        """`trajectory:` with no keys (null) takes every default."""
        return {} if value is None else value
