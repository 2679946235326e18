"""Who was right where the default and the reference disagree, settled run by run.

A scene *disagrees* when the headline mu* (the lowest rising jump that persists) of the
default and of the reference differ by more than tol, or one finds a headline and the
other none. Each verdict the two sides claim at the disputed mu (`disputed`) is watched
(settings.py); a side is *wrong* where a watch contradicts one of its claims, and the
default is wrong too where it *missed a jump* (`missed_jump`). A watch that stays
undetermined leaves a dispute open only where the two sides claim different things there
(`implied_claim`). A row is a dict: seed, index, scene, each setting's `Found`, and the
watches `settled` (at the disputed mu) and `persisted` (above the reference's mu_hi).
"""

from __future__ import annotations

import math

from frictiondisk.studies.wellposed.found import Found
from frictiondisk.studies.wellposed.settings import PERSIST, SETTLE_MAX, TOL
from frictiondisk.verdict.outcomes import STICK, UNDETERMINED


def disagrees(found: Found, reference: Found) -> bool:
    """Headline mu* more than TOL apart, or a headline on one side only."""
    a, b = found.mu_star, reference.mu_star
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) != math.isnan(b)
    return abs(a - b) > TOL * (1 + 1e-9)


def disputed(default: Found, reference: Found) -> list[float]:
    """The mu whose verdicts settle a disagreement: both headline brackets' ends and every
    value either setting decided between the two headlines (the SETTLE_MAX nearest)."""
    heads = [m for m in (default.mu_star, reference.mu_star) if math.isfinite(m)]
    ends = [m for f in (default, reference) for m in (f.mu_lo, f.mu_hi) if math.isfinite(m)]
    if not heads:
        return []
    lo, hi = min(heads) - TOL, max(heads) + TOL
    inside = {mu for f in (default, reference) for mu, _ in f.claims if lo <= mu <= hi}
    centre = 0.5 * (lo + hi)
    inside = sorted(inside - set(ends), key=lambda mu: abs(mu - centre))
    return sorted({*ends, *inside[: max(0, SETTLE_MAX - len(ends))]})


def combine_watches(mu: float, regularized: dict, coulomb: dict | None = None) -> dict:
    """The settling run at mu from its watches (each: outcome, t_end, reason): the verdict
    they show; where both show one and they differ, none (`conflict`)."""
    watches = [regularized] if coulomb is None else [regularized, coulomb]
    decided = [w for w in watches if w["outcome"] != UNDETERMINED]
    shown = {w["outcome"] == STICK for w in decided}
    head = decided[0] if decided else watches[0]
    run = {
        "mu": mu,
        "outcome": head["outcome"] if len(shown) < 2 else "conflict",
        "sticks": next(iter(shown)) if len(shown) == 1 else None,
        "t_end": head["t_end"],
        "reason": "; ".join(w["reason"] for w in decided) if len(decided) > 1 else head["reason"],
    }
    if coulomb is not None:
        run["regularized"], run["coulomb"] = watches
    return run


def claim_at(found: Found, mu: float) -> bool | None:
    """The verdict `found` decided at exactly mu (None: none)."""
    for m, stick in found.claims:
        if m == mu:
            return stick
    return None


def lower_reference(row: dict) -> bool:
    """The reference's headline lies more than tol below the default's."""
    d, ref = row["default"].mu_star, row["reference"].mu_star
    return math.isfinite(d) and math.isfinite(ref) and ref < d - TOL * (1 + 1e-9)


def missed_jump(row: dict) -> bool:
    """Sticking that persists below the default's headline: the settling run at the
    reference's lower mu_hi sticks, and so does every watching run PERSIST_STEPS above it.
    The lowest rising jump then lies at or below that mu_hi (below it still where the
    reference's mu_lo sticks too), and the default did not report it. A default bracket that
    holds that mu_hi (one straddling undetermined mu, wider than tol) reported it."""
    if not lower_reference(row) or not row.get("persisted"):
        return False
    if row["reference"].mu_hi >= row["default"].mu_lo:
        return False
    seen = {run["mu"]: run["sticks"] for run in row["settled"]}
    sticks_above = seen.get(row["reference"].mu_hi) is True
    return sticks_above and all(run["sticks"] is True for run in row["persisted"])


def implied_claim(found: Found, mu: float) -> bool | None:
    """A side's claim at mu: the verdict it decided there; else, below its headline
    bracket, 'does not stick' (its headline is the lowest rising jump), and over the
    persistence width above it, 'sticks' (its headline persists)."""
    claim = claim_at(found, mu)
    if claim is not None or not math.isfinite(found.mu_star):
        return claim
    if mu < found.mu_lo:
        return False
    if found.mu_hi <= mu <= found.mu_hi + PERSIST * TOL:
        return True
    return None


def verdict(row: dict) -> str:
    """Which side the settling runs proved right: default (its claims stand; the
    reference's are refuted, or some stay open), reference, both (a window between their
    samples), neither, or unsettled (a claim of the default is open). A decided verdict
    refutes the side that claimed otherwise there; a missed jump (`missed_jump`) makes the
    default wrong. A watch that ends undetermined leaves open each side's claim there
    (`implied_claim`) where the two differ; where both say the same, as on a scene where
    they agree, the dispute is not there."""
    wrong = {"default": missed_jump(row), "reference": False}
    open_ = {"default": False, "reference": False}
    for run in row["settled"]:
        claims = {side: implied_claim(row[side], run["mu"]) for side in wrong}
        for side in wrong:
            if run["sticks"] is None:
                open_[side] |= claims[side] is not None and len(set(claims.values())) > 1
            elif claim_at(row[side], run["mu"]) not in (None, run["sticks"]):
                wrong[side] = True
    if wrong["default"] and wrong["reference"]:
        return "neither"
    if wrong["default"]:
        return "reference"
    if open_["default"]:
        return "unsettled"
    if wrong["reference"] or open_["reference"]:
        return "default"
    return "both"


def certified_ends(found: Found) -> list[float]:
    """The ends of a certified headline bracket (none without one)."""
    if not found.certified or not math.isfinite(found.mu_star):
        return []
    return [found.mu_lo, found.mu_hi]


def end_contradicted(row: dict) -> bool:
    """A certified headline bracket whose end its watch contradicts: the watch at mu_lo
    sticks, or the one at mu_hi shows it does not (a watch that stays undetermined
    contradicts nothing). An error even where mu* lies within tol of the reference's
    (a Stribeck disk's certified mu_lo that sticks at 171 s had mu* 0.4 tol off)."""
    return bool(contradicted_ends(row))


def end_claims(found: Found) -> dict[float, bool]:
    """What each end of a certified headline bracket claims: mu_lo does not stick, mu_hi
    sticks (empty without one)."""
    ends = certified_ends(found)
    return {ends[0]: False, ends[1]: True} if ends else {}


def contradicted_ends(row: dict) -> list[float]:
    """The ends of a certified headline bracket that their watches contradict."""
    claims = end_claims(row["default"])
    return [
        run["mu"]
        for run in row.get("ends", [])
        if run["mu"] in claims and run["sticks"] is not None and run["sticks"] != claims[run["mu"]]
    ]


def silent(row: dict) -> bool:
    """A default that calls its point certified, wrong: a disagreement settled against it,
    or an end of its bracket contradicted by its watch (`end_contradicted`)."""
    if "reference" not in row or not row["default"].certified:
        return False
    settled_against = disagrees(row["default"], row["reference"]) and verdict(row) in (
        "reference",
        "neither",
    )
    return settled_against or end_contradicted(row)


def silent_errors(rows: list[dict]) -> int:
    return sum(1 for r in rows if silent(r))
