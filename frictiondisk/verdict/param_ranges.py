"""The allowed range of each threshold of `VerdictParams` (verdict/params.py) and the check
that refuses a value outside it, naming the field, its range and its unit."""

from __future__ import annotations

import dataclasses
import math
import numbers
from typing import Any

from frictiondisk.kernel.records import REV_RING


@dataclasses.dataclass(frozen=True)
class Allowed:
    """The range a threshold may take: lo .. hi, each end open or closed."""

    lo: float
    hi: float = math.inf
    lo_open: bool = False
    hi_open: bool = True

    def holds(self, value: float) -> bool:
        above = value > self.lo if self.lo_open else value >= self.lo
        below = value < self.hi if self.hi_open else value <= self.hi
        return above and below

    def __str__(self) -> str:
        hi = "inf" if math.isinf(self.hi) else f"{self.hi:g}"
        return f"{'(' if self.lo_open else '['}{self.lo:g}, {hi}{')' if self.hi_open else ']'}"


# the ranges most thresholds take; a field without its own is a positive number (a count
# at least 1): nonsense such as 0 revolutions or a negative share is refused either way
SHARE = Allowed(0.0, 1.0, lo_open=True)  # a share strictly between 0 and 1
RATIO = SHARE  # a contraction ratio: 1 does not contract
POSITIVE = Allowed(0.0, lo_open=True)
NON_NEGATIVE = Allowed(0.0)
REVOLUTIONS = Allowed(1, REV_RING, hi_open=False)  # at most the revolution ring holds


def count_range(least: int, most: float = math.inf) -> Allowed:
    return Allowed(least, most, hi_open=math.isinf(most))


def threshold(default: float | int, unit: str, reason: str, allowed: Allowed | None = None) -> Any:
    metadata = {"unit": unit, "reason": reason}
    if allowed is not None:
        metadata["allowed"] = allowed
    return dataclasses.field(default=default, metadata=metadata)


def allowed_range(field: dataclasses.Field) -> Allowed:
    """The range of a field: its own, else a positive number (an int: a count >= 1)."""
    if "allowed" in field.metadata:
        return field.metadata["allowed"]
    return count_range(1) if is_count(field) else POSITIVE


def is_count(field: dataclasses.Field) -> bool:
    return field.type in ("int", int)


def check_value(field: dataclasses.Field, value: Any) -> None:
    """Refuse a value of the wrong kind or outside the field's range (ValueError naming the
    field, its range and its unit)."""
    allowed = allowed_range(field)
    kind = "an integer" if is_count(field) else "a number"
    if is_count(field):
        fits = isinstance(value, numbers.Integral) and not isinstance(value, bool)
    else:
        fits = isinstance(value, numbers.Real) and not isinstance(value, bool)
        fits = fits and not math.isnan(value)
    if not (fits and allowed.holds(value)):
        raise ValueError(
            f"VerdictParams.{field.name} = {value!r}: must be {kind} in {allowed} "
            f"[{field.metadata['unit']}]"
        )
