"""What a campaign sets for its search: the root finders it may pick, and how strictly a
located jump is certified. Value objects only; the search itself lives in search/."""

from __future__ import annotations

import dataclasses
from typing import Any

ROOT_FINDERS = ("itp", "bisect")


@dataclasses.dataclass(frozen=True)
class Certify:
    """How a jump is certified: each level multiplies the decision horizon by `horizon`
    and rtol by `rtol`; `levels` is the strictest level a point may reach (0: off)."""

    horizon: float = 4.0
    rtol: float = 0.1
    levels: int = 2

    @property
    def enabled(self) -> bool:
        return self.levels > 0

    def canonical(self) -> dict[str, Any]:
        return {"horizon": self.horizon, "levels": self.levels, "rtol": self.rtol}


OFF = Certify(levels=0)
