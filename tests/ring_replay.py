"""Replay a recorded revolution ring through the verdict's own numba rules, as a run's step
loop calls them (verdict/machine.py): the co-rotation rule at every revolution, the horizon
evidence at t_decide + j T up to the horizon budget. Used where the motion that pins a rule
takes minutes to simulate but its ring is a few kilobytes (tests/data/). Not modelled: the
extension that finishes an open whole-body sticking phase, and the braked disk's bound."""

from __future__ import annotations

import math

import numpy as np

from frictiondisk.kernel.records import MOTION, PHASE, REV_RING, REVOLUTION, RING, one
from frictiondisk.model.scene import scene_from_dict
from frictiondisk.simulation.pack import new_rules, pack_parameters
from frictiondisk.verdict import machine
from frictiondisk.verdict import records as rc
from frictiondisk.verdict.corotation import corotation_verdict
from frictiondisk.verdict.horizon_evidence import evidence_at_horizon
from frictiondisk.verdict.params import VerdictParams
from frictiondisk.verdict.records import VERDICT
from frictiondisk.verdict.section_sequence import new_sequence

EVIDENCE = {
    rc.EV_REPEAT: "repeat",
    rc.EV_CONTRACT: "contract",
    rc.EV_DEPART: "depart",
    rc.EV_SHAKEDOWN: "shakedown",
    rc.EV_CANNOT: "cannot",
    rc.EV_SLIDING: "sliding",
}


def replay(scene: dict, rows: np.ndarray, vp: VerdictParams | None = None):
    """(decision, t [s], vs) of `scene` whose revolution ring held `rows` (REVOLUTION fields
    in order, one row a revolution, oldest first): "stick" (the co-rotation rule), an
    evidence name of EVIDENCE (at a horizon), "undetermined" (the budget spent) or
    "out of rows"; vs: the VERDICT record after it."""
    config = scene_from_dict(scene)
    vp = (vp or VerdictParams()).record()
    p, pts = pack_parameters(config)
    rules = new_rules(config)
    motion = one(MOTION)
    motion["arm"] = max(math.hypot(a, b) for a, b in pts[:, :2]) if config.scene == "disk" else 0.0
    vs = one(VERDICT)
    machine.begin(vp, rules, p, pts, motion, vs)
    phases = np.zeros(RING, dtype=PHASE)
    revs = np.zeros(REV_RING, dtype=REVOLUTION)
    seq = new_sequence()
    t_stop, hold = rules["horizon"], rules["hold"]
    for k, row in enumerate(rows, start=1):
        revs[(k - 1) % REV_RING] = tuple(row)
        motion["n_rev"] = k
        if corotation_verdict(vp, rules, motion, vs, revs) == rc.COROTATING:
            return "stick", float(row[0]), vs
        t_next = rows[k][0] if k < len(rows) else math.inf
        while t_stop < t_next:
            ev = evidence_at_horizon(vp, rules, motion, vs, phases, revs, p["omega_m"], seq, False)
            if ev != rc.EV_NONE:
                return EVIDENCE[ev], float(t_stop), vs
            if t_stop + hold > rules["budget"] * (1 + 1e-12):
                return "undetermined", float(t_stop), vs
            t_stop += hold
    return "out of rows", float(rows[-1][0]), vs
