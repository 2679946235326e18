"""Which settings the accuracy study runs: one ladder of values per knob, and its reference.

A *knob* is one thing the located mu* may depend on. Every knob has a ladder of settings
(scene overrides applied to the campaign point) and one *reference* setting, the best
available answer to the question that knob asks; a row's error is |mu* - mu*_ref| against
its own knob's reference. Pure Python: nothing is simulated here.

Integrator knobs (the answer should not depend on them; one reference for all three, the
tightest numerics, rodas4 at rtol 1e-9, atol 1e-12, NUMERICS_REFERENCE below):

* `rtol`     rodas4, rtol 1e-3 ... 1e-9 with atol = ATOL_PER_RTOL * rtol.
* `method`   the other integrators, each a series: rodas4-fixed over dt, scipy-radau over
             rtol, and (pin) the exact Coulomb model, whose distance from the reference is
             the regularization error at the scene's contact stiffness, not a numerics error.
* `preset`   numerics.preset fast, default, reference (config.NUMERICS_PRESETS).

The decision knob, against its own limit:

* `t_decide` the decision horizon, base numerics; reference = the longest horizon (a
             longer horizon can only see a late permanent stick that a shorter one missed).

Physics knobs (they change the model, so mu* converges to the limit the regularization
approximates, not to the numerics reference). Their rows run at the reference numerics so
that their error is the modelling error alone:

* `stiffness` contact stiffness c 2.53e4 ... 2.53e7 N/m with critical damping
              (contact.damping null, damping_ratio 1). Reference: the c -> infinity limit,
              the exact Coulomb model for the pin; for the disk (no Coulomb model) the
              stiffest c of the ladder, an estimate of the limit.
* `damping`   contact damping 0.1 ... 5 x critical (damping_ratio), at the scene's c.
              Reference: the same c -> infinity limit (damping has no limit of its own; the
              error says which damping approximates Coulomb friction best at this c).
* `eps`       slide->stick threshold 1e-12 ... 1e-4 m/s. Reference: the smallest eps.
* `points`    (disk only) contact points N = 1, 4, 12, 48, 192, 768 in the campaign's own
              contact.layout (ring or annulus). Reference: N = 768, the finest
              discretization of the continuous ring or facing. (The N = 768 rows at the
              reference numerics are slow; frictiondisk/studies/layouts.py runs the same
              sequence at the default numerics.)
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

from frictiondisk.model.presets import NUMERICS_PRESETS
from frictiondisk.model.scene import SceneConfig

ATOL_PER_RTOL = 1.0e-3  # atol = this * rtol: the default numerics' ratio (1e-9 / 1e-6)

RTOLS = (1.0e-3, 1.0e-4, 1.0e-5, 1.0e-6, 1.0e-7, 1.0e-8, 1.0e-9)
FIXED_DTS = (4.0e-2, 2.0e-2, 1.0e-2, 5.0e-3, 2.5e-3, 1.25e-3)  # [s] rodas4-fixed
RADAU_RTOLS = (1.0e-4, 1.0e-6, 1.0e-8)  # scipy-radau (slow: Python right-hand side)
T_DECIDES = (1.0, 2.0, 5.0, 10.0, 30.0, 120.0)  # [s]; 120 = 4 x the default 30 s
STIFFNESSES = (2.53e4, 8.0e4, 2.53e5, 8.0e5, 2.53e6, 8.0e6, 2.53e7)  # [N/m]
DAMPING_RATIOS = (0.1, 0.3, 1.0, 2.0, 5.0)  # fraction of critical 2 sqrt(c m_s)
EPSS = (1.0e-12, 1.0e-10, 1.0e-9, 1.0e-8, 1.0e-6, 1.0e-4)  # [m/s]
POINTS = (1, 4, 12, 48, 192, 768)

# --quick: short ladders and no Python-speed integrators (scipy-radau, coulomb), for tests
# and a first look. The references stay the same as in the full study (the Coulomb pin
# reference of `stiffness` and `damping` included).
QUICK = {
    "rtol": (1.0e-3, 1.0e-5, 1.0e-7, 1.0e-9),
    "dt": (2.0e-2, 1.0e-2),
    "radau": (),
    "t_decide": (2.0, 5.0, 30.0),
    "stiffness": (2.53e4, 2.53e5, 2.53e6),
    "damping": (0.1, 1.0, 5.0),
    "eps": (1.0e-12, 1.0e-9, 1.0e-4),
    "points": (1, 4, 12),
}

INTEGRATOR_KNOBS = ("rtol", "method", "preset")  # all against the numerics reference
OWN_LIMIT_KNOBS = ("t_decide", "stiffness", "damping", "eps", "points")  # each its own
PHYSICS_KNOBS = ("stiffness", "damping", "eps", "points")  # rows at the reference numerics
KNOBS = INTEGRATOR_KNOBS + OWN_LIMIT_KNOBS
DISK_ONLY = ("points",)


def atol_for(rtol: float) -> float:
    """atol = ATOL_PER_RTOL * rtol, rounded to 12 digits (so 1e-9 gives exactly 1e-12, the
    value a user would write, and equal numerics give equal content hashes)."""
    return float(f"{ATOL_PER_RTOL * rtol:.12g}")


NUMERICS_REFERENCE = {
    "numerics.method": "rodas4",
    "numerics.rtol": RTOLS[-1],
    "numerics.atol": atol_for(RTOLS[-1]),
}
NUMERICS_REFERENCE_LABEL = f"rodas4 rtol = {RTOLS[-1]:g}, atol = {atol_for(RTOLS[-1]):g}"


@dataclasses.dataclass(frozen=True)
class Setting:
    """One setting of a knob: the overrides it applies to the campaign point's scene.

    key: the dotted scene key it varies ("" if none); value: its value (NaN if not a
    number); tag: a short text for the figure ("1e-06", "fast"); label: a full name."""

    knob: str
    series: str
    key: str
    value: float
    tag: str
    label: str
    overrides: dict[str, Any]

    def config(self, base: SceneConfig) -> SceneConfig:
        return base.with_overrides(self.overrides)


@dataclasses.dataclass(frozen=True)
class Knob:
    """A ladder of settings and the reference its rows' errors are measured against."""

    name: str
    kind: str  # "numerics" or "physics"
    settings: tuple[Setting, ...]
    reference: Setting
    note: str  # what the reference is and why


def check_knobs(names: Sequence[str], scene: str) -> list[str]:
    """Problems with requested knob names (unknown, or not applicable to `scene`)."""
    problems = []
    for name in names:
        if name not in KNOBS:
            problems.append(f"--knobs: unknown knob {name!r}; allowed: {', '.join(KNOBS)}")
        elif name in DISK_ONLY and scene != "disk":
            problems.append(f"--knobs: knob {name!r} applies to scene 'disk' only, not {scene!r}")
    return problems


def default_knobs(scene: str) -> tuple[str, ...]:
    """Every knob that applies to `scene`."""
    return tuple(name for name in KNOBS if scene == "disk" or name not in DISK_ONLY)


def build_ladder(base: SceneConfig, knobs: Sequence[str], quick: bool = False) -> list[Knob]:
    """The knobs named in `knobs` (validated with `check_knobs`) for the scene `base`."""
    if problems := check_knobs(knobs, base.scene):
        raise ValueError("; ".join(problems))
    makers = {
        "rtol": _rtol,
        "method": _method,
        "preset": _preset,
        "t_decide": _t_decide,
        "stiffness": _stiffness,
        "damping": _damping,
        "eps": _eps,
        "points": _points,
    }
    return [makers[name](base, quick) for name in knobs]


# --- the knobs -----------------------------------------------------------------------------


def _values(name: str, full: tuple, quick: bool) -> tuple:
    return QUICK[name] if quick else full


def _numerics_reference(knob: str) -> Setting:
    return Setting(
        knob=knob,
        series="reference",
        key="numerics.rtol",
        value=RTOLS[-1],
        tag="ref",
        label=NUMERICS_REFERENCE_LABEL,
        overrides=dict(NUMERICS_REFERENCE),
    )


def _by_rtol(method: str, rtol: float, series: str, knob: str) -> Setting:
    """The setting of `method` at `rtol` (atol as atol_for gives it)."""
    return Setting(
        knob=knob,
        series=series,
        key="numerics.rtol",
        value=rtol,
        tag=f"{rtol:.0e}",
        label=f"{method} rtol = {rtol:g}, atol = {atol_for(rtol):g}",
        overrides={
            "numerics.method": method,
            "numerics.rtol": rtol,
            "numerics.atol": atol_for(rtol),
        },
    )


def _rtol(base: SceneConfig, quick: bool) -> Knob:
    settings = tuple(
        _by_rtol("rodas4", rtol, "rodas4 (rtol)", "rtol") for rtol in _values("rtol", RTOLS, quick)
    )
    return Knob(
        "rtol",
        "numerics",
        settings,
        _numerics_reference("rtol"),
        f"numerics reference: {NUMERICS_REFERENCE_LABEL} (the tightest rtol)",
    )


def _method(base: SceneConfig, quick: bool) -> Knob:
    settings = []
    for dt in _values("dt", FIXED_DTS, quick):
        settings.append(
            Setting(
                knob="method",
                series="rodas4-fixed (dt)",
                key="numerics.dt",
                value=dt,
                tag=f"{dt:g} s",
                label=f"rodas4-fixed dt = {dt:g} s",
                overrides={"numerics.method": "rodas4-fixed", "numerics.dt": dt},
            )
        )
    # scipy-radau implements the contacts rule only: for a disk under the co-rotation rule
    # its mu* would answer another question, so the series is left out (docs/accuracy.md)
    radau_fits = base.scene == "pin" or base.numerics.stick_rule == "contacts"
    for rtol in _values("radau", RADAU_RTOLS, quick) if radau_fits else ():
        settings.append(_by_rtol("scipy-radau", rtol, "scipy-radau (rtol)", "method"))
    if base.scene == "pin" and not quick:
        settings.append(_coulomb("method"))
    return Knob(
        "method",
        "numerics",
        tuple(settings),
        _numerics_reference("method"),
        f"numerics reference: {NUMERICS_REFERENCE_LABEL}; the coulomb row differs from it by "
        "the regularization (finite c), not by numerics",
    )


def _coulomb(knob: str) -> Setting:
    return Setting(
        knob=knob,
        series="coulomb (c = inf)",
        key="numerics.method",
        value=math.inf,
        tag="Coulomb",
        label="exact Coulomb pin (c -> infinity)",
        overrides={"numerics.method": "coulomb"},
    )


def _preset(base: SceneConfig, quick: bool) -> Knob:
    settings = tuple(
        Setting(
            knob="preset",
            series="numerics.preset",
            key="numerics.preset",
            value=NUMERICS_PRESETS[name]["rtol"],
            tag=name,
            label=f"numerics.preset = {name}",
            overrides={"numerics.preset": name},
        )
        for name in NUMERICS_PRESETS
    )
    return Knob(
        "preset",
        "numerics",
        settings,
        _numerics_reference("preset"),
        f"numerics reference: {NUMERICS_REFERENCE_LABEL}",
    )


def _t_decide(base: SceneConfig, quick: bool) -> Knob:
    values = _values("t_decide", T_DECIDES, quick)

    def setting(t: float) -> Setting:
        return Setting(
            knob="t_decide",
            series="t_decide",
            key="numerics.t_decide",
            value=t,
            tag=f"{t:g} s",
            label=f"t_decide = {t:g} s",
            overrides={"numerics.t_decide": t},
        )

    ref = setting(max(values))
    return Knob(
        "t_decide",
        "numerics",
        tuple(setting(t) for t in values),
        ref,
        f"the longest horizon, t_decide = {max(values):g} s, at the campaign's numerics",
    )


def _physics(knob: str, series: str, key: str, value: float, tag: str, extra=None) -> Setting:
    overrides = {**NUMERICS_REFERENCE, key: value, **(extra or {})}
    return Setting(knob, series, key, float(value), tag, f"{key} = {value:g}", overrides)


def _critical(c: float) -> dict[str, Any]:
    return {"contact.stiffness": c, "contact.damping": None, "contact.damping_ratio": 1.0}


def _c_limit(base: SceneConfig, knob: str) -> tuple[Setting, str]:
    """The c -> infinity reference: exact Coulomb (pin) or the stiffest c (disk)."""
    if base.scene == "pin":
        return _coulomb(knob), "the c -> infinity limit: the exact Coulomb pin (method coulomb)"
    c = STIFFNESSES[-1]
    ref = _physics(knob, "reference", "contact.stiffness", c, "ref", _critical(c))
    return ref, (
        f"estimate of the c -> infinity limit: the stiffest c = {c:g} N/m, critical damping, "
        f"{NUMERICS_REFERENCE_LABEL}"
    )


def _stiffness(base: SceneConfig, quick: bool) -> Knob:
    settings = tuple(
        _physics(
            "stiffness",
            "c (critical damping)",
            "contact.stiffness",
            c,
            f"{c:.3g}",
            _critical(c),
        )
        for c in _values("stiffness", STIFFNESSES, quick)
    )
    ref, note = _c_limit(base, "stiffness")
    return Knob("stiffness", "physics", settings, ref, note)


def _damping(base: SceneConfig, quick: bool) -> Knob:
    settings = tuple(
        _physics(
            "damping",
            "damping / critical",
            "contact.damping_ratio",
            ratio,
            f"{ratio:g}x",
            {"contact.damping": None},
        )
        for ratio in _values("damping", DAMPING_RATIOS, quick)
    )
    ref, note = _c_limit(base, "damping")
    return Knob("damping", "physics", settings, ref, note)


def _eps(base: SceneConfig, quick: bool) -> Knob:
    values = _values("eps", EPSS, quick)
    settings = tuple(_physics("eps", "eps", "contact.eps", eps, f"{eps:.0e}") for eps in values)
    ref = _physics("eps", "eps", "contact.eps", min(values), f"{min(values):.0e}")
    note = f"the smallest eps = {min(values):g} m/s, {NUMERICS_REFERENCE_LABEL}"
    return Knob("eps", "physics", settings, ref, note)


def _points(base: SceneConfig, quick: bool) -> Knob:
    values = _values("points", POINTS, quick)
    settings = tuple(
        _physics("points", "N contact points", "contact.points", n, f"N={n}") for n in values
    )
    top = max(POINTS)
    ref = _physics("points", "N contact points", "contact.points", top, f"N={top}")
    layout = "ring" if base.scene == "pin" else base.contact.layout
    note = f"the finest {layout}, N = {top} points, {NUMERICS_REFERENCE_LABEL}"
    return Knob("points", "physics", settings, ref, note)
