"""The scene of one run that a search requests (mu, mode, retry and certification
level), from its point's scene (`run_config`); and `PointScenes`, the same as an object
that travels with a search to the worker that advances it (tasks.jobs.RunSearch).
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any

from frictiondisk.model.scene import MAX_HORIZON_BUDGET, SceneConfig, scene_from_dict
from frictiondisk.model.schema import INT64_MAX
from frictiondisk.model.search_settings import OFF, Certify
from frictiondisk.tasks.jump_search.bisection import RunRequest
from frictiondisk.verdict.horizon import horizon_key, horizon_of


def run_config(
    point_config,
    request: RunRequest,
    horizon_factor: float,
    certify: Certify = OFF,
    parameter: str = "params.mu",
):
    """The scene of one requested run: `parameter` (mu unless a find_jump bisects another
    scene key) = request.mu (and the request's numerics.mode, if it names one)
    set, horizon lengthened by the retry level; at certification level `request.strict`
    rtol and atol are multiplied by certify.rtol, contact.eps by certify.eps and the
    horizon budget by certify.horizon,
    once per level, and by horizon_factor once per level of `request.reach`, and a rodas4
    point's run integrates with certify.method unless `request.own_method`; a stricter run
    watches until `request.watch` (numerics.observe_until; with certify.observe, where
    evidence is always observed, its horizon reaches the watch instead)."""
    num = point_config.numerics
    mode = request.mode or num.mode
    key = f"numerics.{horizon_key(mode)}"
    horizon = horizon_of(point_config, mode)
    overrides: dict[str, Any] = {parameter: request.mu}
    if mode != num.mode:
        overrides["numerics.mode"] = mode
    if request.level:
        overrides[key] = horizon * horizon_factor**request.level
    if request.strict:
        # a stricter run observes from the same horizon on, with rtol and atol x certify.rtol
        # (atol too: on a braked disk it moves mu* more than rtol does) and certify.horizon
        # times the budget to find its evidence (docs/model.md section 7)
        overrides["numerics.rtol"] = num.rtol * certify.rtol**request.strict
        overrides["numerics.atol"] = num.atol * certify.rtol**request.strict
        if certify.eps != 1.0:
            # the friction law's resolution too: a slip below eps T a revolution counts as
            # none, so a verdict that slip decided must hold at a finer one
            overrides["contact.eps"] = point_config.contact.eps * certify.eps**request.strict
        if num.method == "rodas4" and not request.own_method:
            # another integrator, of higher order: fewer steps at the stricter tolerance
            overrides["numerics.method"] = certify.method
        budget = min(num.horizon_budget * certify.horizon**request.strict, MAX_HORIZON_BUDGET)
        # where one run covers `reach` retry levels, its budget reaches as far as the last
        # of them would (their horizon times the budget): the same reach, not restarted
        whole = min(budget * horizon_factor**request.reach, MAX_HORIZON_BUDGET)
        overrides["numerics.horizon_budget"] = whole
        # the work budgets grow with the time the run may take: a check given 4x the
        # horizon budget with the point's step budget ran out of steps, not of evidence
        # (a 48-point disk watched 18 000 s: 2e6 steps at ~5 700 s)
        share = whole / num.horizon_budget
        overrides["numerics.max_steps"] = min(int(num.max_steps * share), INT64_MAX)
        overrides["numerics.max_events"] = min(int(num.max_events * share), INT64_MAX)
        if certify.observe:
            # it decides only on what it sees (a repeating section, a stick): an
            # extrapolated verdict is then a prediction that certification checks
            overrides["numerics.evidence"] = "observe"
            horizon_here = horizon * horizon_factor**request.level
            if request.watch > horizon_here:
                # a watch (a motion boundary's end, certify.py) is a longer horizon here
                overrides[key] = min(request.watch, horizon_here * whole)
        elif request.watch > 0.0:
            # it watches before it may extrapolate (certify.py), within its budget
            horizon_here = horizon * horizon_factor**request.level
            overrides["numerics.observe_until"] = min(request.watch, horizon_here * whole)
            # and a departure from sticking decides only at the last horizon of its strict
            # budget at its own retry level (the further reach is for a motion that shows
            # no evidence): still departing after the watch, it is the same motion in
            # progress (section_evidence)
            overrides["numerics.follow_departures_until"] = horizon_here * budget
    return point_config.with_overrides(overrides)


@dataclasses.dataclass(frozen=True)
class PointScenes:
    """The scene of each run a point's search asks for: `run_config` from the point's scene
    (`point`: its `SceneConfig.canonical()`), built once where it is first called."""

    point: dict[str, Any]
    horizon_factor: float
    certify: Certify = OFF
    parameter: str = "params.mu"  # the bisected scene key

    @functools.cached_property
    def config(self) -> SceneConfig:
        """The point's scene."""
        return scene_from_dict(self.point)

    def __call__(self, request: RunRequest) -> SceneConfig:
        return run_config(self.config, request, self.horizon_factor, self.certify, self.parameter)
