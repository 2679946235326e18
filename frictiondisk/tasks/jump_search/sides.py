"""The two sides of a boundary a search locates (`between: [A, B]`): which side of it a run's
outcome lies on. Pure Python.

A side is a class of outcomes (`stick`; `not_stick`: every decided outcome but stick, as
frictiondisk.verdict.outcomes.outcome_class says) or one outcome name (OUTCOMES, read as
data: a motion the verdict adds is a side at once). The searches (bisection, certify, prescan, jumps, trace) keep
their two kinds, HIGH (B, expected above the boundary for a rising jump; `stick` by
default) and LOW (A). A run whose outcome is on neither side (`undetermined`, or a third
motion) is undecided for this boundary: retried with a longer horizon like an
undetermined run (an unsettled `slide` may settle on a side), and named where it stops the
search.

The default, [not_stick, stick], is the stick / not-stick jump: every decided outcome has
a side, and the friction reserve (frictiondisk/verdict/reserve.py), the signal of that
jump alone, guides the searches. Any other boundary is searched on verdicts alone.

`check_between` is the campaign-file check of a `between` key (find_jump, trace).
"""

from __future__ import annotations

import dataclasses
import functools

from frictiondisk.model.axes import pair
from frictiondisk.model.schema import did_you_mean, rule
from frictiondisk.verdict.outcomes import NOT_STICK, OUTCOMES, STICK, UNDETERMINED, outcome_class

HIGH = STICK  # the searches' kind of side B (the stick side of the default jump)
LOW = "not stick"  # their kind of side A
DEFAULT_BETWEEN = (NOT_STICK, STICK)


@functools.cache
def side_members() -> dict[str, frozenset[str]]:
    """Every name `between` takes -> the outcomes it stands for: the classes, then each
    decided outcome."""
    decided = [o for o in OUTCOMES if outcome_class(o) != UNDETERMINED]
    members = {
        STICK: frozenset(o for o in decided if outcome_class(o) == STICK),
        NOT_STICK: frozenset(o for o in decided if outcome_class(o) == NOT_STICK),
    }
    members.update({o: frozenset({o}) for o in decided if o not in members})
    return members


def between_problems(names) -> list[tuple[int | tuple, str]]:
    """What is wrong with `between` (index, text): unknown names (the allowed ones
    listed), a repeated or overlapping pair."""
    members = side_members()
    allowed = ", ".join(members)
    problems: list[tuple[int | tuple, str]] = [
        (
            k,
            f"{name!r} is not an outcome or a class of outcomes; allowed: {allowed}"
            + did_you_mean(name, list(members)),
        )
        for k, name in enumerate(names)
        if name not in members
    ]
    if problems or len(names) != 2:
        return problems
    overlap = members[names[0]] & members[names[1]]
    if overlap:
        problems.append(
            (
                (),
                f"{names[0]} and {names[1]} share {', '.join(sorted(overlap))}: give two "
                "disjoint sides",
            )
        )
    return problems


def between_must() -> str:
    """What `between` accepts (a schema field's `must`)."""
    return "a list [A, B] of two different outcomes or classes: " + ", ".join(side_members())


def check_between(between: tuple[str, str]) -> tuple[str, str]:
    """A pydantic field check: `between` names two disjoint sides, else its problems."""
    problems = between_problems(list(between))
    if problems:
        raise rule(*problems)
    return between


# the schema type of a `between` key: [A, B], checked by check_between
BetweenPair = pair("A, B", between_must(), str, check_between)


@dataclasses.dataclass(frozen=True)
class Between:
    """The boundary between side `low` (A) and side `high` (B)."""

    low: str = NOT_STICK
    high: str = STICK
    reserve: bool = True  # the friction reserve may guide (a search in mu)

    def __post_init__(self):
        problems = between_problems([self.low, self.high])
        if problems:
            raise ValueError("; ".join(text for _, text in problems))

    @property
    def is_default(self) -> bool:
        return (self.low, self.high) == DEFAULT_BETWEEN

    @property
    def uses_reserve(self) -> bool:
        """The friction reserve guides the search (the stick / not-stick jump in mu only)."""
        return self.is_default and self.reserve

    def side(self, outcome: str) -> str | None:
        """HIGH, LOW, or None (undetermined, or a motion on neither side)."""
        members = side_members()
        if outcome in members[self.high]:
            return HIGH
        if outcome in members[self.low]:
            return LOW
        return None

    def is_high(self, outcome: str) -> bool:
        return self.side(outcome) == HIGH

    def is_low(self, outcome: str) -> bool:
        return self.side(outcome) == LOW

    def undecided_text(self, outcome: str) -> str:
        """How a run on neither side is named in a failure's reason."""
        if outcome == UNDETERMINED:
            return UNDETERMINED
        return f"{outcome} (neither {self.low} nor {self.high})"

    def label(self) -> str:
        return f"{self.low} | {self.high}"


NOT_STICK_STICK = Between()
