"""The scene of one run that a search requests (mu, mode, retry and certification
level), from its point's scene. Shared by the planner (plan.py) and the worker (tasks.py), which import it from
here rather than from each other.
"""

from __future__ import annotations

from typing import Any

from frictiondisk.model.search_settings import OFF, Certify
from frictiondisk.outcome.horizon import horizon_key, horizon_of
from frictiondisk.search.bisection import RunRequest


def run_config(point_config, request: RunRequest, horizon_factor: float, certify: Certify = OFF):
    """The scene of one requested run: mu (and the request's numerics.mode, if it names one)
    set, horizon lengthened by the retry level; at certification level `request.strict`
    the horizon is multiplied by certify.horizon, rtol and atol by certify.rtol, once per
    level."""
    num = point_config.numerics
    mode = request.mode or num.mode
    key = f"numerics.{horizon_key(mode)}"
    horizon = horizon_of(point_config, mode)
    overrides: dict[str, Any] = {"params.mu": request.mu}
    if mode != num.mode:
        overrides["numerics.mode"] = mode
    if request.level or request.strict:
        overrides[key] = horizon * horizon_factor**request.level * certify.horizon**request.strict
    if request.strict:  # atol too: on a braked disk it moves mu* more than rtol does
        overrides["numerics.rtol"] = num.rtol * certify.rtol**request.strict
        overrides["numerics.atol"] = num.atol * certify.rtol**request.strict
    return point_config.with_overrides(overrides)
