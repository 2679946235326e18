"""The study's settings as campaigns: where each scene's jumps are located, and the watches
that settle a disagreement.

Per scene and setting one find_jump campaign of one point (along its own x_ms):

* `default`: the campaign defaults: prescan mu = 0.02 ... 0.80 step 0.01, adaptive (its
  stride is the campaign's own), the numerics that tol 1e-4 chooses, certification on;
* `uncertified`: the same with certification off (what certification costs);
* `reference`: every prescan value run (stride 1), horizon x 8, rtol and atol / 100 of
  the default's numerics, no certification.

The ends of every certified default bracket are watched too (a certified end that its
watch contradicts is a silent error even where mu* agrees with the reference);
an end its regularized watch contradicts is watched again at rtol / 100 more, and that
watch, where it decides, takes the first one's place (study.recheck_contradicted_ends).
A watch is a scan campaign over the disputed mu of one scene: t_decide SETTLE_HORIZON,
horizon budget SETTLE_BUDGET, rtol, atol and eps / 100, `numerics.evidence: observe`
(only what a run shows counts); on a Coulomb pin the exact Coulomb integrator watches too
(`numerics.method: coulomb`, over the whole budget, or to a shorter horizon,
Options.exact_horizon: scipy Radau takes about 0.06 s of wall time a simulated second).
"""

from __future__ import annotations

import hashlib
import json
import math
from typing import Any

from frictiondisk.studies.campaigns import name_part

TOL = 1.0e-4
DEFAULT_STEP = 0.01  # the default's prescan step (the issue's own campaign and the shipped ones)
REFERENCE_STEP = 0.01
REFERENCE_HORIZON = 8.0  # factor on the default's t_decide
REFERENCE_RTOL = 0.01  # factor on the default's rtol and atol
SETTLE_HORIZON = 1500.0  # [s] t_decide of a watch
SETTLE_BUDGET = 8.0  # its horizon_budget: up to 12 000 s
SETTLE_RTOL = 0.01  # factor on rtol and atol of a watch
# factor on eps of a watch: slip eps T a revolution counts as none, and a braked disk's
# answer moves with eps below its Melan bound (docs/model.md section 6)
SETTLE_EPS = 0.01
COULOMB_MAX_STEPS = 50_000_000  # scipy Radau steps of an exact Coulomb watch
# a certified end its watch contradicts is watched again, rtol and atol / 100 more: a
# `creep` read at the rim can be the watch's own integration error (docs/wellposed.md)
RECHECK_RTOL = 0.01
RECHECK_STEPS = 4  # factor on its step budget (RODAS4: steps ~ rtol^(-1/4), 100^(1/4) ~ 3.2)
SETTLE_MAX = 6  # watched mu per disagreement at most (the nearest to the dispute)
SETTINGS = ("default", "uncertified", "reference")
PERSIST = 3.0  # [tol] a headline's persistence width (prescan.persist's default)
PERSIST_STEPS = (2, 5, 10, 20)  # [tol] above the reference's mu_hi, watched for a missed jump
WATCHES = ("regularized", "coulomb")


def default_grid(step: float) -> tuple[float, ...]:
    """The prescan: mu = 0.02 ... 0.80 in steps of `step`."""
    n_values = math.floor(0.78 / step + 1e-9) + 1  # the last value <= 0.80
    return tuple(round(0.02 + step * k, 5) for k in range(n_values))


def scene_name(seed: int, index: int, generator: int = 1) -> str:
    """s<seed>-<index> (generator 1, the names of earlier studies), g<k>-s<seed>-<index>."""
    return f"s{seed}-{index}" if generator == 1 else f"g{generator}-s{seed}-{index}"


def locate_name(
    seed: int, index: int, setting: str, step: float, observe: bool, generator: int = 1
) -> str:
    """The campaign name of a setting; a variant of the default (its step, observe) is
    a campaign of its own name, so that one output folder can hold several."""
    name = f"{scene_name(seed, index, generator)}-{setting}"
    if setting != "reference" and step != DEFAULT_STEP:
        name += f"-step{name_part(step)}"
    if setting == "default" and observe:
        name += "-observe"
    return name


def locate_campaign(
    name: str,
    scene: dict,
    setting: str,
    default_numerics: dict[str, float] | None = None,
    step: float = DEFAULT_STEP,
    observe: bool = False,
) -> dict[str, Any]:
    """The find_jump campaign of `setting` for `scene`. The reference needs the numerics
    the default's tol chose (`default_numerics`: t_decide, rtol, atol)."""
    prescan: dict[str, Any] = {"mu": list(default_grid(step)), "mode": "decide"}
    data = {"name": name, **scene}
    if setting == "reference":
        num = default_numerics
        if num is None:
            raise ValueError("the reference is built on the default's numerics: give them")
        prescan = {"mu": list(default_grid(REFERENCE_STEP)), "mode": "decide", "stride": 1}
        data["numerics"] = {
            "t_decide": num["t_decide"] * REFERENCE_HORIZON,
            "rtol": num["rtol"] * REFERENCE_RTOL,
            "atol": num["atol"] * REFERENCE_RTOL,
        }
    certify: Any = False
    if setting == "default":
        certify = {"observe": True} if observe else True
    data["find_jump"] = {
        "tol": TOL,
        "along": {"params.x_ms": [scene["params"]["x_ms"]]},
        "prescan": prescan,
        "certify": certify,
    }
    return data


def watch_scene(
    default_scene,
    longer: int = 1,
    exact: bool = False,
    exact_horizon: float | None = None,
    stricter: bool = False,
) -> dict[str, Any]:
    """The canonical scene of a watch (mu not set yet): the default's point scene
    (`default_scene`, a SceneConfig) with the long, strict, observing numerics above;
    `exact`: the Coulomb integrator's, to `exact_horizon` [s] (None: the whole budget).
    longer: a factor on the horizon and step budgets. stricter: rtol and atol a further
    RECHECK_RTOL, and RECHECK_STEPS times the step budget (the re-watch of a contradicted
    end)."""
    num = default_scene.numerics
    tighter = RECHECK_RTOL if stricter else 1.0
    config = default_scene.with_overrides(
        {
            "numerics.t_decide": SETTLE_HORIZON,
            "numerics.horizon_budget": SETTLE_BUDGET * longer,
            "numerics.max_steps": num.max_steps * longer * (RECHECK_STEPS if stricter else 1),
            "numerics.rtol": num.rtol * SETTLE_RTOL * tighter,
            "numerics.atol": num.atol * SETTLE_RTOL * tighter,
            "contact.eps": default_scene.contact.eps * SETTLE_EPS,
            "numerics.evidence": "observe",
        }
    )
    if exact:
        config = config.with_overrides(
            {
                "numerics.method": "coulomb",
                "numerics.t_decide": exact_horizon or SETTLE_HORIZON * SETTLE_BUDGET * longer,
                "numerics.max_steps": COULOMB_MAX_STEPS * longer,
            }
        )
    return config.canonical()


def watch_prefix(
    seed: int, index: int, watch: str, scene: dict[str, Any], generator: int = 1
) -> str:
    """The name every watch campaign of this scene, watch and numerics starts with: a
    hash of the watch's scene, so that watches under other numerics never mix."""
    digest = hashlib.sha256(json.dumps(scene, sort_keys=True).encode()).hexdigest()[:10]
    return f"{scene_name(seed, index, generator)}-watch-{watch}-{digest}"


def watch_campaign(prefix: str, scene: dict[str, Any], mus: list[float]) -> dict[str, Any]:
    """A scan of the watch scene over `mus` (one campaign per set of mu: its name ends in
    their hash)."""
    mus = sorted(set(mus))
    digest = hashlib.sha256(json.dumps(mus).encode()).hexdigest()[:8]
    return {"name": f"{prefix}-{digest}", **scene, "scan": {"mu": mus, "mode": "decide"}}
