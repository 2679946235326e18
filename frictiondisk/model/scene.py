"""Validated scene configuration (docs/model.md section 5): models, loading, canonical form, hash.

Defaults, units and allowed ranges live only in the model fields below. Each field's
`description` ends with its unit in brackets and `json_schema_extra["unit"]` holds the
unit alone ("1" = dimensionless); error messages read the bounds from the fields.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Mapping, Sequence
from os import PathLike
from typing import Any, Literal

import numpy as np
from pydantic import BaseModel, Field, ValidationError, model_validator
from pydantic_core import PydanticCustomError

from frictiondisk.model import layouts
from frictiondisk.model.overrides import apply_overrides, parse_override
from frictiondisk.model.presets import NUMERICS_PRESETS
from frictiondisk.model.scene_keys import drop_unused, unused_keys, without_unused
from frictiondisk.model.schema import (
    INT64_MAX,
    MODEL_CONFIG,
    extra_of,
    field_at,
    merged,
    problems_of,
)
from frictiondisk.model.schema import field as _field
from frictiondisk.model.yamlio import ConfigError, dump_yaml, load_yaml_file

__all__ = [
    "ConfigError",
    "Contact",
    "Numerics",
    "Params",
    "SceneConfig",
    "Stribeck",
    "load_scene",
    "scene_from_dict",
]

DEFAULT_DISK_POINTS = 12  # contact points of a disk when contact.points is null
MAX_POINTS = 1000  # most contact points of a scene

# Upper bounds that keep the kernel's arithmetic meaningful. Integers go to the
# kernel as int64. Lengths, speeds and the master speed are bounded far beyond any friction
# disk, so that squared terms stay finite and one revolution stays longer than a step:
# x_ms = omega_m = vx0 = 1e300 made a revolution 6e-300 s, "decided" stick after 0 steps.
MAX_LENGTH = 1.0e3  # [m]
MAX_SPEED = 1.0e4  # [m/s]
MAX_OMEGA = 1.0e4  # [rad/s]
MAX_HORIZON = 1.0e9  # [s] simulated time of one run, retries included
MAX_HORIZON_BUDGET = 1000.0  # largest numerics.horizon_budget (certification levels included)
AUTO, AUTO_KEYS = "auto", ("rtol", "atol", "t_decide")  # model/auto_numerics.py
AUTO_DOC, MUST = "; auto: from find_jump.tol", "a finite number > 0{}, or 'auto'"


def _layout_error(name: str, value: Any, message: str) -> None:
    """Reject contact.<name> (a layout rule): the message names the field and the rule."""
    raise PydanticCustomError("layout_rule", message, {"path": f"contact.{name}", "value": value})


class Stribeck(BaseModel):
    """Stribeck curve mu(v) = mu*[r + (1 - r)*exp(-(v/v_s)**delta)] (docs/model.md section 3)."""

    model_config = MODEL_CONFIG

    r: float = _field(1.0, "1", "ratio mu_kinetic/mu_static; 1 is Coulomb friction", gt=0, le=1)
    v_s: float = _field(1.0e-3, "m/s", "Stribeck velocity", gt=0)
    delta: float = _field(1.0, "1", "Stribeck exponent", gt=0)


class Params(BaseModel):
    """Physical parameters and initial state (paper symbols, docs/model.md sections 2 and 5)."""

    model_config = MODEL_CONFIG

    mu: float = _field(0.13, "1", "static friction coefficient", gt=0)
    omega_m: float = _field(1.1, "rad/s", "angular velocity of the master disk", ge=0, le=MAX_OMEGA)
    c_s: float = _field(1.0, "N/m", "stiffness of the slave's support spring", ge=0)
    beta_s: float = _field(0.1, "N s/m", "damping of the slave's support", ge=0)
    m_s: float = _field(1.0, "kg", "slave mass", gt=0)
    F_n: float = _field(1.0, "N", "total normal force", gt=0)
    J_s: float = _field(0.02, "kg m^2", "moment of inertia of the slave disk", gt=0)
    beta_b: float = _field(0.0, "N m s/rad", "brake (rotational viscous) damping", ge=0)
    x_ms: float = _field(
        0.1,
        "m",
        "axes offset: the slave's rest position is (x_ms, 0)",
        ge=-MAX_LENGTH,
        le=MAX_LENGTH,
    )
    x0: float = _field(
        0.0,
        "m",
        "initial spring deflection: the slave starts at x_ms + x0",
        ge=-MAX_LENGTH,
        le=MAX_LENGTH,
    )
    y0: float = _field(0.0, "m", "initial y position of the slave", ge=-MAX_LENGTH, le=MAX_LENGTH)
    vx0: float = _field(0.0, "m/s", "initial x velocity of the slave", ge=-MAX_SPEED, le=MAX_SPEED)
    vy0: float = _field(0.0, "m/s", "initial y velocity of the slave", ge=-MAX_SPEED, le=MAX_SPEED)
    phidot0: float = _field(
        0.0,
        "rad/s",
        "initial angular velocity of the slave disk",
        ge=-MAX_OMEGA,
        le=MAX_OMEGA,
    )


class Contact(BaseModel):
    """Regularized friction contact (docs/model.md section 3); the totals c, beta, F_n are
    spread over the points of `layout` by their weights (frictiondisk/model/layouts.py)."""

    model_config = MODEL_CONFIG

    stiffness: float = _field(2.53e5, "N/m", "contact stiffness c", gt=0)
    damping: float | None = _field(
        None, "N s/m", "contact damping beta; null: damping_ratio*2*sqrt(stiffness*m_s)", gt=0
    )
    damping_ratio: float = _field(
        1.0,
        "1",
        "damping as a fraction of critical 2*sqrt(stiffness*m_s), if damping is null",
        gt=0,
    )
    eps: float = _field(1.0e-9, "m/s", "slip-rate threshold of the slide->stick event", gt=0)
    layout: Literal["ring", "annulus", "points"] = _field(
        "ring",
        None,
        "where the disk's contacts lie: ring (ring_radius), annulus (inner_radius, "
        "outer_radius; uniform pressure) or points (positions, weights)",
    )
    points: int | None = _field(
        None,
        "1",
        f"number of contact points; null: 1 (pin), {DEFAULT_DISK_POINTS} (disk ring or "
        "annulus), len(positions) (layout points)",
        ge=1,
        le=MAX_POINTS,
    )
    ring_radius: float = _field(0.05, "m", "radius of the ring of disk contact points", gt=0)
    inner_radius: float | None = _field(
        None, "m", "inner radius of the annulus (layout annulus only)", ge=0
    )
    outer_radius: float | None = _field(
        None, "m", "outer radius of the annulus, > inner_radius (layout annulus only)", gt=0
    )
    positions: list[list[float]] | None = _field(
        None, "m", "body-frame contact points [[x, y], ...] (layout points only)"
    )
    weights: list[float] | None = _field(
        None,
        "1",
        "share of each point in normal force, stiffness and damping, each > 0, normalized "
        "to sum 1; null: equal (layout points only)",
    )
    stribeck: Stribeck = Field(default_factory=Stribeck, description="Stribeck curve")

    @model_validator(mode="after")
    def _layout_fields(self) -> Contact:
        """Each layout's own fields are given (the other layouts' are refused by SceneConfig,
        frictiondisk.model.scene_keys)."""
        own = {"annulus": ("inner_radius", "outer_radius"), "points": ("positions",)}
        for name in own.get(self.layout, ()):
            if getattr(self, name) is None:
                _layout_error(name, None, f"layout {self.layout!r} needs it")
        if self.layout == "annulus" and self.outer_radius <= self.inner_radius:
            _layout_error(
                "outer_radius",
                self.outer_radius,
                f"must be > inner_radius = {self.inner_radius} m",
            )
        if self.layout == "points":
            self._check_points()
        return self

    def _check_points(self) -> None:
        n = len(self.positions)
        if not 1 <= n <= MAX_POINTS:
            _layout_error("positions", self.positions, f"must hold 1 to {MAX_POINTS} points")
        for i, xy in enumerate(self.positions):
            if len(xy) != 2:
                _layout_error(f"positions.{i}", xy, "must be a pair [x, y] of numbers in m")
        if self.points is not None and self.points != n:
            _layout_error("points", self.points, f"must be null or len(positions) = {n}")
        if self.weights is not None:
            if len(self.weights) != n:
                _layout_error("weights", self.weights, f"must have one weight per position ({n})")
            for i, w in enumerate(self.weights):
                if not w > 0.0:
                    _layout_error(f"weights.{i}", w, "must be > 0")


class Numerics(BaseModel):
    """Integrator, tolerances, horizons and limit-cycle detection.

    `preset` (fast, default, reference) fills method, rtol, atol, dt and h_max from
    NUMERICS_PRESETS; a key given explicitly next to it wins. The preset name itself is not
    part of the canonical form (SceneConfig.canonical): only the values it resolved to are,
    so equal numerics give equal content hashes and journal keys however they were written.
    """

    model_config = MODEL_CONFIG

    method: Literal["rodas4", "rodas4-fixed", "rodas5", "scipy-radau", "coulomb"] = _field(
        "rodas4", None, "integration method"
    )
    rtol: float = _field(
        1.0e-6, "1", "relative tolerance" + AUTO_DOC, MUST.format(" and < 1"), gt=0, lt=1
    )
    atol: float = _field(
        1.0e-9, None, "absolute tolerance, each state's SI unit" + AUTO_DOC, MUST.format(""), gt=0
    )
    # dt = 0.01 s resolves the 4 ms initial contact transient (R1 error 4e-10 m on the default pin);
    # 0.02 s does not (first stick misplaced by 0.2 s).
    dt: float = _field(1.0e-2, "s", "step of rodas4-fixed", gt=0)
    h_max: float = _field(0.1, "s", "largest step", gt=0)
    mode: Literal["decide", "converge"] = _field(
        "decide", None, "decide: stick or not; converge: run to a converged limit cycle"
    )
    # Measured: over 930 pin and disk runs (x_ms 0.02-0.2 m, x0 -0.05-0.05 m, mu 0.5-2 x the
    # oracle) with a 600 s horizon, every permanent stick began before t = 4.8 s.
    t_decide: float = _field(
        30.0,
        "s",
        "decision horizon in mode decide" + AUTO_DOC,
        MUST.format(f" and <= {MAX_HORIZON:g} s"),
        gt=0,
        le=MAX_HORIZON,
    )
    t_max: float = _field(
        3000.0, "s", "simulated-time horizon in mode converge", gt=0, le=MAX_HORIZON
    )
    stop_on_stick: bool = _field(True, None, "stop the run at permanent stick")
    window_revs: float = _field(2.0, "1", "final window, in master revolutions", gt=0)
    cycle_tol: float = _field(1.0e-6, "m", "limit-cycle section points agreement", gt=0)
    cycle_count: int = _field(
        3, "1", "successive section points that must agree", ge=2, le=INT64_MAX
    )
    stick_rule: Literal["corotation", "contacts"] = _field(
        "corotation",
        None,
        "what `stick` means: corotation = the slave co-rotates with the master without net "
        "slip (slip per revolution decays to zero; docs/model.md); contacts = every contact "
        "stays in stick mode for one whole revolution",
    )
    evidence: Literal["extrapolate", "observe"] = _field(
        "extrapolate",
        None,
        "what a verdict may rest on (docs/model.md section 6): extrapolate = also a section "
        "that contracts geometrically to a cycle, departs from sticking, or a slip that "
        "extrapolates to nothing (shakedown); observe = only what the run shows: it sticks, "
        "or its section repeats (for settling disputes with long runs)",
    )
    observe_until: float = _field(
        0.0,
        "s",
        "evidence extrapolate: decide only on what the run shows (as evidence observe) until "
        "this time, then by the rules; no not-stick verdict before it (a certification run's "
        "watch of an extrapolated verdict, docs/model.md section 7). 0: no watch",
        ge=0,
        le=MAX_HORIZON,
    )
    follow_departures_until: float = _field(
        0.0,
        "s",
        "a departure from sticking (slip not falling, sticking time not growing, section "
        "after section) decides only at the last horizon before this time, and only where "
        "the slave sticks as a whole in its steps: until then the run follows it to where it "
        "lands (a cycle, a stick, sliding). A certification run's check of an extrapolated "
        "verdict sets it (docs/model.md section 7). 0: a departure decides when seen",
        ge=0,
        le=MAX_HORIZON,
    )
    horizon_budget: float = _field(
        8.0,
        "1",
        "stick_rule corotation: a run still settling at its horizon may extend it, one "
        "revolution at a time, up to this multiple of t_decide (t_max in mode converge)",
        ge=1,
        le=MAX_HORIZON_BUDGET,
    )
    max_steps: int = _field(2_000_000, "1", "step budget of one run", ge=1, le=INT64_MAX)
    max_events: int = _field(
        200_000, "1", "mode-switch event budget of one run", ge=1, le=INT64_MAX
    )
    preset: Literal["fast", "default", "reference"] = _field(
        "default",
        None,
        "numerics preset: sets method, rtol, atol, dt, h_max unless given explicitly",
    )

    @model_validator(mode="before")
    @classmethod
    def _resolve_preset(cls, data: Any) -> Any:
        """Drop the keys given as `auto` (their defaults here; a find_jump campaign
        chooses them, tasks/campaign.py), then fill the preset's keys that `data` does
        not give (explicit keys win)."""
        if isinstance(data, Mapping):
            data = {k: v for k, v in data.items() if not (k in AUTO_KEYS and v == AUTO)}
            name = data.get("preset", "default")
            if isinstance(name, str) and name in NUMERICS_PRESETS:
                return {**NUMERICS_PRESETS[name], **data}
        return data  # not a mapping or a bad preset: field validation reports it


class SceneConfig(BaseModel):
    """One validated scene: build it with `load_scene` or `scene_from_dict`."""

    model_config = MODEL_CONFIG

    scene: Literal["pin", "disk"] = Field(
        description="pin: point mass on one contact; disk: slave disk on contact.points"
    )
    params: Params = Field(default_factory=Params, description="physical parameters")
    contact: Contact = Field(default_factory=Contact, description="friction contact")
    numerics: Numerics = Field(default_factory=Numerics, description="numerical settings")

    @model_validator(mode="after")
    def _pin_has_one_contact(self) -> SceneConfig:
        if self.scene == "pin" and self.contact.points not in (None, 1):
            raise PydanticCustomError(
                "scene_rule",
                "a pin has exactly one contact; use 1 or null",
                {"path": "contact.points", "value": self.contact.points, "scene": self.scene},
            )
        if (
            self.scene == "disk"
            and self.numerics.method == "scipy-radau"
            and self.numerics.stick_rule == "corotation"
        ):
            raise PydanticCustomError(
                "scene_rule",
                "the scipy-radau cross-check measures no slip per revolution; set "
                "numerics.stick_rule: contacts for a disk (the rules agree for the pin)",
                {"path": "numerics.stick_rule", "value": "corotation", "scene": self.scene},
            )
        if self.scene != "pin" and self.numerics.method == "coulomb":
            raise PydanticCustomError(
                "scene_rule",
                "the exact Coulomb model exists for scene pin only",
                {"path": "numerics.method", "value": "coulomb", "scene": self.scene},
            )
        if self.numerics.method == "coulomb" and self.numerics.observe_until > 0.0:
            raise PydanticCustomError(
                "scene_rule",
                "the exact Coulomb pin has no watch: numerics.observe_until needs method "
                "rodas4, rodas4-fixed, rodas5 or scipy-radau (or numerics.evidence: observe)",
                {
                    "path": "numerics.observe_until",
                    "value": self.numerics.observe_until,
                    "scene": self.scene,
                },
            )
        return self

    @model_validator(mode="wrap")
    @classmethod
    def _only_keys_the_scene_uses(cls, data: Any, handler: Any) -> SceneConfig:
        """A key the scene does not use (a pin's spin or contact layout, another layout's
        keys on a disk) is refused, next to the problems of the other keys (defined after
        the rules above, so that it wraps them)."""
        if not isinstance(data, Mapping):
            return handler(data)
        data, problems = without_unused(data)
        return merged(handler, data, problems, list(cls.model_fields))

    @property
    def n_contacts(self) -> int:
        """Number of contact points N: 1 for a pin; for a disk `contact.points` or 12, or
        len(contact.positions) for layout points."""
        if self.scene == "pin":
            return 1
        if self.contact.layout == "points":
            return len(self.contact.positions)
        return self.contact.points or DEFAULT_DISK_POINTS

    @property
    def contact_damping(self) -> float:
        """Total contact damping beta [N s/m]: `damping`, else a fraction of critical."""
        if self.contact.damping is not None:
            return self.contact.damping
        critical = 2.0 * math.sqrt(self.contact.stiffness * self.params.m_s)
        return self.contact.damping_ratio * critical

    def _layout(self) -> tuple[np.ndarray, np.ndarray]:
        con = self.contact
        if self.scene == "pin":
            return np.zeros((1, 2)), np.ones(1)
        return layouts.layout(
            con.layout,
            self.n_contacts,
            con.ring_radius,
            con.inner_radius,
            con.outer_radius,
            con.positions,
            con.weights,
        )

    def contact_positions(self) -> np.ndarray:
        """Body-frame contact points p_i [m], shape (N, 2), of `contact.layout`
        (frictiondisk/model/layouts.py); a pin's one contact is at its centre."""
        return self._layout()[0]

    def contact_weights(self) -> np.ndarray:
        """Relative weights N w_i (mean 1), shape (N,): contact i carries w_i of F_n, c
        and beta. Exactly 1.0 for every point of a ring."""
        return layouts.relative_weights(self._layout()[1])

    def contact_layout(self) -> tuple[np.ndarray, np.ndarray]:
        """(`contact_positions()`, `contact_weights()`) from one layout."""
        positions, shares = self._layout()
        return positions, layouts.relative_weights(shares)

    def canonical(self) -> dict[str, Any]:
        """Plain JSON-able dict, every default filled in, `points` resolved, keys sorted.

        Only the keys the scene uses are kept (frictiondisk.model.scene_keys): a pin has no
        spin and no layout keys; a disk keeps the fields of its `contact.layout` (ring:
        ring_radius; annulus: inner_radius, outer_radius; points: positions and weights,
        null weights written out as equal ones)."""
        data = drop_unused(self.model_dump(mode="json"), self.scene, self.contact.layout)
        data["contact"]["points"] = self.n_contacts
        if self.contact.layout == "points" and self.contact.weights is None:
            data["contact"]["weights"] = [1.0] * self.n_contacts
        # the preset is resolved into concrete values; its name is not content
        del data["numerics"]["preset"]
        if not data["numerics"]["observe_until"]:  # absent when off: run keys stay as they were
            del data["numerics"]["observe_until"]
        if not data["numerics"]["follow_departures_until"]:
            del data["numerics"]["follow_departures_until"]
        return _sorted(data)

    def content_hash(self) -> str:
        """sha256 hex digest of the canonical dict as compact, key-sorted JSON."""
        text = json.dumps(self.canonical(), sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(text.encode()).hexdigest()

    def to_yaml(self) -> str:
        """The canonical dict as YAML; `load_scene` reads it back to the same canonical form."""
        return dump_yaml(self.canonical())

    def with_overrides(self, overrides: Mapping[str, Any]) -> SceneConfig:
        """New validated config with dotted keys set, e.g. {"params.mu": 0.12}.

        Setting "numerics.preset" sets every key of that preset too (the values of this
        config are all explicit by now), except keys given in the same `overrides`. The
        keys of this config that the new scene does not use are dropped (a disk made a
        pin loses its spin); an override naming one is refused.
        """
        quick = self._with_section_values(overrides)
        if quick is not None:
            return quick
        name = overrides.get("numerics.preset")
        if isinstance(name, str) and name in NUMERICS_PRESETS:
            implied = {f"numerics.{key}": value for key, value in NUMERICS_PRESETS[name].items()}
            overrides = {**implied, **overrides}
        origins = {key: f"override {key}" for key in overrides}
        scene = overrides.get("scene", self.scene)
        layout = overrides.get("contact.layout", self.contact.layout)
        data = drop_unused(self.model_dump(), scene, layout)
        data = apply_overrides(data, overrides.items(), "<overrides>")
        return _validate(data, "<overrides>", origins)

    def _with_section_values(self, overrides: Mapping[str, Any]) -> SceneConfig | None:
        """`with_overrides` of keys `section.field` that leave the scene's structure as it
        is, validated section by section: a section no key changes is this config's own,
        valid as it stands, and the scene's rules are checked again on the whole. About a
        third of the full validation's cost (a campaign's points, a basin's samples). None
        where it does not apply, or where any value is refused: the full path then says
        why, naming the key."""
        unused = unused_keys(self.scene, self.contact.layout)
        changes: dict[str, dict[str, Any]] = {}
        for key, value in overrides.items():
            section, _, name = key.partition(".") if isinstance(key, str) else ("", "", "")
            if name not in _SECTION_FIELDS.get(section, ()) or key in unused:
                return None
            if not _same(value, getattr(getattr(self, section), name)):
                changes.setdefault(section, {})[name] = value
        if not changes:
            return self
        data = {"scene": self.scene, **{name: getattr(self, name) for name in _SECTION_FIELDS}}
        try:
            for section, values in changes.items():
                model = data[section]
                data[section] = type(model).model_validate({**model.model_dump(), **values})
            return SceneConfig.model_validate(data)
        except ValidationError:
            return None


def scene_from_dict(
    data: Any, overrides: Sequence[str] = (), source: str = "<dict>"
) -> SceneConfig:
    """Validate `data` (e.g. parsed YAML) after applying `KEY=VALUE` override strings.

    Raises ConfigError listing every problem as `dotted.path: message`.
    """
    if isinstance(overrides, str):
        raise TypeError(
            "overrides must be a sequence of 'KEY=VALUE' strings, not one string: "
            f"write [{overrides!r}]"
        )
    pairs, problems = [], []
    for text in overrides:
        try:
            pairs.append(parse_override(text, source))
        except ConfigError as err:
            problems += err.problems
    if problems:
        raise ConfigError(problems, source)
    origins = {key: f"--set {text}" for (key, _), text in zip(pairs, overrides, strict=True)}
    return _validate(apply_overrides(data, pairs, source), source, origins)


def load_scene(path: str | PathLike[str], overrides: Sequence[str] = ()) -> SceneConfig:
    """Load and validate a scene YAML file; `overrides` are CLI `--set KEY=VALUE` strings."""
    return scene_from_dict(load_yaml_file(path), overrides, source=str(path))


# --- validation -------------------------------------------------------------------


def _validate(data: Any, source: str, origins: Mapping[str, str]) -> SceneConfig:
    try:
        return SceneConfig.model_validate(data)
    except ValidationError as err:
        problems = problems_of(err, SceneConfig, origins, unused=_unused_keys(data))
        raise ConfigError(problems, source) from None


def _unused_keys(data: Any) -> tuple[str, ...]:
    """The dotted keys the scene as given does not use (a pin's spin and layout keys),
    left out of the allowed keys an unknown key's message lists."""
    if not isinstance(data, Mapping):
        return ()
    contact = data.get("contact")
    layout = contact.get("layout", "ring") if isinstance(contact, Mapping) else "ring"
    return tuple(unused_keys(data.get("scene"), layout))


def describe_key(dotted: str) -> tuple[str | None, str]:
    """Unit ("1" = dimensionless, None = not a quantity) and description of a scene key,
    e.g. "params.x_ms" -> ("m", "axes offset ... [m]"). KeyError for an unknown key."""
    field = field_at(SceneConfig, tuple(dotted.split(".")))
    if field is None:
        raise KeyError(dotted)
    return extra_of(field).get("unit"), field.description or dotted


# The sections whose fields `_with_section_values` sets, less the keys that change what a
# scene is made of: a preset implies other keys, a layout changes the keys the scene uses.
_SECTION_FIELDS = {
    "params": frozenset(Params.model_fields),
    "contact": frozenset(Contact.model_fields) - {"layout"},
    "numerics": frozenset(Numerics.model_fields) - {"preset"},
}
_SCALARS = (bool, int, str)


def _same(value: Any, current: Any) -> bool:
    """Whether setting a field now holding `current` to `value` leaves it as it is: a
    scalar of the same type and value (a float of the same sign too: -0.0 is written so)."""
    if type(value) is not type(current):
        return False
    if isinstance(value, float):
        return value == current and math.copysign(1.0, value) == math.copysign(1.0, current)
    return isinstance(value, _SCALARS) and value == current


def _sorted(value: dict[str, Any]) -> dict[str, Any]:
    """`value` with the keys of every dict in it sorted (lists are left as they are)."""
    return {
        key: _sorted(item) if isinstance(item := value[key], dict) else item
        for key in sorted(value)
    }
