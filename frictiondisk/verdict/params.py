"""Every threshold of the verdict in one documented record: `VerdictParams`.

What a run is (stick, creep, stick_slip, slide, undetermined) rests on a few dozen tuning
numbers: how many revolutions back a trend, how far a section may move and still repeat,
how close to zero an extrapolated slip must come. Each is a field here with its unit, its
default (the value the studies and the campaigns were run with) and a one-line reason;
the cases that pin each one are rows of tests/test_verdict_cases.py. The record is passed
in, never read from module globals: `simulate(config, verdict=VerdictParams(q_max=0.95))`
runs a scene under other thresholds without editing code (the default leaves every result
and every journal key as it was). The numba state machine reads it as a record
(`VerdictParams.record()`, dtype PARAMS); the Python label reads the dataclass.
Modelled on BifurcationKit's ContinuationPar: one record of every tuning parameter.

Scene-level settings (numerics.cycle_tol, cycle_count, window_revs, horizon_budget,
stick_rule, evidence) stay in the scene: they are part of what a user asks for and of
its journal key. Buffer capacities (kernel/records.py REV_RING, RING; SEQ_MAX) and the
integrator's event numerics (kernel/events.py) are no thresholds of the verdict.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from frictiondisk.kernel.records import REV_RING

from .param_ranges import (
    NON_NEGATIVE,
    POSITIVE,
    RATIO,
    SHARE,
    Allowed,
    allowed_range,
    check_value,
    count_range,
    threshold,
)
from .section_sequence import SEQ_MAX


@dataclasses.dataclass(frozen=True)
class VerdictParams:
    """The thresholds of the verdict (module docstring); units in each field's metadata."""

    # --- the co-rotation rule: the slip per revolution on the small orbit -----------------
    verdict_revs: int = threshold(
        5,
        "revolutions",
        "revolutions on the small orbit behind a slip-trend verdict: four decay ratios give "
        "a standard error; fewer let one grazing contact's lumpy slip look like a trend",
        allowed=count_range(3, REV_RING),
    )
    slide_revs: int = threshold(
        8,
        "revolutions",
        "revolutions of whole-body sliding behind the sliding evidence: a slip that fell at "
        "every one of them is an approach to sticking",
        allowed=count_range(3, REV_RING // 2),
    )
    envelope_periods: float = threshold(
        2.0,
        "oscillation periods",
        "each window of the sliding evidence's lowest-slip comparison spans this many periods "
        "of the slip's oscillation (read from its troughs), so that each holds a trough: an "
        "oscillating slip whose troughs fall cannot pass",
        allowed=POSITIVE,
    )
    envelope_min_revs: int = threshold(
        8,
        "revolutions",
        "least revolutions in each window of that comparison (the sliding evidence's own "
        "slide_revs): a slip that does not oscillate still shows its lowest value over 8",
        allowed=count_range(1, REV_RING // 2),
    )
    verdict_z: float = threshold(
        2.0,
        "standard errors",
        "by how much a decay must be established (~97.5 % one-sided)",
        allowed=POSITIVE,
    )
    limit_min_spacing: int = threshold(
        4,
        "revolutions",
        "least spacing of Aitken's limit of the slip per revolution: at 2 the last fast "
        "transient of a braked disk reads as the limit",
        allowed=count_range(1, REV_RING // 4),
    )
    limit_drift: float = threshold(
        0.02,
        "1",
        "largest spread of the limit's estimates (made 0 ... m revolutions back), as a share "
        "of the limit, for a ratchet to count as settled",
        allowed=Allowed(0.0, 1.0, hi_open=False),
    )
    creep_share: float = threshold(
        0.5,
        "1",
        "share of the last revolution's slip the extrapolated limit must keep for a settled "
        "ratchet (most of today's slip persists)",
        allowed=SHARE,
    )
    # --- evidence from the motion's own section ---------------------------------------------
    repeat_count: int = threshold(
        3,
        "section steps",
        "distances within tolerance that make a repeat",
        allowed=count_range(1, SEQ_MAX // 2),
    )
    max_lag: int = threshold(
        3,
        "sticking phases",
        "sticking phases per period of a cycle recognised as a repeat",
        allowed=count_range(1, SEQ_MAX // 4),
    )
    contract_distances: int = threshold(
        5,
        "section steps",
        "distances behind a contraction ratio and its trend",
        allowed=count_range(3, SEQ_MAX // 2),
    )
    q_max: float = threshold(
        0.98,
        "1",
        "largest extrapolated contraction ratio accepted as convergence to a cycle",
        allowed=RATIO,
    )
    rho_max: float = threshold(
        0.9,
        "1",
        "the contraction ratio's own changes must shrink at least this fast ...",
        allowed=RATIO,
    )
    q_steady: float = threshold(0.01, "1", "... unless each of them is below this", allowed=SHARE)
    geometric_keep: float = threshold(
        0.75,
        "1",
        "1 - q now must keep this share of 1 - q half the sequence ago: geometric, not "
        "algebraic (a power law halves it)",
        allowed=Allowed(0.0, 1.0, lo_open=True, hi_open=False),
    )
    contract_slip_fall: float = threshold(
        0.1,
        "1",
        "share of the slip per step that may still fall on the way to a contracting cycle",
        allowed=SHARE,
    )
    contract_slip_fall_stribeck: float = threshold(
        0.01,
        "1",
        "the same under a Stribeck law, whose friction rises as the slip slows and feeds its "
        "own fall: only what a steady slip may lose (steady_fall)",
        allowed=SHARE,
    )
    slip_steady: float = threshold(
        1e-4,
        "1",
        "changes of the slip per step below this share of it are no change",
        allowed=SHARE,
    )
    depart_steps: int = threshold(
        4,
        "section steps",
        "steps of growing slip and shrinking sticking time behind a departure",
        allowed=count_range(2, SEQ_MAX // 2),
    )
    stick_noise: float = threshold(
        1e-9,
        "s",
        "sticking times closer than this are equal (event location ~1e-11 s)",
        allowed=NON_NEGATIVE,
    )
    approach_steps: int = threshold(
        8,
        "section steps",
        "steps over which a creep onto a sticking circle is recognised ...",
        allowed=count_range(2, SEQ_MAX),
    )
    approach_fall: float = threshold(
        1e-3,
        "1",
        "... by a fall of the slip per step by more than this share of it",
        allowed=Allowed(0.0, 1.0),
    )
    shakedown_steps: int = threshold(
        8,
        "section steps",
        "steps needed before a slip limit is extrapolated (shakedown)",
        allowed=count_range(4, SEQ_MAX),
    )
    shakedown_depth: float = threshold(
        1e-2,
        "1",
        "a limit is read only once the slip per step has fallen below this share of its "
        "largest value: a first fall that looks geometric can level off at a cycle",
        allowed=Allowed(0.0, 1.0, lo_open=True, hi_open=False),
    )
    shakedown_zero: float = threshold(
        1e-2,
        "1",
        "the extrapolated limit must be at most this share of the slip still left: a fall "
        "levelling off at a slip below eps T is a cycle there, not sticking",
        allowed=SHARE,
    )
    section_min_spacing: int = threshold(
        4,
        "section steps",
        "least spacing of an Aitken triple of the section's slip: at 2 a last transient looks "
        "like a limit",
        allowed=count_range(1, SEQ_MAX // 4),
    )
    aitken_slowing: float = threshold(
        0.7,
        "1",
        "the second fall of an Aitken triple must be at most this share of the first: an "
        "almost linear fall gives no well-conditioned limit (S ~ n^-p, p >= 1.03)",
        allowed=RATIO,
    )
    log_lookback: float = threshold(
        0.75,
        "1",
        "a power law's log-spaced fall ratio is compared with the one at this share of n ...",
        allowed=SHARE,
    )
    log_ratio_drift: float = threshold(
        0.03,
        "1",
        "... and may have grown by at most this (a fall levelling off grows it)",
        allowed=Allowed(0.0, 1.0),
    )
    # --- is a small slip per period steady? ------------------------------------------------
    fall_window: int = threshold(
        128,
        "section steps",
        "newest steps over which a slip per period is shown steady",
        allowed=count_range(3, SEQ_MAX),
    )
    fall_min: int = threshold(
        8, "periods", "least periods in that window", allowed=count_range(3, SEQ_MAX)
    )
    steady_fall: float = threshold(
        0.01,
        "1",
        "a steady slip per period loses (or gains) at most this share over the window ...",
        allowed=SHARE,
    )
    fall_z: float = threshold(
        2.0, "standard errors", "... at this many standard errors of its trend", allowed=POSITIVE
    )
    # --- Melan's shakedown bound of a braked disk -------------------------------------------
    on_orbit_revs: int = threshold(
        5,
        "revolutions",
        "revolutions on the small orbit before the bound decides (as the rules)",
        allowed=count_range(1, REV_RING),
    )
    bound_blocks: int = threshold(
        3,
        "blocks",
        "blocks of on_orbit_revs revolutions whose reserves show it approaching zero or not",
        allowed=count_range(2),
    )
    bound_solver_rtol: float = threshold(
        1e-8,
        "1",
        "relative accuracy of the limit analysis (measured 1e-9), part of the bound's margin",
        allowed=SHARE,
    )
    # --- the exact Coulomb pin creeping onto the rim of its sticking disc -------------------
    rim_check_every: int = threshold(
        8, "stick onsets", "onsets between two tests of a creep", allowed=count_range(1)
    )
    rim_min_onsets: int = threshold(
        16, "stick onsets", "onsets in the fitted window at least", allowed=count_range(3)
    )
    rim_min_fall: float = threshold(
        1.5,
        "1",
        "the gap to the rim falls by this factor over the window (1/n falls by 2 over its "
        "newest half)",
        allowed=Allowed(1.0, lo_open=True),
    )
    rim_max_residual: float = threshold(
        0.05, "1", "rms residual of the tangent-map line, relative to its mean", allowed=POSITIVE
    )
    rim_max_ratio_drift: float = threshold(
        0.1,
        "1",
        "relative change of 1 - ratio over a geometric approach to a cycle",
        allowed=POSITIVE,
    )
    rim_max_limit: float = threshold(
        0.1,
        "1",
        "the fitted limit may lie above the rim by this share of the newest gap",
        allowed=NON_NEGATIVE,
    )

    # --- a Coulomb pin grazing its sticking circle (verdict/grazing.py) --------------------
    graze_revs: int = threshold(
        8,
        "revolutions",
        "newest revolutions in each of which the pin must leave sticking for a moment "
        "behind a grazing departure (as slide_revs)",
        allowed=count_range(2, REV_RING),
    )
    graze_margin: float = threshold(
        0.2,
        "rad",
        "the slip's direction stays this far short of tangential over its whole arc: at most "
        "2 pi (1 - stick share) of a revolution on one side of the largest demand, where it "
        "is acos |(m_s omega_m^2 - c_s) / g| from radial",
        allowed=Allowed(0.0, 1.5707963267948966),
    )
    graze_slip: float = threshold(
        0.01,
        "1",
        "each of those revolutions slips at most this share of the circle's radius: a slip "
        "that short leaves the circle's geometry, and the slip's direction, as they were",
        allowed=SHARE,
    )

    # --- the motion's own section: the pure-sliding motions (verdict/motion_evidence.py) --
    own_slide_steps: int = threshold(
        3,
        "own periods",
        "own-section steps without whole-body sticking before a motion counts as sliding "
        "(a sticking phase ends the regime and its rows)",
        allowed=count_range(1),
    )
    own_ratios: int = threshold(
        4,
        "ratios",
        "successive ratios of the own section behind a geometric decay (as contract_distances)",
        allowed=count_range(2),
    )
    own_rest_zero: float = threshold(
        0.01,
        "1",
        "Aitken's limit of the largest speed per own period at most this share of the newest "
        "one: the motion comes to rest (as shakedown_zero)",
        allowed=Allowed(0.0, 1.0),
    )
    own_motion_keep: float = threshold(
        0.5,
        "1",
        "Aitken's limit of the largest speed per own period at least this share of the newest "
        "one: the limit still moves (a cycle, not rest)",
        allowed=POSITIVE,
    )
    own_rest_slip: float = threshold(
        10.0,
        "eps",
        "slip rate of the mean contact over the newest own period above this many eps: the "
        "rest state slides (a state at rest that does not slip is sticking)",
        allowed=POSITIVE,
    )
    own_window: int = threshold(
        32,
        "own periods",
        "window over which the band of the step-mean |r| of a disk's whirl is compared with "
        "its ring's ripple within an own period, and with the band of the window before",
        allowed=count_range(2),
    )
    band_change: float = threshold(
        2.0,
        "1",
        "a whirl's band of the step-mean |r| is steady while it changes by less than this "
        "factor from one window to the next (the ripple's aliasing beats it by less)",
        allowed=Allowed(1.0, lo_open=True),
    )
    env_count: int = threshold(
        3,
        "envelopes",
        "whole envelopes of the step-mean |r| behind a modulation (amplitudes A_j and A_j-1 "
        "compared twice)",
        allowed=count_range(2),
    )
    env_tol: float = threshold(
        0.01,
        "1",
        "envelopes agree within this share of their period and depth: sampled once a whirl "
        "(~20 samples an envelope) the extremes read from a parabola jitter ~1e-4, the "
        "layout ripple adds ~1e-5 m",
        allowed=SHARE,
    )
    env_min_depth: float = threshold(
        0.001,
        "1",
        "a modulation needs a depth of at least this share of the mean radius (and "
        "env_min_depth_tols cycle_tol): less is the whirl with its ripple",
        allowed=SHARE,
    )
    env_min_depth_tols: float = threshold(
        10.0,
        "cycle_tol",
        "a modulation needs a depth of at least this many cycle_tol: a shallower envelope is "
        "within the section's own tolerance of a whirl",
        allowed=Allowed(1.0),
    )
    env_trend_count: int = threshold(
        12,
        "envelopes",
        "whole envelopes (at least; all but the first env_count) behind the trend of the "
        "depth (ln depth against time) read ahead, and the most behind a steady depth's bound",
        allowed=count_range(3),
    )
    env_trend_sigmas: float = threshold(
        4.0,
        "standard errors",
        "a trend's rate counts beyond this many standard errors; a decay's implied limit and "
        "a steady depth's change are bounded at value plus this many",
        allowed=POSITIVE,
    )
    env_depth_precision: float = threshold(
        0.004,
        "1",
        "relative precision of an envelope's depth, a floor on the error of its trend's "
        "bend: near the torus bifurcation ln(depth) wobbles about its line by +-0.35 % with "
        "a period of ~20 envelopes (measured), which the residuals of fewer do not show",
        allowed=SHARE,
    )
    env_trend_limit: float = threshold(
        0.5,
        "1",
        "a decay whose bend implies a limit below this share of the newest depth dies out "
        "(a decay towards a modulation keeps more)",
        allowed=SHARE,
    )
    layout_alias: float = threshold(
        0.05,
        "1",
        "an envelope frequency within this share of the layout ripple N |Omega - phidot| "
        "aliased to the own period is the discrete ring, not a modulation",
        allowed=Allowed(0.0, 0.5),
    )
    # --- the pure-sliding motions: measures, the size's trend, the ring's ripple ----------
    own_period_rows: int = threshold(
        4,
        "own periods",
        "newest own-section steps whose mean duration is the own period",
        allowed=count_range(1),
    )
    alias_min_steps: int = threshold(
        8,
        "own periods",
        "least newest own periods over which the layout ripple's aliased frequency is read "
        "(at least an envelope's): its spin and period are means over them",
        allowed=count_range(2),
    )
    amp_trend_count: int = threshold(
        16,
        "own periods",
        "least own periods (the newer half of the regime, at least this) behind the trend of "
        "the motion's size: a repeat needs it shown steady (a spiral near a Hopf point "
        "repeats within tolerance while it decays: 3.8e-4 1/s at 4e-8 1/s error over 16)",
        allowed=count_range(3),
    )
    amp_trend_sigmas: float = threshold(
        4.0,
        "standard errors",
        "the size's rate counts beyond this many standard errors; a steady size's change is "
        "bounded at value plus this many (as env_trend_sigmas)",
        allowed=POSITIVE,
    )
    amp_precision: float = threshold(
        1e-3,
        "1",
        "a rate that changes the size by less than this share over the fitted span is no "
        "trend: the precision of an extent (a whirl's scatters by 1e-9, a Hopf spiral's "
        "ln(size) by 7e-5 about its line)",
        allowed=SHARE,
    )
    amp_steady_change: float = threshold(
        0.01,
        "1",
        "a steady size changes by at most this share over as long again at its rate's "
        "bound (as env_tol)",
        allowed=SHARE,
    )
    ring_ripple_tol: float = threshold(
        0.01,
        "1",
        "own periods within this share of 2 pi / (N |phidot|) turn with the ring's ripple: "
        "a disk at rest shaken by its contacts (measured within 4e-6 at 48 points)",
        allowed=SHARE,
    )

    def __post_init__(self) -> None:
        for field in dataclasses.fields(self):
            check_value(field, getattr(self, field.name))

    def record(self) -> np.void:
        """The record the numba state machine reads (dtype PARAMS; one per distinct set
        of values, made once: the machine only reads it)."""
        return _record(self)

    def changed(self) -> dict[str, float | int]:
        """The fields that differ from the defaults (empty for the defaults)."""
        default = VerdictParams()
        return {
            f.name: getattr(self, f.name)
            for f in dataclasses.fields(self)
            if getattr(self, f.name) != getattr(default, f.name)
        }


PARAMS = np.dtype(
    [
        (f.name, np.int64 if f.type in ("int", int) else np.float64)
        for f in dataclasses.fields(VerdictParams)
    ]
)


@functools.lru_cache(maxsize=64)
def _record(params: VerdictParams) -> np.void:
    values = tuple(getattr(params, f.name) for f in dataclasses.fields(params))
    return np.array([values], dtype=PARAMS)[0]


def markdown_table() -> str:
    """The record as a markdown table (docs/model.md, section 6: its parameters)."""
    lines = ["| name | unit | default | allowed | reason |", "|---|---|---|---|---|"]
    for f in dataclasses.fields(VerdictParams):
        lines.append(
            f"| `{f.name}` | {f.metadata['unit']} | {f.default!r} | {allowed_range(f)} | "
            f"{f.metadata['reason']} |"
        )
    return "\n".join(lines)
