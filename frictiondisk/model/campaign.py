"""Campaign files (`campaigns/*.yaml`): a base scene plus one task, validated like scenes.

A campaign file holds a `name`, a base scene (the keys of a scene file: `scene`, `params`,
`contact`, `numerics`) and exactly one task:

- `find_jump`: bisect mu to the jump mu* (docs/model.md section 7) at every point of a line of one
  scene key or a grid of two, e.g. `along: {params.x_ms: {start: 0.02, stop: 0.2, num: 10}}`.
- `scan`: run every point of a grid of mu (and optionally one more scene key) in
  `numerics.mode` `converge` (or `decide`), keeping each run's outcome and measures; this
  feeds size-versus-mu curves.
- `trajectory`: one recorded run of the base scene (the orbit of the paper's Figs 4-5),
  shown whole or as its last converged limit cycle.
- `basin`: basin stability (frictiondisk.engine.basin_plan): at every point of an optional
  line or grid of scene keys, the fraction of each outcome over initial states drawn from
  `sample` (a fixed count, or adaptively to a target standard error); or, with `grid`
  instead of `sample`, one run per cell of a grid of 1 or 2 initial-state keys (a basin map).

Varied values are a list of numbers or `{start, stop, num}` (numpy.linspace). Any numeric
scene key may be varied, numerics ones included (`numerics.rtol`, `contact.stiffness`).

Validation follows `frictiondisk.model.scene`: the base scene is validated exactly as a scene file
(same paths, same messages); every varied value is checked by building the scene it gives;
all problems are collected and raised together as one `ConfigError`, one line
`dotted.path: what is wrong; what is allowed` each, list items written `path[i]`.
"""

from __future__ import annotations

import dataclasses
import difflib
import hashlib
import itertools
import json
import math
import operator
import re
import types
from collections.abc import Mapping
from dataclasses import dataclass
from os import PathLike
from typing import Any, ClassVar, Union, get_args, get_origin

import numpy as np
import yaml
from pydantic import BaseModel
from pydantic.fields import FieldInfo

# Private helpers of config are shared on purpose, so that campaign messages read exactly like
# scene messages: _show/_kind render values, _requirement says what a scene field accepts.
from frictiondisk.model.scene import (
    _DOTTED_KEY,
    MAX_HORIZON,
    ConfigError,
    Numerics,
    SceneConfig,
    _kind,
    _requirement,
    _show,
    scene_from_dict,
)
from frictiondisk.model.search_settings import OFF as CERTIFY_OFF
from frictiondisk.model.search_settings import ROOT_FINDERS, Certify
from frictiondisk.model.yamlio import StrictDumper, load_yaml_text, read_text_file

__all__ = [
    "Basin",
    "Campaign",
    "FindJump",
    "Trajectory",
    "Point",
    "Scan",
    "campaign_from_dict",
    "campaign_from_text",
    "load_campaign",
]

SCENE_KEYS = ("scene", "params", "contact", "numerics")
TASK_KEYS = ("find_jump", "scan", "trajectory", "basin")
TOP_KEYS = ("name", *SCENE_KEYS, *TASK_KEYS)
FIND_JUMP_KEYS = (
    "parameter",
    "bracket",
    "tol",
    "limits",
    "max_retries",
    "horizon_factor",
    "lanes",
    "along",
    "prescan",
    "split",
    "certify",
    "root_finder",
)
CERTIFY_KEYS = ("horizon", "rtol", "levels")
SCAN_KEYS = ("mu", "along", "mode")
PRESCAN_KEYS = ("mu", "mode", "stride")
TRAJECTORY_KEYS = ("dt_out", "show")
TRAJECTORY_SHOW = ("whole", "cycle")
LINSPACE_KEYS = ("start", "stop", "num")
MAX_AXIS_VALUES = 10_000  # values of one varied key (each is validated as a scene)
BASIN_KEYS = ("sample", "samples", "target_se", "max_samples", "batch", "seed", "along", "grid")
BASIN_SAMPLE_ONLY = ("sample", "samples", "target_se", "max_samples", "batch", "seed")
# Initial-state keys a basin samples or maps (params.phidot0: disk only).
INITIAL_STATE_KEYS = ("params.x0", "params.y0", "params.vx0", "params.vy0", "params.phidot0")
DISTRIBUTIONS = {"uniform": "low, high", "normal": "mean, sd"}

# find_jump defaults (docs/model.md section 7: the bisection stops at mu_hi - mu_lo <= 1e-4).
DEFAULT_TOL = 1.0e-4
DEFAULT_LIMITS = (1.0e-6, 10.0)  # the bracket may be widened within these
DEFAULT_MAX_RETRIES = 2  # retries of an undetermined run with a longer horizon
DEFAULT_HORIZON_FACTOR = 2.0  # each retry multiplies numerics.t_decide (or t_max) by this
DEFAULT_LANES = 2  # warm-start chains
DEFAULT_SPLIT = 2  # parts per bisection round: 2 = plain bisection (bisection.Bisection)
MAX_SPLIT = 64
DEFAULT_CERTIFY = Certify()  # horizon x 4, rtol x 0.1 per level, up to level 2
DEFAULT_ROOT_FINDER = "itp"  # interpolate on the friction reserve (bisection.Bisection)
DEFAULT_SCAN_MODE = "converge"  # a size curve needs the converged cycle (docs/model.md section 6)
DEFAULT_DT_OUT = 0.01  # [s] recording interval of a trajectory (switching instants are added)
DEFAULT_BASIN_BATCH = 100  # samples per adaptive batch (target_se): the stop rule's step
DEFAULT_BASIN_SEED = 0
MAX_BASIN_SAMPLES = 10_000_000

_NAME = re.compile(r"[A-Za-z0-9_-]+")
_MODE_FIELD = Numerics.model_fields["mode"]
_MISSING: Any = object()  # a key not given at all (unlike a null value)
_FLOAT_MAX = 1.7976931348623157e308
_SYMBOLS = {"gt": ">", "ge": ">=", "lt": "<", "le": "<="}
_COMPARE = {"gt": operator.gt, "ge": operator.ge, "lt": operator.lt, "le": operator.le}


# --- the campaign -----------------------------------------------------------------------


@dataclass(frozen=True)
class Prescan:
    """Values of mu run at every point before bisecting, in numerics.mode `mode`; every
    change between neighbours is then bisected (frictiondisk.search.jumps.JumpSearch). `stride`:
    run every stride-th value first and refine where needed (frictiondisk.search.prescan); None
    picks `prescan.stride_of` (1, dense, for converge mode and stick_rule contacts)."""

    mu: tuple[float, ...]
    mode: str
    stride: int | None = None

    def canonical(self) -> dict[str, Any]:
        out: dict[str, Any] = {"mode": self.mode, "mu": list(self.mu)}
        if self.stride is not None:
            out["stride"] = self.stride
        return out


@dataclass(frozen=True)
class FindJump:
    """Bisect `parameter` (mu) to the jump mu* at every point of `along`.

    `bracket` = (lo, hi) with lo expected not to stick and hi to stick; the bisection stops
    when hi - lo <= `tol`. The bracket may be widened within `limits`. An undetermined run is
    retried up to `max_retries` times, each with numerics.t_decide (or t_max) multiplied by
    `horizon_factor`. `lanes`: how many points of a row (the last dim) are in flight at
    once; the row runs coarse to fine and each inner point predicts its bracket from the
    two that bound it (campaign/plan.py). `root_finder`: "itp" aims at the friction
    reserve's zero, "bisect" halves (frictiondisk.search.bisection). `along` maps 1 or 2 dotted
    scene keys, in file order, to their values.
    """

    kind: ClassVar[str] = "find_jump"

    parameter: str
    bracket: tuple[float, float]
    tol: float
    limits: tuple[float, float]
    max_retries: int
    horizon_factor: float
    lanes: int
    along: dict[str, tuple[float, ...]]
    prescan: Prescan | None = None
    split: int = DEFAULT_SPLIT  # parts per bisection round (k - 1 runs per round, at once)
    certify: Certify = DEFAULT_CERTIFY  # re-check of every jump at stricter numerics
    root_finder: str = DEFAULT_ROOT_FINDER  # "itp" (interpolating) or "bisect"

    def canonical(self) -> dict[str, Any]:
        """JSON-able dict, keys sorted except `along`, whose order is the dims order.
        `prescan` and `split` appear only when given (split != 2), so campaigns without
        them keep their hash."""
        out = {
            "along": {key: list(values) for key, values in self.along.items()},
            "bracket": list(self.bracket),
            "horizon_factor": self.horizon_factor,
            "lanes": self.lanes,
            "limits": list(self.limits),
            "max_retries": self.max_retries,
            "parameter": self.parameter,
            "tol": self.tol,
        }
        if self.prescan is not None:
            out["prescan"] = self.prescan.canonical()
        if self.split != DEFAULT_SPLIT:
            out["split"] = self.split
        if self.certify != DEFAULT_CERTIFY:
            out["certify"] = self.certify.canonical()
        if self.root_finder != DEFAULT_ROOT_FINDER:
            out["root_finder"] = self.root_finder
        return {key: out[key] for key in sorted(out)}


@dataclass(frozen=True)
class Scan:
    """Run every point of the grid `mu` x `along` with numerics.mode = `mode`.

    `along` maps at most one dotted scene key to its values (empty: a line in mu).
    """

    kind: ClassVar[str] = "scan"

    mu: tuple[float, ...]
    along: dict[str, tuple[float, ...]]
    mode: str

    def canonical(self) -> dict[str, Any]:
        """JSON-able dict, keys sorted."""
        return {
            "along": {key: list(values) for key, values in self.along.items()},
            "mode": self.mode,
            "mu": list(self.mu),
        }


@dataclass(frozen=True)
class Trajectory:
    """Record one run of the base scene every `dt_out` seconds (plus every switching
    instant) and show it `whole` (transient and cycle, paper Fig. 4) or only its last
    converged limit cycle, `cycle` (paper Fig. 5; needs numerics.mode converge)."""

    kind: ClassVar[str] = "trajectory"

    dt_out: float
    show: str

    @property
    def along(self) -> dict[str, tuple[float, ...]]:
        return {}

    def canonical(self) -> dict[str, Any]:
        """JSON-able dict, keys sorted."""
        return {"dt_out": self.dt_out, "show": self.show}


@dataclass(frozen=True)
class Distribution:
    """One sampled initial-state key: `uniform` on [a, b) or `normal` with mean a, sd b."""

    kind: str  # "uniform" or "normal"
    a: float
    b: float

    def canonical(self) -> dict[str, Any]:
        return {self.kind: [self.a, self.b]}


@dataclass(frozen=True)
class Basin:
    """Basin stability (fractions of outcomes over sampled initial states) or a basin map.

    Sampling (`sample` non-empty): at each point of `along` (0, 1 or 2 scene keys) draw
    initial states from `sample` (dotted initial-state key -> Distribution); either
    `samples` of them, or batches of `batch` until the standard error of the not-stick
    fraction is <= `target_se` or `max_samples` are drawn. Draws are fixed by `seed` and
    the point's values (frictiondisk.engine.basin_plan).
    Map (`grid` non-empty): one run per cell of 1 or 2 initial-state keys; no sampling.
    """

    kind: ClassVar[str] = "basin"

    sample: dict[str, Distribution]
    samples: int | None
    target_se: float | None
    max_samples: int | None
    batch: int
    seed: int
    along: dict[str, tuple[float, ...]]
    grid: dict[str, tuple[float, ...]]

    @property
    def is_map(self) -> bool:
        return bool(self.grid)

    @property
    def sample_limit(self) -> int:
        """Most samples a point can take (1 for a map: each cell is one run)."""
        if self.is_map:
            return 1
        return self.samples if self.samples is not None else self.max_samples

    def canonical(self) -> dict[str, Any]:
        """JSON-able dict, keys sorted except `along`/`grid`/`sample` (their file order)."""
        if self.is_map:
            return {"grid": {key: list(values) for key, values in self.grid.items()}}
        out: dict[str, Any] = {
            "along": {key: list(values) for key, values in self.along.items()},
            "sample": {key: dist.canonical() for key, dist in self.sample.items()},
            "seed": self.seed,
        }
        if self.samples is not None:
            out["samples"] = self.samples
        else:
            out |= {"batch": self.batch, "max_samples": self.max_samples}
            out["target_se"] = self.target_se
        return {key: out[key] for key in sorted(out)}


@dataclass(frozen=True)
class Point:
    """One grid point: its `index` in `Campaign.shape`, varied values and full scene."""

    index: tuple[int, ...]
    coords: dict[str, float]
    config: SceneConfig


@dataclass(frozen=True)
class Campaign:
    """One validated campaign: build it with `load_campaign` or `campaign_from_text/_dict`.

    `text` is the YAML the campaign was read from (for `campaign_from_dict`, the canonical
    form as YAML); it does not take part in equality.
    """

    name: str
    base: SceneConfig
    task: FindJump | Scan | Trajectory | Basin
    text: str = dataclasses.field(default="", compare=False, repr=False)

    @property
    def kind(self) -> str:
        """ "find_jump", "scan", "trajectory" or "basin"."""
        return self.task.kind

    @property
    def dims(self) -> tuple[str, ...]:
        """Varied dotted keys in file order; a scan's first dim is "params.mu"."""
        return tuple(self._axes())

    @property
    def coords(self) -> dict[str, np.ndarray]:
        """Values of each dim (fresh arrays)."""
        return {dim: np.array(values, dtype=float) for dim, values in self._axes().items()}

    @property
    def shape(self) -> tuple[int, ...]:
        """Number of values of each dim."""
        return tuple(len(values) for values in self._axes().values())

    def points(self) -> list[Point]:
        """Every grid point in C order over `shape` (the last dim varies fastest).

        `config` is the base scene with the point's values set; for a scan also params.mu
        and numerics.mode = the scan's mode.
        """
        axes = self._axes()
        fixed = {"numerics.mode": self.task.mode} if isinstance(self.task, Scan) else {}
        points = []
        for index in itertools.product(*(range(len(values)) for values in axes.values())):
            coords = {dim: axes[dim][i] for dim, i in zip(axes, index, strict=True)}
            overrides = {dim: _scene_value(dim, value) for dim, value in coords.items()}
            config = self.base.with_overrides({**overrides, **fixed})
            points.append(Point(index=index, coords=coords, config=config))
        return points

    def canonical(self) -> dict[str, Any]:
        """JSON-able dict: defaults filled in, the base scene canonical, values as lists.

        Keys are sorted, except under `along`, whose order is the order of `dims`.
        """
        data = {**self.base.canonical(), "name": self.name, self.kind: self.task.canonical()}
        return {key: data[key] for key in sorted(data)}

    def content_hash(self) -> str:
        """sha256 hex digest of the canonical dict as compact JSON.

        Like `SceneConfig.content_hash`, but the keys are not re-sorted: `canonical()` is
        already sorted, and the order of `along` (the dims order) is part of the content.
        """
        text = json.dumps(self.canonical(), separators=(",", ":"))
        return hashlib.sha256(text.encode()).hexdigest()

    def diff(self, other: Campaign) -> list[str]:
        """Lines `dotted.path: mine -> other's` for each canonical value that differs."""
        mine, theirs = _flatten(self.canonical()), _flatten(other.canonical())
        lines = [
            _difference(path, mine, theirs)
            for path in sorted(mine.keys() | theirs.keys())
            if mine.get(path, _MISSING) != theirs.get(path, _MISSING)
        ]
        if self.dims != other.dims and set(self.dims) == set(other.dims):
            lines.append(f"dims: {', '.join(self.dims)} -> {', '.join(other.dims)}")
        return lines

    def _axes(self) -> dict[str, tuple[float, ...]]:
        if isinstance(self.task, Scan):
            return {"params.mu": self.task.mu, **self.task.along}
        if isinstance(self.task, Basin):
            return {**self.task.along, **self.task.grid}
        return dict(self.task.along)


# --- loading ----------------------------------------------------------------------------


def load_campaign(path: str | PathLike[str]) -> Campaign:
    """Load and validate a campaign YAML file; any problem is a `ConfigError`."""
    # the text itself, not only the parsed data: the campaign keeps it (results attributes)
    return campaign_from_text(read_text_file(path), source=str(path))


def campaign_from_text(text: str, source: str = "<string>") -> Campaign:
    """Validate a campaign given as YAML text; `source` names it in errors."""
    return _read(load_yaml_text(text, source=source), source, text)


def campaign_from_dict(data: Any, source: str = "<dict>") -> Campaign:
    """Validate a campaign given as a dict (e.g. parsed YAML).

    Raises ConfigError listing every problem as `dotted.path: message`.
    """
    return _read(data, source, None)


def _read(data: Any, source: str, text: str | None) -> Campaign:
    problems: list[str] = []
    top = _mapping(data, "", TOP_KEYS, problems)
    if top is None:
        raise ConfigError(problems, source)
    name = _name(top.get("name", _MISSING), problems)
    base = None
    try:
        base = scene_from_dict({key: top[key] for key in SCENE_KEYS if key in top}, source=source)
    except ConfigError as err:
        problems += err.problems
    tasks = [key for key in TASK_KEYS if key in top]
    task: FindJump | Scan | Trajectory | Basin | None = None
    if not tasks:
        problems.append(f"(top level): no task: give exactly one of {', '.join(TASK_KEYS)}")
    elif len(tasks) > 1:
        problems.append(
            f"(top level): {' and '.join(tasks)} given: give exactly one task "
            f"({', '.join(TASK_KEYS)})"
        )
    elif tasks[0] == "find_jump":
        task = _find_jump(top["find_jump"], base, problems)
    elif tasks[0] == "scan":
        task = _scan(top["scan"], base, problems)
    elif tasks[0] == "basin":
        task = _basin(top["basin"], base, problems)
    else:
        task = _trajectory(top["trajectory"], base, problems)
    if problems:
        raise ConfigError(problems, source)
    campaign = Campaign(name=name, base=base, task=task)
    if text is None:
        # Block-style YAML like yamlio.dump_yaml, but `along` keeps its order (the dims).
        text = yaml.dump(
            campaign.canonical(), Dumper=StrictDumper, sort_keys=False, default_flow_style=False
        )
    return dataclasses.replace(campaign, text=text)


# --- tasks ------------------------------------------------------------------------------


def _find_jump(data: Any, base: SceneConfig | None, problems: list[str]) -> FindJump | None:
    spec = _mapping(data, "find_jump", FIND_JUMP_KEYS, problems)
    if spec is None:
        return None
    parameter = spec.get("parameter", "mu")
    if parameter != "mu":
        problems.append(f"find_jump.parameter: {_show(parameter)} is not allowed: must be 'mu'")
    prescan = None
    if "prescan" in spec:
        prescan = _prescan(spec["prescan"], base, problems)
        if prescan is None:
            return None
    default_bracket = [min(prescan.mu), max(prescan.mu)] if prescan else _MISSING
    bracket = _pair(spec.get("bracket", default_bracket), "find_jump.bracket", "lo, hi", problems)
    tol = _number(spec.get("tol", DEFAULT_TOL), "find_jump.tol", problems, gt=0)
    limits = _pair(spec.get("limits", DEFAULT_LIMITS), "find_jump.limits", "low, high", problems)
    max_retries = _number(
        spec.get("max_retries", DEFAULT_MAX_RETRIES),
        "find_jump.max_retries",
        problems,
        integer=True,
        ge=0,
        le=10,
    )
    horizon_factor = _number(
        spec.get("horizon_factor", DEFAULT_HORIZON_FACTOR),
        "find_jump.horizon_factor",
        problems,
        gt=1,
    )
    lanes = _number(
        spec.get("lanes", DEFAULT_LANES), "find_jump.lanes", problems, integer=True, ge=1, le=64
    )
    split = _number(
        spec.get("split", DEFAULT_SPLIT),
        "find_jump.split",
        problems,
        integer=True,
        ge=2,
        le=MAX_SPLIT,
    )
    if bracket is not None:
        lo, hi = bracket
        if tol is not None and tol >= hi - lo:
            problems.append(
                f"find_jump.tol: {_show(tol)} is out of range: must be > 0 and "
                f"< hi - lo = {hi - lo:.6g} (the bracket's width)"
            )
        if limits is not None and not (limits[0] <= lo and hi <= limits[1]):
            problems.append(
                f"find_jump.limits: {_show(list(limits))} does not contain the bracket "
                f"{_show(list(bracket))}: must have limits[0] <= lo and hi <= limits[1]"
            )
    along = _along(
        spec.get("along", _MISSING),
        "find_jump.along",
        base,
        problems,
        counts=(1, 2),
        taken={"params.mu": "params.mu is the bisected parameter; it cannot also be varied"},
    )
    if base is not None and None not in (max_retries, horizon_factor):
        _check_retry_horizon(base, prescan, max_retries, horizon_factor, problems)
    certify = _certify(spec.get("certify", True), problems)
    root_finder = _one_of(
        spec.get("root_finder", DEFAULT_ROOT_FINDER),
        "find_jump.root_finder",
        ROOT_FINDERS,
        problems,
    )
    needed = (bracket, tol, limits, max_retries, horizon_factor, lanes, split, along, certify)
    if None in (*needed, root_finder):
        return None
    return FindJump(
        parameter=parameter,
        bracket=bracket,
        tol=tol,
        limits=limits,
        max_retries=max_retries,
        horizon_factor=horizon_factor,
        lanes=lanes,
        along=along,
        prescan=prescan,
        split=split,
        certify=certify,
        root_finder=root_finder,
    )


def _certify(data: Any, problems: list[str]) -> Certify | None:
    """find_jump.certify: true (the defaults), false (off) or {horizon, rtol, levels}."""
    if data is True:
        return DEFAULT_CERTIFY
    if data is False:
        return CERTIFY_OFF
    spec = _mapping(data, "find_jump.certify", CERTIFY_KEYS, problems)
    if spec is None:
        return None
    horizon = _number(
        spec.get("horizon", DEFAULT_CERTIFY.horizon), "find_jump.certify.horizon", problems, gt=1
    )
    rtol = _number(
        spec.get("rtol", DEFAULT_CERTIFY.rtol), "find_jump.certify.rtol", problems, gt=0, le=1
    )
    levels = _number(
        spec.get("levels", DEFAULT_CERTIFY.levels),
        "find_jump.certify.levels",
        problems,
        integer=True,
        ge=0,
        le=4,
    )
    if None in (horizon, rtol, levels):
        return None
    return Certify(horizon=horizon, rtol=rtol, levels=levels)


def _check_retry_horizon(
    base: SceneConfig,
    prescan: Prescan | None,
    max_retries: int,
    horizon_factor: float,
    problems: list[str],
) -> None:
    """The last retry's horizon, horizon * horizon_factor**max_retries, must stay finite
    and <= MAX_HORIZON (compared in logs: the power itself may overflow)."""
    num = base.numerics
    modes = {num.mode} | ({prescan.mode} if prescan else set())
    horizon = max(num.t_max if mode == "converge" else num.t_decide for mode in modes)
    if max_retries and (
        math.log(horizon) + max_retries * math.log(horizon_factor) > math.log(MAX_HORIZON)
    ):
        top = (MAX_HORIZON / horizon) ** (1.0 / max_retries)
        problems.append(
            f"find_jump.horizon_factor: {_show(horizon_factor)} is out of range: with "
            f"max_retries {max_retries} the last retry would run {horizon:g} s x "
            f"{_show(horizon_factor)}^{max_retries}, beyond the largest horizon "
            f"{MAX_HORIZON:g} s: must be > 1 and <= {top:.6g}"
        )


def _prescan(data: Any, base: SceneConfig | None, problems: list[str]) -> Prescan | None:
    spec = _mapping(data, "find_jump.prescan", PRESCAN_KEYS, problems)
    if spec is None:
        return None
    mu = _values(spec.get("mu", _MISSING), "find_jump.prescan.mu", problems)
    if mu is not None:
        if len(mu) < 2:
            problems.append("find_jump.prescan.mu: one value given: give at least 2")
            mu = None
        elif base is not None:
            for i, value in enumerate(mu):
                _check_scene(base, "params.mu", value, f"find_jump.prescan.mu[{i}]", problems)
    mode = spec.get("mode", "decide")
    if mode not in get_args(_MODE_FIELD.annotation):
        must = _requirement(_MODE_FIELD)
        problems.append(f"find_jump.prescan.mode: {_show(mode)} is not allowed: must be {must}")
        mode = None
    stride = None
    if "stride" in spec:
        top = max(1, len(mu) - 1) if mu else 64
        stride = _number(
            spec["stride"], "find_jump.prescan.stride", problems, integer=True, ge=1, le=top
        )
        if stride is None:
            return None
    if None in (mu, mode):
        return None
    return Prescan(mu=tuple(sorted(mu)), mode=mode, stride=stride)


def _scan(data: Any, base: SceneConfig | None, problems: list[str]) -> Scan | None:
    spec = _mapping(data, "scan", SCAN_KEYS, problems)
    if spec is None:
        return None
    mu = _values(spec.get("mu", _MISSING), "scan.mu", problems)
    if mu is not None and base is not None:
        for i, value in enumerate(mu):
            _check_scene(base, "params.mu", value, f"scan.mu[{i}]", problems)
    along = _along(
        spec.get("along", {}),
        "scan.along",
        base,
        problems,
        counts=(0, 1),
        taken={"params.mu": "params.mu is the scan's own axis: give its values in scan.mu"},
    )
    mode = spec.get("mode", DEFAULT_SCAN_MODE)
    if mode not in get_args(_MODE_FIELD.annotation):
        must = _requirement(_MODE_FIELD)
        problems.append(f"scan.mode: {_show(mode)} is not allowed: must be {must}")
        mode = None
    if None in (mu, along, mode):
        return None
    return Scan(mu=mu, along=along, mode=mode)


def _trajectory(data: Any, base: SceneConfig | None, problems: list[str]) -> Trajectory | None:
    spec = _mapping({} if data is None else data, "trajectory", TRAJECTORY_KEYS, problems)
    if spec is None:
        return None
    dt_out = _number(spec.get("dt_out", DEFAULT_DT_OUT), "trajectory.dt_out", problems, gt=0)
    show = _one_of(spec.get("show", "whole"), "trajectory.show", TRAJECTORY_SHOW, problems)
    if show == "cycle" and base is not None and base.numerics.mode != "converge":
        problems.append(
            "trajectory.show: 'cycle' needs the converged limit cycle: "
            f"set numerics.mode: converge (got {base.numerics.mode!r})"
        )
        show = None
    if dt_out is not None and base is not None:
        from frictiondisk.model.limits import recording_problem

        problem = recording_problem(base, dt_out, "trajectory.dt_out")
        if problem is not None:
            problems.append(problem)
            dt_out = None
    if None in (dt_out, show):
        return None
    return Trajectory(dt_out=dt_out, show=show)


def _basin(data: Any, base: SceneConfig | None, problems: list[str]) -> Basin | None:
    spec = _mapping(data, "basin", BASIN_KEYS, problems)
    if spec is None:
        return None
    if "grid" in spec:
        return _basin_map(spec, base, problems)
    if "sample" not in spec:
        problems.append(
            "basin: give `sample` (fractions over sampled initial states) or `grid` "
            "(a basin map over 1 or 2 initial-state keys)"
        )
        return None
    sample = _sample(spec["sample"], base, problems)
    samples = target_se = max_samples = None
    ok = True
    if "samples" in spec and "target_se" in spec:
        problems.append("basin: samples and target_se given: give one (a fixed count or a target)")
        ok = False
    elif "samples" in spec:
        samples = _number(
            spec["samples"], "basin.samples", problems, integer=True, ge=1, le=MAX_BASIN_SAMPLES
        )
        for key in ("max_samples", "batch"):
            if key in spec:
                problems.append(f"basin.{key}: only used with basin.target_se; remove it")
                ok = False
    elif "target_se" in spec:
        target_se = _number(spec["target_se"], "basin.target_se", problems, gt=0, le=0.5)
        max_samples = _number(
            spec.get("max_samples", _MISSING),
            "basin.max_samples",
            problems,
            integer=True,
            ge=1,
            le=MAX_BASIN_SAMPLES,
        )
        ok = None not in (target_se, max_samples)
    else:
        problems.append(
            "basin: no sample count: give samples (e.g. 400) or target_se with max_samples"
        )
        ok = False
    batch = _number(
        spec.get("batch", DEFAULT_BASIN_BATCH),
        "basin.batch",
        problems,
        integer=True,
        ge=1,
        le=MAX_BASIN_SAMPLES,
    )
    seed = _number(spec.get("seed", DEFAULT_BASIN_SEED), "basin.seed", problems, integer=True, ge=0)
    taken = {
        key: f"{key} is sampled (basin.sample); it cannot also be varied" for key in sample or {}
    }
    along = _along(spec.get("along", {}), "basin.along", base, problems, counts=(0, 2), taken=taken)
    if not ok or None in (sample, batch, seed, along):
        return None
    return Basin(
        sample=sample,
        samples=samples,
        target_se=target_se,
        max_samples=max_samples,
        batch=batch,
        seed=seed,
        along=along,
        grid={},
    )


def _basin_map(spec: dict[str, Any], base: SceneConfig | None, problems: list[str]) -> Basin | None:
    """basin.grid: a map, one run per cell; sampling keys and `along` do not apply."""
    before = len(problems)
    for key in (*BASIN_SAMPLE_ONLY, "along"):
        if key in spec:
            problems.append(
                f"basin.{key}: not used with basin.grid (a basin map runs each cell of the "
                "grid once, at the base scene's parameters); remove it or drop grid"
            )
    grid = _along(spec["grid"], "basin.grid", base, problems, counts=(1, 2), taken={})
    if grid is None:
        return None
    for key in grid:
        _initial_state_key(key, f"basin.grid.{key}", base, problems)
    if len(problems) > before:
        return None
    return Basin(
        sample={},
        samples=None,
        target_se=None,
        max_samples=None,
        batch=1,
        seed=DEFAULT_BASIN_SEED,
        along={},
        grid=grid,
    )


def _initial_state_key(key: str, path: str, base: SceneConfig | None, problems: list[str]) -> bool:
    """Whether `key` is an initial-state key of the scene; else a problem naming `path`."""
    if key not in INITIAL_STATE_KEYS:
        problems.append(
            f"{path}: not an initial-state key; allowed: {', '.join(INITIAL_STATE_KEYS)}"
        )
        return False
    if key == "params.phidot0" and base is not None and base.scene != "disk":
        problems.append(f"{path}: the spin of a slave disk; scene {base.scene!r} has none")
        return False
    return True


def _sample(
    data: Any, base: SceneConfig | None, problems: list[str]
) -> dict[str, Distribution] | None:
    """basin.sample: initial-state key -> {uniform: [low, high]} or {normal: [mean, sd]}."""
    spec = _mapping(data, "basin.sample", None, problems)
    if spec is None:
        return None
    if not spec:
        problems.append(
            "basin.sample: no keys: map at least one of "
            f"{', '.join(INITIAL_STATE_KEYS)} to a distribution"
        )
        return None
    out: dict[str, Distribution] = {}
    ok = True
    for key, item in spec.items():
        path = f"basin.sample.{key}"
        if not _initial_state_key(key, path, base, problems):
            ok = False
            continue
        dist = _distribution(item, path, problems)
        if dist is None:
            ok = False
            continue
        if base is not None and dist.kind == "uniform":
            for i, value in enumerate((dist.a, dist.b)):
                _check_scene(base, key, value, f"{path}.uniform[{i}]", problems)
        out[key] = dist
    return out if ok else None


def _distribution(data: Any, path: str, problems: list[str]) -> Distribution | None:
    must = "must be {uniform: [low, high]} with low < high, or {normal: [mean, sd]} with sd > 0"
    spec = _mapping(data, path, tuple(DISTRIBUTIONS), problems)
    if spec is None:
        return None
    if len(spec) != 1:
        if len(spec) == len(data):  # unknown keys were reported by _mapping already
            problems.append(f"{path}: {len(spec)} distributions given: {must}")
        return None
    kind, value = next(iter(spec.items()))
    names = DISTRIBUTIONS[kind]
    where = f"{path}.{kind}"
    if not isinstance(value, list | tuple) or len(value) != 2:
        got = _kind(value) if value is None else f"{_kind(value)} {_show(value)}"
        problems.append(f"{where}: expected a list [{names}]; got {got}: {must}")
        return None
    a, b = (_number(item, f"{where}[{i}]", problems) for i, item in enumerate(value))
    if a is None or b is None:
        return None
    if kind == "uniform" and not a < b:
        problems.append(f"{where}: {_show([a, b])} is not allowed: low < high needed")
        return None
    if kind == "normal" and not b > 0:
        problems.append(f"{where}[1]: {_show(b)} is out of range: the sd must be > 0")
        return None
    return Distribution(kind=kind, a=a, b=b)


def _along(
    data: Any,
    path: str,
    base: SceneConfig | None,
    problems: list[str],
    counts: tuple[int, int],
    taken: Mapping[str, str],
) -> dict[str, tuple[float, ...]] | None:
    """The varied keys under `path`, each checked against the scene with each value."""
    least, most = counts
    allowed = f"{least} or {most}" if least else f"at most {most}"
    noun = "scene key" if most == 1 else "scene keys"
    if data is _MISSING:
        problems.append(f"{path}: missing; must be a mapping of {allowed} dotted {noun} to values")
        return None
    spec = _mapping(data, path, None, problems)
    if spec is None:
        return None
    ok = True
    if not least <= len(spec) <= most:
        got = f"{len(spec)} keys ({', '.join(spec)})" if spec else "no keys"
        problems.append(f"{path}: {got} given: vary {allowed} {noun}")
        ok = False
    along = {}
    for key, item in spec.items():
        item_path = f"{path}.{key}"
        values = _values(item, item_path, problems)
        if key in taken:
            problems.append(f"{item_path}: {taken[key]}")
        elif _numeric_scene_field(key, path, problems) and values is not None:
            if base is not None:
                for i, value in enumerate(values):
                    _check_scene(base, key, value, f"{item_path}[{i}]", problems)
            along[key] = values
            continue
        ok = False
    return along if ok else None


# --- checks -----------------------------------------------------------------------------


def _mapping(
    data: Any, path: str, allowed: tuple[str, ...] | None, problems: list[str]
) -> dict[str, Any] | None:
    """`data` as a dict of its text keys that are `allowed` (None: any), else None."""
    where = path or "(top level)"
    keys = f"keys {', '.join(allowed)}" if allowed else "dotted scene keys"
    if not isinstance(data, Mapping):
        got = _kind(data) if data is None else f"{_kind(data)} {_show(data)}"
        problems.append(f"{where}: expected a mapping with {keys}; got {got}")
        return None
    under = f"under {path}" if path else "at top level"
    out = {}
    for key, value in data.items():
        if not isinstance(key, str):
            problems.append(f"{where}: key {_show(key)} is not text; allowed: {keys}")
        elif allowed is not None and key not in allowed:
            text = f"unknown key; allowed keys {under}: {', '.join(allowed)}"
            close = difflib.get_close_matches(key, allowed, n=1)
            text += f" (did you mean {close[0]!r}?)" if close else ""
            problems.append(f"{_join(path, key)}: {text}")
        else:
            out[key] = value
    return out


def _name(value: Any, problems: list[str]) -> str | None:
    must = "must be text of letters, digits, _ and - only"
    if value is _MISSING:
        problems.append(f"name: missing; {must}")
    elif not isinstance(value, str):
        problems.append(f"name: {_show(value)} is {_kind(value)}, not text: {must}")
    elif not _NAME.fullmatch(value):
        problems.append(f"name: {_show(value)} is not allowed: {must}")
    else:
        return value
    return None


def _one_of(value: Any, path: str, allowed: tuple[str, ...], problems: list[str]) -> Any:
    """`value` if it is one of `allowed`, else None (and the problem, naming them)."""
    if value in allowed:
        return value
    choices = " or ".join(repr(item) for item in allowed)
    problems.append(f"{path}: {_show(value)} is not allowed: must be {choices}")
    return None


def _number(
    value: Any,
    path: str,
    problems: list[str],
    integer: bool = False,
    **bounds: float,
) -> Any:
    """`value` as a finite float (or an int), within `bounds` (gt/ge/lt/le), else None."""
    limits = " and ".join(f"{_SYMBOLS[name]} {bound}" for name, bound in bounds.items())
    noun = "an integer" if integer else "a number"
    must = f"must be {'an integer' if integer else 'a finite number'} {limits}".rstrip()
    if value is _MISSING:
        problems.append(f"{path}: missing; {must}")
        return None
    if value is None:
        problems.append(f"{path}: missing value (null); {must}")
        return None
    kinds = (int,) if integer else (int, float)
    if isinstance(value, bool) or not isinstance(value, kinds):
        hint = " (write numbers without quotes)" if isinstance(value, str) else ""
        problems.append(f"{path}: {_show(value)} is {_kind(value)}, not {noun}: {must}{hint}")
        return None
    if isinstance(value, float) and not math.isfinite(value):
        problems.append(f"{path}: {_show(value)} is not allowed: {must}")
        return None
    if not integer and abs(value) > _FLOAT_MAX:  # a huge YAML integer: no float holds it
        problems.append(f"{path}: {_show(value)} is out of range: {must}, |x| <= {_FLOAT_MAX}")
        return None
    if not all(_COMPARE[name](value, bound) for name, bound in bounds.items()):
        problems.append(f"{path}: {_show(value)} is out of range: must be {limits}")
        return None
    return value if integer else float(value)


def _pair(value: Any, path: str, names: str, problems: list[str]) -> tuple[float, float] | None:
    """`[a, b]` with 0 < a < b, both finite, else None."""
    must = f"must be a list [{names}] of two finite numbers with 0 < {names.replace(', ', ' < ')}"
    if value is _MISSING:
        problems.append(f"{path}: missing; {must}")
        return None
    if not isinstance(value, list | tuple) or len(value) != 2:
        got = _kind(value) if value is None else f"{_kind(value)} {_show(value)}"
        problems.append(f"{path}: expected a list [{names}]; got {got}: {must}")
        return None
    items = [_number(item, f"{path}[{i}]", problems, gt=0) for i, item in enumerate(value)]
    if None in items:
        return None
    if items[0] >= items[1]:
        problems.append(f"{path}: {_show(items)} is not allowed: {must}")
        return None
    return items[0], items[1]


def _values(value: Any, path: str, problems: list[str]) -> tuple[float, ...] | None:
    """A non-empty list of distinct finite numbers, or `{start, stop, num}` (linspace)."""
    must = f"must be a list of numbers or a mapping with keys {', '.join(LINSPACE_KEYS)}"
    if value is _MISSING:
        problems.append(f"{path}: missing; {must}")
        return None
    if isinstance(value, Mapping):
        spec = _mapping(value, path, LINSPACE_KEYS, problems)
        start = _number(spec.get("start", _MISSING), f"{path}.start", problems)
        stop = _number(spec.get("stop", _MISSING), f"{path}.stop", problems)
        num = _number(
            spec.get("num", _MISSING),
            f"{path}.num",
            problems,
            integer=True,
            ge=1,
            le=MAX_AXIS_VALUES,
        )
        if None in (start, stop, num) or len(spec) < len(value):
            return None
        if num > 1 and start == stop:
            problems.append(
                f"{path}: start = stop = {_show(start)} with num {num} repeats one value: "
                "use num: 1 or different start and stop"
            )
            return None
        return tuple(float(item) for item in np.linspace(start, stop, num))
    if not isinstance(value, list | tuple):
        got = _kind(value) if value is None else f"{_kind(value)} {_show(value)}"
        problems.append(f"{path}: expected a list or a mapping; got {got}: {must}")
        return None
    if not value:
        problems.append(f"{path}: empty list: give at least one number")
        return None
    if len(value) > MAX_AXIS_VALUES:
        problems.append(f"{path}: {len(value)} values: allowed at most {MAX_AXIS_VALUES}")
        return None
    items = [_number(item, f"{path}[{i}]", problems) for i, item in enumerate(value)]
    if None in items:
        return None
    first: dict[float, int] = {}
    for i, item in enumerate(items):
        if item in first:
            problems.append(
                f"{path}[{i}]: {_show(item)} repeats {path}[{first[item]}]: values must differ"
            )
        first.setdefault(item, i)
    return tuple(items) if len(first) == len(items) else None


def _numeric_scene_field(key: str, path: str, problems: list[str]) -> bool:
    """Whether dotted `key` names a numeric scene field; else a problem naming path.key."""
    key_path = f"{path}.{key}"
    if not _DOTTED_KEY.fullmatch(key):
        problems.append(f"{key_path}: not a dotted scene key, e.g. params.x_ms")
        return False
    model: Any = SceneConfig
    parts = key.split(".")
    for depth, part in enumerate(parts):
        section = ".".join(parts[:depth])
        if not _is_model(model):
            text = f"unknown scene key; {section} is a value, not a section"
            problems.append(f"{key_path}: {text}")
            return False
        fields = model.model_fields
        if part not in fields:
            under = f"under {section}" if section else "at top level"
            text = f"unknown scene key; allowed keys {under}: {', '.join(fields)}"
            close = difflib.get_close_matches(part, list(fields), n=1)
            text += f" (did you mean {close[0]!r}?)" if close else ""
            problems.append(f"{key_path}: {text}")
            return False
        model = fields[part].annotation
    if _is_model(model):
        keys = ", ".join(model.model_fields)
        problems.append(f"{key_path}: a section, not a number: vary one of its keys: {keys}")
        return False
    field = _scene_field(key)
    if not _field_types(field) <= {int, float}:
        problems.append(
            f"{key_path}: not a numeric scene key (it must be {_requirement(field)}); "
            "only numbers can be varied"
        )
        return False
    return True


def _check_scene(base: SceneConfig, key: str, value: float, path: str, problems: list[str]) -> None:
    """Problems of the scene `base` with `key` = `value`, reported under `path`."""
    try:
        base.with_overrides({key: _scene_value(key, value)})
    except ConfigError as err:
        for problem in err.problems:
            text = problem.removesuffix(f" (from override {key})")
            problems.append(f"{path}: {text.removeprefix(f'{key}: ')}")


def _scene_value(key: str, value: float) -> float | int:
    """`value` as the scene field `key` takes it: a whole float becomes an int for int keys."""
    if _field_types(_scene_field(key)) == {int} and float(value).is_integer():
        return int(value)
    return value


# --- helpers ----------------------------------------------------------------------------


def _scene_field(key: str) -> FieldInfo:
    """The SceneConfig field of an existing dotted key."""
    model: Any = SceneConfig
    *sections, leaf = key.split(".")
    for part in sections:
        model = model.model_fields[part].annotation
    return model.model_fields[leaf]


def _field_types(field: FieldInfo) -> set[Any]:
    """The types a field accepts besides null, e.g. {float} for `float | None`."""
    annotation = field.annotation
    union = get_origin(annotation) in (Union, types.UnionType)
    kinds = set(get_args(annotation)) if union else {annotation}
    return {kind for kind in kinds if kind is not type(None)}


def _is_model(annotation: Any) -> bool:
    return isinstance(annotation, type) and issubclass(annotation, BaseModel)


def _join(path: str, key: str) -> str:
    return f"{path}.{key}" if path else key


def _flatten(data: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """{"a": {"b": 1}} -> {"a.b": 1}; lists are values."""
    out: dict[str, Any] = {}
    for key, value in data.items():
        path = _join(prefix, key)
        if isinstance(value, Mapping) and value:
            out |= _flatten(value, path)
        else:
            out[path] = value
    return out


def _show_or_absent(flat: Mapping[str, Any], path: str, digits: int | None = None) -> str:
    if path not in flat:
        return "(absent)"
    return _show(flat[path]) if digits is None else _show(_rounded(flat[path], digits))


def _rounded(value: Any, digits: int) -> Any:
    """Floats (also inside lists) to `digits` significant digits, so that float noise such
    as 0.09999999999999999 (from a linspace) reads 0.1."""
    if isinstance(value, float):
        return float(f"{value:.{digits}g}")
    if isinstance(value, list | tuple):
        return [_rounded(v, digits) for v in value]
    return value


def _difference(path: str, mine: Mapping[str, Any], theirs: Mapping[str, Any]) -> str:
    """`path: mine -> theirs`, rounded to 12 significant digits unless that hides the change."""
    old, new = _show_or_absent(mine, path, 12), _show_or_absent(theirs, path, 12)
    if old == new:
        old, new = _show_or_absent(mine, path), _show_or_absent(theirs, path)
    return f"{path}: {old} -> {new}"
