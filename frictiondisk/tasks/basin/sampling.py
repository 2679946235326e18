"""A basin point's samples and the not-stick count its stop rule and fractions read.

Which start sample j of a point gets is frictiondisk.tasks.sampling.draws (shared with the
map task's sampled starts).

The not-stick ("large limit cycle") fraction counts every determined outcome other than
`stick` (stick_slip, slide, and any outcome the result adds later); `undetermined`
samples count in no fraction but their own (they stay in the denominator).
"""

from __future__ import annotations

from frictiondisk.tasks.sampling.runs import SampledRuns
from frictiondisk.verdict.outcomes import OUTCOMES, STICK, UNDETERMINED


class BasinPointResult(SampledRuns):
    """The samples of one point, in sample order, and why sampling stopped."""

    @property
    def not_stick(self) -> int:
        """Samples with a determined outcome other than stick (the large limit cycle)."""
        return sum(1 for r in self.results if r["outcome"] not in (STICK, UNDETERMINED))


def not_stick_outcomes(outcomes: tuple[str, ...] = OUTCOMES) -> tuple[str, ...]:
    """The outcomes counted as the large limit cycle: all but stick and undetermined."""
    return tuple(o for o in outcomes if o not in (STICK, UNDETERMINED))
