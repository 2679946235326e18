"""What a pure-sliding motion is, from its own section (docs/model.md section 6, "The
pure-sliding motions"): self-centring, a sliding limit cycle, a modulated cycle, or not
settled.

It reads the rows of kernel/own_section.py (one per whole turn of the velocity phase psi =
atan2(ydot, xdot)) of the current sliding regime: the rows after the last one in which the
body stuck as a whole. Each motion's evidence is a module of its own, asked in this order:

* self_centring_evidence.py: the speed falls geometrically to rest, still slipping;
* slide_cycle_evidence.py: the section repeats or contracts while the motion keeps moving,
  or a disk's whirl stays within its ring's ripple;
* modulated_evidence.py: what the envelopes of the step-mean |r| (envelopes.py) show: a
  modulated cycle, or a ripple or a dying envelope around a whirl (slide_cycle).

Anything else is no evidence: the run stays `slide` (not stick, not settled). Plain numpy
on at most OWN_RING rows, once per run after it ends: no compile cost for the kernel.
"""

from __future__ import annotations

import numpy as np

from .modulated_evidence import envelope_evidence
from .own_evidence import (
    MotionEvidence,
    OwnScene,
    own_measures,
    own_tolerance,
    section_points,
    sliding_rows,
)
from .params import VerdictParams
from .self_centring_evidence import rest_evidence
from .slide_cycle_evidence import ring_ripple_evidence, section_cycle_evidence

__all__ = ["MotionEvidence", "OwnScene", "judge"]


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
    # the cycle and the ripple need a motion that moves
    for rule in (rest_evidence, section_cycle_evidence, ring_ripple_evidence):
        found = rule(regime, pts, dist, scene, vp)
        if found is not None:
            return found
    resting = float(regime["v_max"][-1] * regime["dt"][-1]) <= own_tolerance(pts[-1], scene)
    found = None if resting else envelope_evidence(regime, scene, vp)
    if found is not None:
        return found
    m = own_measures(regime, scene)
    return MotionEvidence(
        "",
        False,
        f"its own section neither comes to rest, repeats, contracts steadily nor shows "
        f"steady envelopes over {regime.shape[0]} own periods (newest {m['own_period']:.4g} s, "
        f"mean radius {m['mean_radius']:.4g} m, newest step {float(dist[-1]):.3g} m)",
        **m,
    )
