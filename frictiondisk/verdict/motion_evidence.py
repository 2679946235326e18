"""What a pure-sliding motion is, from its own section (docs/model.md section 6, "The
pure-sliding motions"): self-centring, a sliding limit cycle, a modulated cycle, or not
yet shown.

It reads the rows of kernel/own_section.py (one per whole turn of the velocity phase psi =
atan2(ydot, xdot), or one closed by time at rest) of the current sliding regime: the rows
after the last one in which the body stuck as a whole. The rules, in the order asked:

* self_centring.py `rest`: the speed falls steadily to nothing, or the motion is at rest;
* self_centring.py `ring_ripple`: the velocity turns with the ring's ripple, N phidot: a
  rest point shaken by its contacts, not a cycle;
* slide_cycle.py `cycle` and `ripple`: a contracting section, or a repeating section or a
  band inside the ring's ripple of a size shown steady (amplitude_trend.py); where that size
  falls on a straight line the motion is a spiral dying out (self_centring at its rate),
  where it grows the motion leaves its rest point (read ahead);
* modulated.py `envelope`: the envelopes of the step-mean |r| (envelopes.py);
* the size's trend alone: a spiral dying out, or a motion leaving its rest point.

A motion is named only when its evidence excludes its neighbours; anything else is no
evidence, and the run stays `slide` (not stick, its motion not yet shown), with the size's
trend in its reason. Plain numpy on at most OWN_RING rows, once per run after it ends: no
compile cost for the kernel.
"""

from __future__ import annotations

import numpy as np

from . import amplitude_trend as at
from .modulated import envelope
from .outcomes import MODULATED, SELF_CENTRING, SLIDE_CYCLE
from .own_evidence import (
    AMPLITUDE_TREND,
    ENVELOPE_TREND,
    MotionEvidence,
    OwnScene,
    aitken,
    at_rest,
    measures,
    section_points,
    sliding_rows,
    steady_ratio,
    tolerance,
)
from .params import VerdictParams
from .self_centring import dying_spiral, rest, ring_ripple
from .slide_cycle import cycle, leaves, ripple

__all__ = [
    "AMPLITUDE_TREND",
    "ENVELOPE_TREND",
    "MODULATED",
    "SELF_CENTRING",
    "SLIDE_CYCLE",
    "MotionEvidence",
    "OwnScene",
    "aitken",
    "judge",
    "section_points",
    "sliding_rows",
    "steady_ratio",
]


def judge(rows: np.ndarray | None, scene: OwnScene, vp: VerdictParams) -> MotionEvidence:
    """The pure-sliding motion shown by the own-section rows (module docstring)."""
    if rows is None:
        return MotionEvidence("", False, "no own section (this integrator keeps none)")
    regime = sliding_rows(rows)
    need = max(vp.own_slide_steps, vp.own_ratios + 1, 3)
    if regime.shape[0] < need:
        return MotionEvidence(
            "",
            False,
            f"{regime.shape[0]} own periods of sliding ({need} needed to read its own section)",
        )
    pts = section_points(regime, scene)
    dist = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    for rule in (rest, ring_ripple, cycle, ripple):  # cycle and ripple need a moving motion
        found = rule(regime, pts, dist, scene, vp)
        if found is not None:
            return found
    if at_rest(regime, tolerance(pts[-1], scene)):
        return _nothing(regime, dist, scene, vp, "")
    found = envelope(regime, scene, vp)
    if found is not None:
        return found
    trend = None if scene.observe else at.size_trend(regime, vp)
    what = at.kind(trend, vp)
    if what == at.FALLS:
        return dying_spiral(regime, trend, scene, vp)
    if what == at.GROWS:
        return leaves(regime, trend, scene, vp)
    return _nothing(regime, dist, scene, vp, f"; {at.describe(trend)}" if trend else "")


def _nothing(regime, dist, scene: OwnScene, vp: VerdictParams, trend: str) -> MotionEvidence:
    m = measures(regime, scene, vp)
    return MotionEvidence(
        "",
        False,
        f"its own section neither comes to rest, repeats with a steady size, contracts "
        f"steadily nor shows steady envelopes over {regime.shape[0]} own periods (newest "
        f"{m['own_period']:.4g} s, mean radius {m['mean_radius']:.4g} m, newest step "
        f"{float(dist[-1]):.3g} m{trend})",
        **m,
    )
