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
- `basin`: basin stability (frictiondisk/tasks/basin/): at every point of an optional
  line or grid of scene keys, the fraction of each outcome over initial states drawn from
  `sample` (a fixed count, or adaptively to a target standard error); or, with `grid`
  instead of `sample`, one run per cell of a grid of 1 or 2 initial-state keys (a basin map).
- `trace`: follow every jump curve through a plane of one scene key and mu (a first look
  finds the curves, each is followed with adaptive steps, folds located; docs/trace.md).

Varied values are a list of numbers or `{start, stop, num}` (numpy.linspace). Any numeric
scene key may be varied, numerics ones included (`numerics.rtol`, `contact.stiffness`).

The keys, defaults and units are the task specs (frictiondisk/tasks/<task>/spec.py,
found through frictiondisk.tasks.registry; docs/reference.md). Validation follows
`frictiondisk.model.scene`: the base scene is validated exactly as a scene file (same
paths, same messages); every varied value is checked by building the scene it gives; all
problems are collected and raised together as one `ConfigError`, one line `dotted.path:
what is wrong; what is allowed` each, list items written `path[i]`.
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
from collections.abc import Mapping
from dataclasses import dataclass
from os import PathLike
from typing import Any

import numpy as np
import yaml
from pydantic import ValidationError

from frictiondisk.model.auto_numerics import NumericsChoice
from frictiondisk.model.scene import ConfigError, SceneConfig, scene_from_dict
from frictiondisk.model.schema import error_lines, problems_of
from frictiondisk.model.schema import show as _show
from frictiondisk.model.varied import scene_value
from frictiondisk.model.yamlio import StrictDumper, load_yaml_text, read_text_file
from frictiondisk.tasks.campaign_file import SCENE_KEYS, campaign_file_model
from frictiondisk.tasks.entry import TaskEntry
from frictiondisk.tasks.registry import TASKS
from frictiondisk.tasks.spec import TaskSpec

__all__ = [
    "Campaign",
    "Point",
    "campaign_from_dict",
    "campaign_from_text",
    "load_campaign",
]

TASK_KEYS = tuple(TASKS)
CampaignFile = campaign_file_model(TASKS.values())
_MISSING: Any = object()  # a key not given at all (unlike a null value)


# --- the campaign -----------------------------------------------------------------------


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
    form as YAML); it does not take part in equality. A find_jump's numerics keys not given
    (numerics auto) are chosen from its tol when it is read: `base` holds the values,
    `numerics_choice` what was chosen and why (frictiondisk.model.auto_numerics).
    """

    name: str
    base: SceneConfig
    task: TaskSpec
    text: str = dataclasses.field(default="", compare=False, repr=False)
    # find_jump: the numerics its tol chose or rated (base holds the values)
    numerics_choice: NumericsChoice | None = dataclasses.field(
        default=None, compare=False, repr=False
    )

    @property
    def kind(self) -> str:
        """The task's name: its section's key in the file."""
        return self.task.kind

    @property
    def entry(self) -> TaskEntry:
        """The task's plug-in (frictiondisk.tasks.registry)."""
        return TASKS[self.task.kind]

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

        `config` is the base scene with the point's values set, and those the task sets at
        every point (a scan: numerics.mode = its mode).
        """
        axes = self._axes()
        fixed = self.task.point_overrides()
        points = []
        # each axis value as its scene field takes it, once per value, not once per point
        as_scene = {dim: [scene_value(dim, value) for value in axes[dim]] for dim in axes}
        for index in itertools.product(*(range(len(values)) for values in axes.values())):
            coords = {dim: axes[dim][i] for dim, i in zip(axes, index, strict=True)}
            overrides = {dim: as_scene[dim][i] for dim, i in zip(axes, index, strict=True)}
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
        return self.task.axes()


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
    """Validate: the file's keys and name, then the base scene (as a scene file), then the
    one task, its values checked against the base scene."""
    base, scene_problems, tasks = None, [], []
    if isinstance(data, Mapping):
        try:
            base = scene_from_dict({k: data[k] for k in SCENE_KEYS if k in data}, source=source)
        except ConfigError as err:
            scene_problems = err.problems
        tasks = [key for key in TASK_KEYS if key in data]
        if len(tasks) != 1:  # no task is validated until there is exactly one
            data = {key: value for key, value in data.items() if key not in TASK_KEYS}
    try:
        spec = CampaignFile.model_validate(data, context={"base": base})
        errors = []
    except ValidationError as err:
        if not isinstance(data, Mapping):
            raise ConfigError(problems_of(err, CampaignFile, brackets=True), source) from None
        spec, errors = None, sorted(err.errors(include_url=False), key=_rank)
    lines = {rank: [] for rank in range(3)}
    for error in errors:
        lines[_rank(error)] += error_lines(error, CampaignFile, brackets=True)
    problems = lines[0] + lines[1] + scene_problems + lines[2]
    if not tasks:
        problems.append(f"(top level): no task: give exactly one of {', '.join(TASK_KEYS)}")
    elif len(tasks) > 1:
        problems.append(
            f"(top level): {' and '.join(tasks)} given: give exactly one task "
            f"({', '.join(TASK_KEYS)})"
        )
    if problems:
        raise ConfigError(problems, source)
    task = getattr(spec, tasks[0])
    choice = task.numerics_choice(base, data.get("numerics"))  # find_jump: from its tol
    if choice is not None and choice.chosen:
        base = base.with_overrides(choice.overrides())
    campaign = Campaign(name=spec.name, base=base, task=task, numerics_choice=choice)
    if text is None:
        # Block-style YAML like yamlio.dump_yaml, but `along` keeps its order (the dims).
        text = yaml.dump(
            campaign.canonical(), Dumper=StrictDumper, sort_keys=False, default_flow_style=False
        )
    return dataclasses.replace(campaign, text=text)


def _rank(error: Any) -> int:
    """Where a file's error is listed: unknown keys first (as in a scene file), then the
    name; the base scene's problems follow, then the task's."""
    head = error["loc"][:1]
    if head and head[0] in TASK_KEYS:
        return 2
    return 0 if error["type"] in ("extra_forbidden", "invalid_key") else 1


# --- helpers ----------------------------------------------------------------------------


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
