"""The outcomes a run can have (docs/model.md section 6), in the order tables and figures
list them, and the class of each: which side of the jump it lies on. Dependency-free, so
that planning, storage and figures can name them without loading the kernel; what decides
among them is verdict/label.py.

* stick: the slave co-rotates with the master for good (stick_rule corotation) or every
  contact stuck for a whole master revolution (contacts);
* creep: it ratchets on its small orbit, slipping a little every revolution for ever;
* stick_slip: sticking and sliding alternate (a cycle reached, or approached);
* self_centring: it slides to rest at a sliding equilibrium near the master's axis;
* slide_cycle: a pure-sliding limit cycle (the pin's large cycle, the axisymmetric disk's
  circular whirl), its own section repeating or contracting;
* modulated: a pure-sliding cycle whose amplitude and spin oscillate on a slow envelope;
* slide: it never sticks as a whole, and its motion is not (yet) shown to be one of the
  three above;
* undetermined: the run could not tell (a budget, a failure, or no evidence in time).

The jump is the boundary between the classes `stick` and `not_stick`; the pure-sliding
names only refine `not_stick` (a run that is not stick keeps that class whatever its name).
"""

STICK = "stick"
NOT_STICK = "not_stick"
UNDETERMINED = "undetermined"

# outcome -> class, in the listing order
OUTCOME_CLASS = {
    "stick": STICK,
    "creep": NOT_STICK,
    "stick_slip": NOT_STICK,
    "self_centring": NOT_STICK,
    "slide_cycle": NOT_STICK,
    "modulated": NOT_STICK,
    "slide": NOT_STICK,
    "undetermined": UNDETERMINED,
}
OUTCOMES = tuple(OUTCOME_CLASS)
CLASSES = (STICK, NOT_STICK, UNDETERMINED)
# the motions a run can be shown to settle on without sticking (refinements of `slide`)
SLIDING_MOTIONS = ("self_centring", "slide_cycle", "modulated")


def outcome_class(outcome: str) -> str:
    """`stick`, `not_stick` or `undetermined`; ValueError for a name that is no outcome."""
    try:
        return OUTCOME_CLASS[outcome]
    except KeyError:
        raise ValueError(f"unknown outcome {outcome!r}; outcomes: {', '.join(OUTCOMES)}") from None


def is_stick(outcome: str) -> bool:
    """True for the sticking solution (the stick side of the jump)."""
    return outcome_class(outcome) == STICK


def is_not_stick(outcome: str) -> bool:
    """True for a decided outcome on the not-stick side of the jump."""
    return outcome_class(outcome) == NOT_STICK
