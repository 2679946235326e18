"""`numerics.rtol: auto`: the numerics of a find_jump campaign, chosen from its tol.

A campaign asks for mu* to `find_jump.tol`. The numerics keys it does not give (rtol,
atol, t_decide) are chosen here, before anything runs, as the cheapest measured setting
whose expected mu* error is at most ERROR_FRACTION x tol. The expectation comes from an
error model of the scene's *kind* (`scene_kinds`): the table numerics_error.csv next to
this module, the mu* error measured per kind against rtol and atol and against the
decision horizon, with its provenance (the command and commit that generated it; the
generator is frictiondisk/studies/error_model.py) in its header. Nothing here is a value
for a particular campaign: the table is data, the rules below are the same for every
campaign.

Rules (docs/accuracy.md, "Numerics from the tol"):

* the error of a setting (rtol, atol) is the largest error measured at any setting at
  least as tight in both (the table's least monotone bound); a setting that was not
  measured is rated by the tightest measured setting at least as loose in both; none:
  unknown. The horizon's error likewise, non-increasing in t_decide;
* the expected error of a point is the numerics' error plus the horizon's, at the worst
  of its kinds (a Stribeck disk is rated as both a disk and a Stribeck pin), and of a
  campaign at the worst of its points;
* keys given explicitly win (rtol, atol, t_decide, a `numerics.preset`, a method other
  than rodas4, a numerics key varied along the campaign); the rest is chosen: the horizon
  first (the shortest measured one >= the default 30 s that leaves room for some measured
  numerics within the bound), then the cheapest measured rtol and atol within what is
  left (fewest steps per simulated second). Where the tol is out of reach, neither is
  pushed past what the other can use: the horizon is the shortest one whose error is
  negligible (a tenth) beside the best numerics' error, else the one with the least
  error, and the numerics come within a tenth of the horizon's error;
* the expected error is a prediction, never a proof: certification (docs/model.md section
  7) still re-checks every bracket at stricter numerics;
* a campaign whose numerics cannot reach its tol is told the smallest tol they reach (its
  floor: the least expected error of any horizon and setting it may take, over
  ERROR_FRACTION); `run` refuses it before any work, or with --tol-floor runs it at that
  floor.

A single run (`simulate`, scan, trajectory and basin campaigns) has no tol: there `auto`
is today's default numerics, rtol 1e-6, atol 1e-9, t_decide 30 s.
"""

from __future__ import annotations

import csv
import dataclasses
import io
import itertools
import math
from collections.abc import Iterable, Mapping
from functools import lru_cache
from importlib import resources
from typing import Any

from frictiondisk.model.scene import AUTO, AUTO_KEYS

ERROR_FRACTION = 0.1  # the expected mu* error is at most this x find_jump.tol (docs/accuracy.md)
TABLE = "numerics_error.csv"
DEFAULT_T_DECIDE = 30.0  # [s] the field default: auto never chooses a shorter horizon
NEGLIGIBLE = 0.1  # an error this fraction of another is negligible beside it
# the scene keys scene_kinds reads: a campaign varying one is rated at each of its values
KIND_KEYS = ("params.beta_b", "params.phidot0", "params.omega_m", "contact.stribeck.r")

KINDS = {
    "pin": "a pin (one contact)",
    "disk_corotating": "a disk started co-rotating (phidot0 = omega_m), no brake",
    "disk_from_rest": "a disk not started co-rotating, no brake",
    "disk_braked": "a braked disk (beta_b > 0)",
    "stribeck": "a Stribeck curve (contact.stribeck.r < 1)",
}


def scene_kinds(config) -> tuple[str, ...]:
    """The kinds of the error model a scene belongs to: its body (pin, or a disk started
    co-rotating, not co-rotating, or braked), and `stribeck` with a Stribeck curve."""
    params = config.params
    if config.scene == "pin":
        body = "pin"
    elif params.beta_b > 0:
        body = "disk_braked"
    elif params.phidot0 == params.omega_m:
        body = "disk_corotating"
    else:
        body = "disk_from_rest"
    return (body, "stribeck") if config.contact.stribeck.r < 1 else (body,)


# --- the table ---------------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class Row:
    """One measured setting of one kind: `knob` rtol (rtol and atol varied, t_decide the
    default) or t_decide; error = |mu* - mu*_ref| plus both bracket half widths (an upper
    bound); cost: accepted steps per simulated second."""

    kind: str
    knob: str
    rtol: float
    atol: float
    t_decide: float
    error: float
    cost: float


@dataclasses.dataclass(frozen=True)
class ErrorModel:
    rows: tuple[Row, ...]
    provenance: str  # the table's header: what measured it, and how

    def numerics_error(self, kind: str, rtol: float, atol: float) -> float | None:
        """Upper bound of the mu* error of (rtol, atol) at the default horizon (None: no
        measured setting at least as loose in both, or a kind not measured)."""
        rows = self._rows(kind, "rtol")
        looser = [r for r in rows if r.rtol >= rtol * _EPS and r.atol >= atol * _EPS]
        if not looser:
            return None
        return min(
            max(r.error for r in rows if r.rtol <= s.rtol * _UP and r.atol <= s.atol * _UP)
            for s in looser
        )

    def horizon_error(self, kind: str, t_decide: float) -> float | None:
        """Upper bound of the mu* error of the decision horizon t_decide [s] (None: shorter
        than every measured horizon, or a kind not measured)."""
        rows = self._rows(kind, "t_decide")
        shorter = [r for r in rows if r.t_decide <= t_decide * _UP]
        if not shorter:
            return None
        nearest = max(r.t_decide for r in shorter)
        return max(r.error for r in rows if r.t_decide >= nearest * _EPS)

    def settings(self, kind: str) -> list[Row]:
        """The measured (rtol, atol) settings of a kind."""
        return self._rows(kind, "rtol")

    def horizons(self) -> list[float]:
        return sorted({r.t_decide for r in self.rows if r.knob == "t_decide"})

    def kinds(self) -> set[str]:
        return {r.kind for r in self.rows}

    def _rows(self, kind: str, knob: str) -> list[Row]:
        return [r for r in self.rows if r.kind == kind and r.knob == knob]


_EPS = 1.0 - 1e-9  # float slack when comparing measured settings
_UP = 1.0 + 1e-9


@lru_cache(maxsize=1)
def error_model() -> ErrorModel:
    """The package's error model (numerics_error.csv)."""
    text = resources.files("frictiondisk.model").joinpath(TABLE).read_text(encoding="utf-8")
    return parse_table(text)


def parse_table(text: str) -> ErrorModel:
    """An ErrorModel from the CSV text of numerics_error.csv ('#' lines: provenance).
    Rows whose bisection did not converge are not settings the model can choose."""
    header = [line[1:].strip() for line in text.splitlines() if line.startswith("#")]
    body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    rows = []
    for item in csv.DictReader(io.StringIO(body)):
        if item["status"] != "converged" or item["is_reference"] == "1":
            continue
        rows.append(
            Row(
                kind=item["kind"],
                knob=item["knob"],
                rtol=float(item["rtol"]),
                atol=float(item["atol"]),
                t_decide=float(item["t_decide"]),
                error=float(item["error"]),
                cost=float(item["n_steps"]) / float(item["t_simulated"]),
            )
        )
    return ErrorModel(tuple(rows), "\n".join(header))


# --- the choice --------------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class NumericsChoice:
    """What numerics a find_jump campaign runs at, and why.

    rtol, atol, t_decide: the values (chosen or given); chosen: the keys chosen here;
    expected: the expected mu* error (None: unknown); bound: ERROR_FRACTION x tol;
    kinds: the scene kinds rated; reason: why nothing was chosen or rated ("" if rated)."""

    tol: float
    rtol: float
    atol: float
    t_decide: float
    chosen: tuple[str, ...]
    expected: float | None
    bound: float
    kinds: tuple[str, ...]
    reason: str = ""
    advice: str = ""  # what to do when they cannot reach the tol
    # where they cannot reach the tol: the smallest tol they reach (the keys given fixed),
    # two significant digits rounded up; else None
    floor: float | None = None
    horizon: str = ""  # the horizon named instead of t_decide ("t_max 4000 s": converge mode)

    @property
    def reaches(self) -> bool:
        """True unless the expected error is known and above the bound."""
        return self.expected is None or self.expected <= self.bound * _UP

    def overrides(self) -> dict[str, float]:
        """The dotted numerics keys to set on the base scene (the chosen ones)."""
        return {f"numerics.{key}": getattr(self, key) for key in self.chosen}

    def describe(self) -> str:
        """One line: what runs, and why, e.g. `tol 1e-08: rtol 1e-08, atol 1e-14,
        t_decide 30 s (auto; expected mu* error 7.4e-11 <= tol/10 = 1e-09; kind pin)`."""
        values = self._values()
        given = [key for key in AUTO_KEYS if key not in self.chosen]
        how = (
            "auto"
            if not given
            else "given"
            if not self.chosen
            else f"auto {', '.join(self.chosen)}; given {', '.join(given)}"
        )
        if self.reason:
            return f"tol {self.tol:g}: {values} ({how}; {self.reason})"
        relation = "<=" if self.reaches else ">"
        return (
            f"tol {self.tol:g}: {values} ({how}; expected mu* error {self.expected:.2g} "
            f"{relation} tol/{1 / ERROR_FRACTION:g} = {self.bound:.2g}; "
            f"kind {' + '.join(self.kinds)})"
        )

    def warning(self) -> str | None:
        """Why the numerics cannot reach the tol, with the floor they reach and what to do
        (None: they can). `run` refuses such a campaign unless --tol-floor."""
        if self.reaches:
            return None
        floor = f"; the smallest tol they reach is {self.floor:.2g}" if self.floor else ""
        return (
            f"numerics cannot reach find_jump.tol {self.tol:g}: expected mu* error "
            f"{self.expected:.2g} > tol/{1 / ERROR_FRACTION:g} = {self.bound:.2g} "
            f"({self._values()}; kind {' + '.join(self.kinds)}){floor}; {self.advice}"
        )

    def _values(self) -> str:
        horizon = self.horizon or f"t_decide {self.t_decide:g} s"
        return f"rtol {self.rtol:g}, atol {self.atol:g}, {horizon}"

    def attrs(self) -> dict[str, Any]:
        """results.nc attributes."""
        return {
            "numerics_choice": self.describe(),
            "numerics_auto_keys": ", ".join(self.chosen),
            "numerics_expected_mu_error": math.nan if self.expected is None else self.expected,
            "numerics_error_bound": self.bound,
            "numerics_kinds": ", ".join(self.kinds),
        }


def for_campaign(base, along: Mapping[str, Any], tol: float, numerics: Any) -> NumericsChoice:
    """The numerics of a find_jump campaign: `base` its validated base scene, `along` its
    varied keys and values, `numerics` the numerics mapping as written (which keys it
    gives; a `preset` gives rtol and atol)."""
    written = numerics if isinstance(numerics, Mapping) else {}
    given = {key for key in AUTO_KEYS if written.get(key, AUTO) != AUTO}
    if "preset" in written:
        given |= {"rtol", "atol"}
    values = {key: getattr(base.numerics, key) for key in given}
    written_keys = sorted(key for key in written if key in (*AUTO_KEYS, "preset"))
    varied = sorted(key for key in along if key.startswith("numerics."))
    if base.numerics.method != "rodas4":
        return unrated(tol, values, f"no error model for method {base.numerics.method!r}")
    if base.numerics.mode != "decide":  # its runs end at t_max, not t_decide
        reason = f"no error model for numerics.mode {base.numerics.mode!r}"
        horizon = f"t_max {base.numerics.t_max:g} s"
        return dataclasses.replace(unrated(tol, values, reason), horizon=horizon)
    if varied:
        return unrated(tol, values, f"{varied[0]} varied along the campaign: not rated")
    kinds = set()
    keys = [key for key in along if key in KIND_KEYS]
    for combination in itertools.product(*(along[key] for key in keys)):
        kinds.update(scene_kinds(base.with_overrides(dict(zip(keys, combination, strict=True)))))
    return choose(tol, kinds, values, names=written_keys)


def choose(
    tol: float,
    kinds: Iterable[str],
    given: Mapping[str, float],
    model: ErrorModel | None = None,
    names: Iterable[str] = (),
) -> NumericsChoice:
    """The numerics for find_jump.tol `tol` on scenes of `kinds`; `given` holds the keys
    of AUTO_KEYS the campaign fixes (with their values), the rest is chosen; `names`: the
    keys as written (e.g. `preset`), for the advice (default: those of `given`). Where
    they cannot reach the tol, `floor` is the smallest tol they reach."""
    model = model or error_model()
    kinds = tuple(sorted(set(kinds)))
    choice = _choose(tol, kinds, given, model, names)
    if choice.reaches or choice.expected is None:
        return choice
    floor = _floor(model, kinds, given)
    if floor is None:
        return choice
    advice = choice.advice
    if advice.startswith("no measured numerics"):
        advice = f"loosen find_jump.tol to at least {floor:.2g}"
    return dataclasses.replace(choice, floor=floor, advice=advice)


def _choose(
    tol: float,
    kinds: tuple[str, ...],
    given: Mapping[str, float],
    model: ErrorModel,
    names: Iterable[str] = (),
) -> NumericsChoice:
    """choose, without the floor."""
    bound = ERROR_FRACTION * tol
    missing = [kind for kind in kinds if kind not in model.kinds()]
    if missing:
        return unrated(tol, given, f"no error model for kind {missing[0]}", kinds)

    def horizon_error(t: float) -> float | None:
        return _worst(model.horizon_error(kind, t) for kind in kinds)

    def numerics_error(rtol: float, atol: float) -> float | None:
        return _worst(model.numerics_error(kind, rtol, atol) for kind in kinds)

    settings = _settings(model, kinds, given)
    rated = [(numerics_error(r, a), cost, r, a) for r, a, cost in settings]

    def reachable(t: float) -> bool:
        """Some setting fits in what the horizon t leaves of the bound."""
        spare = bound - _key(horizon_error(t))
        return any(_within(error, spare) for error, *_ in rated)

    if "t_decide" in given:
        t_decide = given["t_decide"]
    else:
        candidates = [t for t in model.horizons() if t >= DEFAULT_T_DECIDE * _EPS]
        t_decide = next((t for t in candidates if reachable(t)), None)
        if t_decide is None:  # out of reach: no horizon longer than the numerics can use
            floor = NEGLIGIBLE * min((_key(error) for error, *_ in rated), default=0.0)
            best = min(candidates, key=lambda t: (_key(horizon_error(t)), t), default=None)
            negligible = (t for t in candidates if _within(horizon_error(t), floor))
            t_decide = next(negligible, best) or DEFAULT_T_DECIDE
    t_error = horizon_error(t_decide) or 0.0
    # where the horizon alone misses the bound, numerics far more accurate than its
    # error would not locate mu* better
    target = max(bound - t_error, NEGLIGIBLE * t_error)
    fits = [item for item in rated if _within(item[0], target)]
    if fits:  # the cheapest; of equal cost the loosest
        _, _, rtol, atol = min(fits, key=lambda item: (item[1], -item[2], -item[3]))
    else:  # the most accurate there is; of equal error the cheapest
        _, _, rtol, atol = min(rated, key=lambda item: (_key(item[0]), item[1]))
    n_error, t_error = numerics_error(rtol, atol), horizon_error(t_decide)
    expected = None if n_error is None or t_error is None else n_error + t_error
    chosen = tuple(key for key in AUTO_KEYS if key not in given)
    values = {"rtol": rtol, "atol": atol, "t_decide": t_decide}
    reason = "" if expected is not None else "expected mu* error unknown: not measured"
    advice = "no measured numerics and horizon reach it: loosen find_jump.tol"
    if given and expected is not None and expected > bound * _UP:
        if _choose(tol, kinds, {}, model).reaches:
            fixed = ", ".join(sorted(names) or sorted(given))
            advice = f"leave {fixed} out to let the tol choose them"
    return NumericsChoice(tol, *values.values(), chosen, expected, bound, kinds, reason, advice)


def _floor(model: ErrorModel, kinds: tuple[str, ...], given: Mapping[str, float]) -> float | None:
    """The smallest tol whose choice reaches it, to two significant digits (rounded up):
    of the expected errors of the horizons and settings `choose` may take (the given keys
    fixed), the least whose tol (error / ERROR_FRACTION) `choose` reaches; None if none."""
    if "t_decide" in given:
        horizons = [given["t_decide"]]
    else:
        horizons = [t for t in model.horizons() if t >= DEFAULT_T_DECIDE * _EPS]
    errors = set()
    for t in horizons:
        t_error = _worst(model.horizon_error(kind, t) for kind in kinds)
        for rtol, atol, _ in _settings(model, kinds, given):
            n_error = _worst(model.numerics_error(kind, rtol, atol) for kind in kinds)
            if t_error is not None and n_error is not None and t_error + n_error > 0:
                errors.add(_round_up((t_error + n_error) / ERROR_FRACTION))
    return next((tol for tol in sorted(errors) if _choose(tol, kinds, given, model).reaches), None)


def _round_up(value: float) -> float:
    """`value` > 0 rounded up to two significant digits (7.31e-10 -> 7.4e-10)."""
    step = 10.0 ** (math.floor(math.log10(value)) - 1)
    return float(f"{math.ceil(value / step * (1 - 1e-12)) * step:.2g}")


def _settings(model: ErrorModel, kinds, given) -> list[tuple[float, float, float]]:
    """(rtol, atol, cost) to choose from: the measured settings, or with rtol and/or atol
    given, those values with the measured ratios or rtols; cost: the worst kind's."""
    measured = {}
    for kind in kinds:
        for row in model.settings(kind):
            key = (row.rtol, row.atol)
            measured[key] = max(measured.get(key, 0.0), row.cost)
    if "rtol" in given and "atol" in given:
        return [(given["rtol"], given["atol"], 0.0)]
    if "rtol" in given:
        ratios = sorted({_round(a / r) for r, a in measured}, reverse=True)
        return [(given["rtol"], _round(ratio * given["rtol"]), i) for i, ratio in enumerate(ratios)]
    if "atol" in given:
        rtols = sorted({r for r, _ in measured}, reverse=True)
        return [(rtol, given["atol"], i) for i, rtol in enumerate(rtols)]
    return [(r, a, cost) for (r, a), cost in measured.items()]


def unrated(tol: float, given: Mapping[str, float], reason: str, kinds=()) -> NumericsChoice:
    """Nothing chosen, nothing rated: the given keys, today's defaults for the rest."""
    values = {"rtol": 1.0e-6, "atol": 1.0e-9, "t_decide": DEFAULT_T_DECIDE, **given}
    bound = ERROR_FRACTION * tol
    return NumericsChoice(
        tol, *(values[k] for k in AUTO_KEYS), (), None, bound, tuple(kinds), reason
    )


def _worst(errors: Iterable[float | None]) -> float | None:
    errors = list(errors)
    return None if any(e is None for e in errors) else max(errors, default=0.0)


def _within(error: float | None, bound: float) -> bool:
    return error is not None and error <= bound * _UP


def _key(error: float | None) -> float:
    return math.inf if error is None else error


def _round(value: float) -> float:
    """12 significant digits: 1e-3 x 1e-6 gives exactly 1e-9, as a user would write it."""
    return float(f"{value:.12g}")
