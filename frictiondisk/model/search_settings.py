"""What a campaign sets for its search: the root finders it may pick, how strictly a
located jump is certified, and the flags a certification ends with. Value objects only;
the search itself lives in frictiondisk/tasks/jump_search/."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, model_validator

from frictiondisk.model.schema import MODEL_CONFIG, field

ROOT_FINDERS = ("itp", "bisect")
# retries of an undetermined run, each with a longer horizon (find_jump and trace); a third
# rescued braked disks' failures but some wrongly (docs/wellposed.md, Run H)
DEFAULT_MAX_RETRIES = 2
# Flag values of the `certification` variables (CF flag_values / flag_meanings), in the order
# of their codes (frictiondisk.tasks.jump_search.certify)
CERTIFICATION_FLAGS = ("off", "certified", "recertified", "uncertain", "vanished", "failed")


class Certify(BaseModel):
    """How a jump is certified: each level multiplies rtol and atol by `rtol` and the horizon budget
    (how far a run may extend to find its evidence) by `horizon`; `levels` is the strictest
    level a point may reach (0: off)."""

    model_config = MODEL_CONFIG

    horizon: float = field(
        4.0, "1", "factor on numerics.horizon_budget per level (the evidence's patience)", gt=1
    )
    rtol: float = field(0.1, "1", "factor on numerics.rtol and atol per level", gt=0, le=1)
    levels: int = field(2, "1", "strictest certification level; 0: off", ge=0, le=4)
    method: Literal["rodas5", "rodas4"] = field(
        "rodas5",
        None,
        "integrator of the stricter runs where the point's numerics.method is rodas4: rodas5 "
        "(5th order) reaches the stricter tolerance in fewer steps and is an integrator "
        "independent of the run it checks; rodas4 re-runs the same one (docs/wellposed.md)",
    )
    eps: float = field(
        1.0,
        "1",
        "factor on contact.eps (the slide->stick threshold, the friction law's resolution) "
        "per level: 0.1 checks that a verdict a slip below eps T a revolution decided holds "
        "at a finer resolution, at a cost; 1: off (docs/model.md section 7)",
        gt=0,
        le=1,
    )
    observe: bool = field(
        False,
        None,
        "the stricter levels decide only on what a run shows (numerics.evidence: observe): "
        "extrapolated verdicts are checked too, at several times the cost (docs/model.md "
        "section 7)",
    )

    watch: float = field(
        2.0,
        "1",
        "a stricter run at a bracket end whose run before it was decided by an extrapolation "
        "(a trend or section read ahead) watches (numerics.observe_until) until this factor "
        "times that run's decision time, within its horizon budget, before it may "
        "extrapolate, and follows a departure from sticking to where it lands "
        "(numerics.follow_departures_until); 0: off (docs/model.md section 7)",
        ge=0,
    )

    @model_validator(mode="before")
    @classmethod
    def _switch(cls, value: Any) -> Any:
        """true: the default certification; false: none."""
        return {True: {}, False: {"levels": 0}}[value] if isinstance(value, bool) else value

    @property
    def enabled(self) -> bool:
        return self.levels > 0

    def canonical(self) -> dict[str, Any]:
        found = {
            "horizon": self.horizon,
            "levels": self.levels,
            "rtol": self.rtol,
        }
        # absent when off or default: the journals of earlier campaigns stay valid
        if self.observe:
            found["observe"] = True
        if self.eps != 1.0:
            found["eps"] = self.eps
        if self.method != "rodas5":
            found["method"] = self.method
        found["watch"] = self.watch  # on by default: 0 must survive a round trip
        return found


OFF = Certify(levels=0)
