"""The outcomes a run can have (docs/model.md section 6): one `Outcome` record per motion,
in the order tables and figures list them, with everything that names or draws it: its
side of the jump, a one-line description, its colour, edge colour and marker in figures
and its legend text. Figures, CF metadata, tables, the CLI help and the studies read these
records; a new motion is its rule (verdict/) plus one row of `RECORDS`. Dependency-free,
so that planning, storage and figures can name them without loading the kernel; what
decides among them is verdict/label.py.

The jump is the boundary between the sides `stick` and `not_stick`; the pure-sliding
names only refine `not_stick` (a run that is not stick keeps that side whatever its name).
"""

from __future__ import annotations

import dataclasses

# the sides of the jump; `stick` and `undetermined` are also the names of outcomes
STICK = "stick"
NOT_STICK = "not_stick"
UNDETERMINED = "undetermined"
CLASSES = (STICK, NOT_STICK, UNDETERMINED)
# the outcome names, for code that must name one (everything else reads RECORDS)
CREEP = "creep"
STICK_SLIP = "stick_slip"
SELF_CENTRING = "self_centring"
SLIDE_CYCLE = "slide_cycle"
MODULATED = "modulated"
SLIDE = "slide"

STICK_COLOR = "#08306b"  # dark blue: sticking
SLIDE_COLOR = "#9ecae1"  # light blue: sliding
FAIL_COLOR = "tab:red"


@dataclasses.dataclass(frozen=True)
class Outcome:
    """One motion a run can be shown to settle on (or `undetermined`).

    name: the outcome as stored and printed; side: `stick`, `not_stick` or `undetermined`
    (its side of the jump); description: what the motion is, one line; color, edge: face
    and edge colour of its marker (matplotlib colours); marker: its matplotlib marker;
    legend: its legend entry in figures.
    """

    name: str
    side: str
    description: str
    color: str
    edge: str
    marker: str
    legend: str

    def __post_init__(self) -> None:
        if self.side not in CLASSES:
            raise ValueError(f"outcome {self.name!r}: side {self.side!r} not in {CLASSES}")


# the listing order of tables, figures and help texts
RECORDS: tuple[Outcome, ...] = (
    Outcome(
        STICK,
        STICK,
        "the slave co-rotates with the master for good (corotation), or every contact "
        "stuck for a whole master revolution (contacts)",
        STICK_COLOR,
        STICK_COLOR,
        "o",
        "stick",
    ),
    Outcome(
        CREEP,
        NOT_STICK,
        "it ratchets on its small orbit, slipping a little every revolution for ever",
        "#e0a040",
        "#9a6a1c",
        "D",
        "creep (ratchets on the small orbit)",
    ),
    Outcome(
        STICK_SLIP,
        NOT_STICK,
        "sticking and sliding alternate in the final window (settled or not: cycle_converged)",
        SLIDE_COLOR,
        "#3f6e8c",
        "o",
        "stick_slip (limit cycle)",
    ),
    Outcome(
        SELF_CENTRING,
        NOT_STICK,
        "it slides to rest at a sliding equilibrium near the master's axis",
        "#7fbf7f",
        "#3f7f3f",
        "v",
        "self_centring (slides to rest)",
    ),
    Outcome(
        SLIDE_CYCLE,
        NOT_STICK,
        "a pure-sliding limit cycle (the pin's large cycle, the axisymmetric disk's "
        "circular whirl), its own section repeating or contracting",
        "#b58fd6",
        "#6f4a94",
        "^",
        "slide_cycle (pure-sliding cycle)",
    ),
    Outcome(
        MODULATED,
        NOT_STICK,
        "a pure-sliding cycle whose amplitude and spin oscillate on a slow envelope",
        "#e07fb0",
        "#9a3f6e",
        "P",
        "modulated (cycle with a slow envelope)",
    ),
    Outcome(
        SLIDE,
        NOT_STICK,
        "it never sticks as a whole in the final window, and its motion is not yet shown to "
        "be one of the pure-sliding motions",
        "0.55",
        "0.35",
        "s",
        "slide (not stick, not settled)",
    ),
    Outcome(
        UNDETERMINED,
        UNDETERMINED,
        "the run could not tell (a budget, a failure, or no evidence in time)",
        FAIL_COLOR,
        FAIL_COLOR,
        "x",
        "undetermined",
    ),
)
BY_NAME: dict[str, Outcome] = {record.name: record for record in RECORDS}

# outcome -> class (side), in the listing order
OUTCOME_CLASS = {record.name: record.side for record in RECORDS}
OUTCOMES = tuple(OUTCOME_CLASS)
# the motions a run can be shown to settle on without sticking (refinements of `slide`)
SLIDING_MOTIONS = (SELF_CENTRING, SLIDE_CYCLE, MODULATED)


def record(outcome: str) -> Outcome:
    """The record of `outcome`; ValueError for a name that is no outcome."""
    try:
        return BY_NAME[outcome]
    except KeyError:
        raise ValueError(f"unknown outcome {outcome!r}; outcomes: {', '.join(OUTCOMES)}") from None


def outcome_class(outcome: str) -> str:
    """`stick`, `not_stick` or `undetermined`; ValueError for a name that is no outcome."""
    return record(outcome).side


def is_stick(outcome: str) -> bool:
    """True for the sticking solution (the stick side of the jump)."""
    return outcome_class(outcome) == STICK


def is_not_stick(outcome: str) -> bool:
    """True for a decided outcome on the not-stick side of the jump."""
    return outcome_class(outcome) == NOT_STICK


def names_text(conjunction: str = "or") -> str:
    """ "stick, creep, ..., slide or undetermined": every outcome, in the listing order."""
    return f"{', '.join(OUTCOMES[:-1])} {conjunction} {OUTCOMES[-1]}"
