"""The accuracy study (`AccuracyStudy`): one bisection per distinct setting, gathered into
a Dataset. Pure Python: it says which searches to run (`searches`) and builds accuracy.nc
from them (`to_dataset`); frictiondisk.engine.local runs them in this process (serially,
or on a small thread pool: the kernel releases the GIL), reading no journal (a cost
study must not read cached runs).

Every setting of every knob (ladder.py) and every knob's reference is a scene: the
campaign point with the setting's overrides. Settings that give the same scene (same
content hash: e.g. rtol = 1e-9 and the numerics reference) are bisected once. Each
bisection is the campaign's own find_jump (bracket, limits, retries, horizon factor) with
the study's `tol`.

Cost of one setting, summed over the runs its bisection made:
* n_steps  accepted integrator steps (rodas4 kernel steps; for scipy-radau and coulomb,
           scipy Radau steps, which cost far more each), and t_simulated the simulated time
           they cover (steps per simulated second compare settings whose searches probed
           different mu);
* wall_s   the runs' own wall times (integration only, not config validation);
* n_events stick/slide transitions (all contacts), n_runs the runs themselves.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.model.scene import SceneConfig, describe_key
from frictiondisk.store import cf
from frictiondisk.store.journal_entry import kernel_version
from frictiondisk.studies.accuracy.ladder import (
    ATOL_PER_RTOL,
    Knob,
    Setting,
    build_ladder,
    default_knobs,
)
from frictiondisk.tasks.jobs import RunSearch
from frictiondisk.tasks.jump_search.bisection import UNDETERMINED, Bisection
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.requests import PointScenes
from frictiondisk.version import __version__

# CF flags of accuracy.nc (frictiondisk.store.cf.complete)
FLAGS = {
    "is_reference": ((0, 1), "not_reference reference"),
    "in_ladder": ((0, 1), "not_in_ladder in_ladder"),
    "monotone": ((0, 1), "contradicts_a_single_jump single_jump"),
}
VARIABLES = {  # name -> (units or None, long name)
    "knob": (None, "what is varied (accuracy/ladder.py)"),
    "series": (None, "marker series of the work-precision figure"),
    "key": (None, "dotted scene key varied"),
    "value": (None, "value of the varied key (units in value_units; NaN if not a number)"),
    "value_units": (None, "units of value"),
    "tag": (None, "short label of the setting"),
    "label": (None, "the setting"),
    "is_reference": ("1", "1 if this row is its knob's reference"),
    "in_ladder": ("1", "1 for a setting of the knob's ladder, 0 for its added reference"),
    "reference": (None, "the reference the error is measured against"),
    "mu_lo": ("1", "bracket end that does not stick"),
    "mu_hi": ("1", "bracket end that sticks"),
    "mu_star": ("1", "located jump mu* (bracket midpoint)"),
    "half_width": ("1", "half the bracket width (mu_hi - mu_lo)/2"),
    "mu_star_ref": ("1", "mu* of the knob's reference"),
    "error": ("1", "|mu* - mu*_ref|"),
    "error_bound": ("1", "uncertainty of error: half_width plus the reference's half width"),
    "wall_s": ("s", "wall time of the bisection's runs, summed"),
    "n_steps": ("1", "accepted integrator steps of the bisection's runs, summed"),
    "t_simulated": ("s", "simulated time of the bisection's runs, summed"),
    "n_rejected": ("1", "rejected integrator steps, summed"),
    "n_events": ("1", "stick/slide transitions of the bisection's runs, summed"),
    "n_runs": ("1", "runs the bisection made"),
    "n_undetermined": ("1", "runs that ended undetermined (each retried)"),
    "monotone": ("1", "0 if a stick was found below a not-stick"),
    "status": (None, "bisection status: converged or failed"),
    "reason": (None, "why this status"),
    "config_hash": (None, "content hash of the setting's scene (bisection parameter unset)"),
}


@dataclasses.dataclass(frozen=True)
class Outcome:
    """One bisection's answer and cost."""

    status: str
    reason: str
    mu_lo: float
    mu_hi: float
    monotone: bool
    wall_s: float
    n_steps: int
    t_simulated: float  # s
    n_rejected: int
    n_events: int
    n_runs: int
    n_undetermined: int

    @property
    def mu_star(self) -> float:
        return 0.5 * (self.mu_lo + self.mu_hi)

    @property
    def half_width(self) -> float:
        return 0.5 * (self.mu_hi - self.mu_lo)


def setting_search(config: SceneConfig, task, tol: float) -> RunSearch:
    """The bisection of mu* for one scene with the find_jump `task`'s bracket and rules at
    `tol`, as a job (no certification)."""
    bisection = Bisection(
        tuple(task.bracket),
        BisectionSettings(tol, tuple(task.limits), task.max_retries, root_finder=task.root_finder),
    )
    return RunSearch(bisection, PointScenes(config.canonical(), task.horizon_factor))


def outcome_of(bisection: Bisection) -> Outcome:
    """A finished setting's answer and cost."""
    result = bisection.result()
    runs = [run.result for run in result.runs]
    return Outcome(
        status=result.status,
        reason=result.reason,
        mu_lo=result.mu_lo,
        mu_hi=result.mu_hi,
        monotone=result.monotone,
        wall_s=float(sum(run["wall_s"] for run in runs)),
        n_steps=sum(run["n_steps"] for run in runs),
        t_simulated=float(sum(run["t_end"] for run in runs)),
        n_rejected=sum(run["n_rejected"] for run in runs),
        n_events=sum(run["n_transitions"] for run in runs),
        n_runs=len(runs),
        n_undetermined=sum(run["outcome"] == UNDETERMINED for run in runs),
    )


@dataclasses.dataclass(frozen=True)
class Row:
    setting: Setting
    config_hash: str
    is_reference: bool
    reference: str  # the knob's reference: label and note
    reference_hash: str
    in_ladder: bool = True  # False: the knob's reference, added because no setting is it


def plan_rows(base: SceneConfig, knobs: Sequence[Knob]) -> tuple[list[Row], dict[str, SceneConfig]]:
    """One row per setting, plus each knob's reference unless a setting already is it;
    and the distinct scenes to bisect, by content hash."""
    rows: list[Row] = []
    scenes: dict[str, SceneConfig] = {}

    def scene_of(setting: Setting) -> str:
        config = setting.config(base)
        key = config.content_hash()
        scenes.setdefault(key, config)
        return key

    for knob in knobs:
        ref_hash = scene_of(knob.reference)
        reference = f"{knob.reference.label} ({knob.note})"
        hashes = [scene_of(setting) for setting in knob.settings]
        for setting, key in zip(knob.settings, hashes, strict=True):
            rows.append(Row(setting, key, key == ref_hash, reference, ref_hash))
        if ref_hash not in hashes:
            rows.append(Row(knob.reference, ref_hash, True, reference, ref_hash, False))
    return rows, scenes


class AccuracyStudy:
    """The accuracy study at one point of a find_jump campaign (see module docstring).

    knobs: knob names (ladder.KNOBS); empty: every knob that applies to the scene.
    tol: bisection tolerance of every setting (much below the campaign's, or the bracket
    hides the errors)."""

    name = "accuracy"  # its progress bar's label
    unit = "bisection"  # what the bar counts

    def __init__(
        self,
        campaign,
        point_index: int = 0,
        knobs: Sequence[str] = (),
        tol: float = 1.0e-9,
        quick: bool = False,
    ):
        self.campaign, self.point_index, self.tol, self.quick = campaign, point_index, tol, quick
        self.base = campaign.points()[point_index].config
        names = tuple(knobs) or default_knobs(self.base.scene)
        self.ladder = build_ladder(self.base, names, quick)
        self.rows, self.scenes = plan_rows(self.base, self.ladder)

    def searches(self) -> dict[str, RunSearch]:
        """One bisection per distinct scene (by content hash)."""
        task = self.campaign.task
        return {key: setting_search(config, task, self.tol) for key, config in self.scenes.items()}

    def labels(self) -> dict[str, str]:
        """The label of each scene's (first) setting, to show while it runs."""
        labels: dict[str, str] = {}
        for row in self.rows:
            labels.setdefault(row.config_hash, row.setting.label)
        return labels

    def to_dataset(self, finished: dict[str, Bisection], wall: float, workers: int) -> xr.Dataset:
        """accuracy.nc from every scene's finished bisection; `wall` [s]: the study's wall
        time on `workers` threads."""
        outcomes = {key: outcome_of(bisection) for key, bisection in finished.items()}
        ds = build_dataset(self.rows, outcomes, self.scenes)
        attrs = _attrs(self, workers, wall)
        ds.attrs.update(attrs)
        ds.attrs.update(cf.scene_attrs(self.base))
        return cf.complete(
            ds,
            title=ds.attrs["title"],
            what=f"frictiondisk accuracy: campaign {self.campaign.name}, point {self.point_index}",
            flags=FLAGS,
            dimensionless=("setting",),
        )


def build_dataset(
    rows: Sequence[Row], outcomes: dict[str, Outcome], scenes: dict[str, SceneConfig]
) -> xr.Dataset:
    """accuracy.nc: one row (dim `setting`) per setting, variables as in VARIABLES."""
    columns: dict[str, list[Any]] = {name: [] for name in VARIABLES}
    for row in rows:
        out, ref = outcomes[row.config_hash], outcomes[row.reference_hash]
        both = out.status == "converged" and ref.status == "converged"
        setting = row.setting
        unit = _units(setting.key) if setting.key != "numerics.method" else ""
        nan = math.nan
        values = {
            "knob": setting.knob,
            "series": setting.series,
            "key": setting.key,
            "value": setting.value,
            "value_units": unit,
            "tag": setting.tag,
            "label": setting.label,
            "is_reference": int(row.is_reference),
            "in_ladder": int(row.in_ladder),
            "reference": row.reference,
            "mu_lo": out.mu_lo,
            "mu_hi": out.mu_hi,
            "mu_star": out.mu_star,
            "half_width": out.half_width,
            "mu_star_ref": ref.mu_star,
            "error": abs(out.mu_star - ref.mu_star) if both else nan,
            "error_bound": out.half_width + ref.half_width if both else nan,
            "wall_s": out.wall_s,
            "n_steps": out.n_steps,
            "t_simulated": out.t_simulated,
            "n_rejected": out.n_rejected,
            "n_events": out.n_events,
            "n_runs": out.n_runs,
            "n_undetermined": out.n_undetermined,
            "monotone": int(out.monotone),
            "status": out.status,
            "reason": out.reason,
            "config_hash": row.config_hash,
        }
        for name, value in values.items():
            columns[name].append(value)
    data_vars = {}
    for name, (units, long_name) in VARIABLES.items():
        values = columns[name]
        if values and isinstance(values[0], str):
            array = np.array(values, dtype=object)
        elif name in ("n_steps", "n_rejected", "n_events", "n_runs", "n_undetermined"):
            array = np.array(values, dtype=np.int64)
        elif name in ("is_reference", "in_ladder", "monotone"):
            array = np.array(values, dtype=np.int8)
        else:
            array = np.array(values, dtype=float)
        attrs = {"long_name": long_name, **({"units": units} if units else {})}
        data_vars[name] = ("setting", array, attrs)
    coords = {"setting": ("setting", np.arange(len(rows)), {"long_name": "row number"})}
    return xr.Dataset(data_vars, coords=coords)


def _units(key: str) -> str:
    try:
        unit, _ = describe_key(key)
    except KeyError:
        return ""
    return unit or ""


def _attrs(study: AccuracyStudy, workers: int, wall: float) -> dict:
    campaign, point_index, base = study.campaign, study.point_index, study.base
    ladder, tol, quick, n_bisections = study.ladder, study.tol, study.quick, len(study.scenes)
    point = campaign.points()[point_index]
    coords = ", ".join(f"{key} = {value:g}" for key, value in point.coords.items())
    task = campaign.task
    return {
        "title": "accuracy study of the jump mu* (frictiondisk accuracy)",
        "campaign_name": campaign.name,
        "campaign_yaml": campaign.text,
        "point_index": point_index,
        "point": coords,
        "scene": base.scene,
        "base_scene_yaml": base.to_yaml(),
        "tol": tol,
        "bracket": list(task.bracket),
        "limits": list(task.limits),
        "max_retries": task.max_retries,
        "horizon_factor": task.horizon_factor,
        "quick": int(quick),
        "workers": workers,
        "n_bisections": n_bisections,
        "study_wall_s": wall,
        "atol_per_rtol": ATOL_PER_RTOL,
        "knobs": ", ".join(knob.name for knob in ladder),
        "references": "\n".join(f"{knob.name}: {knob.note}" for knob in ladder),
        "physics_numerics": "rows of stiffness, damping, eps, points run at the numerics reference",
        "cost": "n_steps and wall_s summed over every run of the setting's bisection; "
        "scipy-radau and coulomb steps are scipy Radau steps",
        "frictiondisk_version": __version__,
        "kernel_version": kernel_version(),
    }
