"""What a pure-sliding motion is, from its own section (docs/model.md section 6, "The
pure-sliding motions"): self-centring, a sliding limit cycle, a modulated cycle, or not
settled.

It reads the rows of kernel/own_section.py (one per whole turn of the velocity phase psi =
atan2(ydot, xdot)) of the current sliding regime: the rows after the last one in which the
body stuck as a whole. Section point p_k = (x, y, xdot / w0, ydot / w0, l phidot / w0) [m]
(w0 = sqrt(c_s / m_s) the support's own frequency, or omega_m without a spring; l the
longest arm), d_k = |p_k - p_k-1|, tol_k = max(cycle_tol, atol + rtol |p_k|_inf) (as the
section evidence), V_k the largest speed |rdot| over step k.

* self_centring: V_k falls by a steady ratio q <= q_max (own_ratios ratios within q_steady
  of each other), Aitken's limit of V is at most own_rest_zero V_k (it comes to rest), and
  the mean contact still slips there faster than own_rest_slip eps (a sliding rest state,
  not sticking). Converged where the travel left, d_k q / (1 - q), is within tol_k.
* slide_cycle: V keeps moving (Aitken's limit at least own_motion_keep V_k) and the section
  repeats (repeat_count distances within tol_k) or contracts by a steady ratio q <= q_max
  (converged where the travel left is within tol_k); or the envelope of the step-mean |r|
  is steady with a depth below env_min_depth of the mean radius (a whirl with the ripple
  of its discrete ring) or at the layout ripple's aliased frequency.
* modulated: env_count whole envelopes of the step-mean |r| (between its upward crossings
  of its mean) agree in period and depth within env_tol, their depth shows no trend
  (envelope_trend.py: no rate beyond its errors over up to env_trend_count envelopes, and
  at its bound a change within env_tol over as long again), the depth at least
  env_min_depth of the mean radius and 10 cycle_tol, and not at the layout's aliased
  ripple frequency (the layout guard: a ring of N contacts makes |r| ripple at
  N |Omega - phidot|, which a section taken once a whirl aliases into a slow beat). Or the
  depths settle geometrically towards a limit that keeps that depth (Aitken), converged
  where the rest is within tol. Or, read ahead over at least env_trend_count envelopes
  (rule ENVELOPE_TREND), the depth grows: the motion leaves the whirl. An envelope that
  dies out geometrically (Aitken, or that trend falling on a line that does not bend
  towards a limit) is the approach to a whirl: slide_cycle.

Anything else is no evidence: the run stays `slide` (not stick, not settled). Plain numpy
on at most OWN_RING rows, once per run after it ends: no compile cost for the kernel.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .envelope_trend import DepthTrend, depth_trend
from .params import VerdictParams

SELF_CENTRING = "self_centring"
SLIDE_CYCLE = "slide_cycle"
MODULATED = "modulated"
ENVELOPE_TREND = "envelope_trend"  # the rule that reads an envelope's trend ahead


@dataclasses.dataclass(frozen=True)
class OwnScene:
    """What the evidence needs of the scene and its numerics (SI units)."""

    omega0: float  # the support's own frequency sqrt(c_s / m_s), or omega_m [rad/s]
    arm: float  # longest contact arm [m] (0 for the pin)
    eps: float  # the friction law's slide->stick threshold [m/s]
    n_contacts: int
    cycle_tol: float  # numerics.cycle_tol [m]
    atol: float
    rtol: float
    observe: bool = False  # numerics.evidence observe: no extrapolation
    # beta_s / 2 m_s [1/s]: the decay rate of a Coulomb pin's self-centring (its tangential
    # mode, which friction does not touch), quoted beside the measured rate
    tangential_rate: float = math.nan


@dataclasses.dataclass(frozen=True)
class MotionEvidence:
    """A pure-sliding motion and its measures (NaN where a measure does not apply)."""

    motion: str  # SELF_CENTRING, SLIDE_CYCLE, MODULATED, or "" (no evidence)
    converged: bool
    reason: str
    own_period: float = math.nan  # mean duration of the newest own steps [s]
    mean_radius: float = math.nan  # time mean of |r| over the newest own step (modulated:
    # over the envelopes) [m]
    amplitude: float = math.nan  # (max |r| - min |r|) / 2 over the newest own step [m]
    spin_rate: float = math.nan  # mean phidot over the newest own step [rad/s] (NaN: pin)
    floquet_ratio: float = math.nan  # contraction of the own section per own period [1]
    decay_rate: float = math.nan  # -ln(ratio) / own period [1/s]
    r_eq_x: float = math.nan  # the rest point (self-centring) [m]
    r_eq_y: float = math.nan
    r_eq: float = math.nan  # its radius [m]
    r_eq_angle: float = math.nan  # its angle from +x, counter-clockwise [rad]
    envelope_period: float = math.nan  # the modulation's period [s]
    envelope_depth: float = math.nan  # half its range of the step-mean |r| [m]
    rule: str = ""  # ENVELOPE_TREND where a trend read ahead named the motion


def sliding_rows(rows: np.ndarray) -> np.ndarray:
    """The rows of the current sliding regime: those after the newest locked row."""
    locked = np.flatnonzero(rows["locked"])
    return rows[locked[-1] + 1 :] if locked.size else rows


def section_points(rows: np.ndarray, scene: OwnScene) -> np.ndarray:
    """(k, 5) section points in metres (module docstring)."""
    w0 = scene.omega0
    return np.column_stack(
        (rows["x"], rows["y"], rows["xd"] / w0, rows["yd"] / w0, scene.arm * rows["phid"] / w0)
    )


def aitken(values: np.ndarray) -> float:
    """Aitken's limit of the newest three values (NaN where their steps do not shrink)."""
    a, b, c = (float(v) for v in values[-3:])
    denominator = (c - b) - (b - a)
    if denominator == 0.0 or abs(c - b) >= abs(b - a):
        return math.nan
    return c - (c - b) ** 2 / denominator


def steady_ratio(values: np.ndarray, count: int, vp: VerdictParams) -> float:
    """The ratio of successive values where the newest `count` ratios are all <= q_max and
    within q_steady of each other; NaN otherwise."""
    if values.shape[0] < count + 1 or np.any(values[-count - 1 : -1] <= 0.0):
        return math.nan
    ratios = values[-count:] / values[-count - 1 : -1]
    if np.max(ratios) > vp.q_max or np.ptp(ratios) > vp.q_steady:
        return math.nan
    return float(ratios[-1])


def _measures(rows: np.ndarray, scene: OwnScene) -> dict[str, float]:
    last = rows[-1]
    newest = rows[-min(rows.shape[0], 4) :]
    spin = float(last["spin"] / last["dt"]) if scene.arm > 0.0 else math.nan
    return {
        "own_period": float(np.mean(newest["dt"])),
        "mean_radius": float(last["r_mean"]),
        "amplitude": 0.5 * float(last["r_max"] - last["r_min"]),
        "spin_rate": spin,
    }


def _tolerance(point: np.ndarray, scene: OwnScene) -> float:
    return max(scene.cycle_tol, scene.atol + scene.rtol * float(np.max(np.abs(point))))


def _rest(rows, pts, dist, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
    """self_centring, where the evidence holds (module docstring): a steady geometric fall
    of the speed to an Aitken limit of nothing, or, shown, a motion that has come to rest
    (it moved less than tol_k in each of the newest repeat_count own periods)."""
    speed = rows["v_max"]
    tol = _tolerance(pts[-1], scene)
    count = vp.repeat_count
    at_rest = bool(np.all(speed[-count:] * rows["dt"][-count:] <= tol))
    q = steady_ratio(speed, vp.own_ratios, vp)
    limit = aitken(speed) if not math.isnan(q) else math.nan
    falls = not math.isnan(limit) and abs(limit) <= vp.own_rest_zero * float(speed[-1])
    if not falls and not at_rest:
        return None
    last = rows[-1]
    slip_rate = float(last["slip"] / last["dt"])
    if slip_rate <= vp.own_rest_slip * scene.eps:
        return None
    rest, tail = pts[-1, :2], 0.0
    if falls:
        tail = float(dist[-1]) * q / (1.0 - q)
        rest = pts[-1, :2] + (pts[-1, :2] - pts[-2, :2]) * q / (1.0 - q)
    shown = at_rest or bool(np.all(dist[-count:] <= tol))
    converged = shown if scene.observe else (shown or tail <= tol)
    measures = _measures(rows, scene)
    rate = -math.log(q) / measures["own_period"] if falls else math.nan
    radius = float(np.hypot(*rest))
    how = f"falls by {q:.4g} (rate {rate:.4g} 1/s)" if falls else "has fallen"
    return MotionEvidence(
        SELF_CENTRING,
        converged,
        f"self-centres: its largest speed per own period ({measures['own_period']:.4g} s) "
        f"{how} to rest at |r| = {radius:.6g} m, where it still slips at {slip_rate:.3g} m/s; "
        f"travel left {tail:.3g} m (tolerance {tol:.3g} m; beta_s/2m_s = "
        f"{scene.tangential_rate:.4g} 1/s)",
        floquet_ratio=q if falls else math.nan,
        decay_rate=rate,
        r_eq_x=float(rest[0]),
        r_eq_y=float(rest[1]),
        r_eq=radius,
        r_eq_angle=math.atan2(float(rest[1]), float(rest[0])),
        **measures,
    )


def _cycle(rows, pts, dist, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
    """slide_cycle from a repeating or contracting section (module docstring)."""
    speed = rows["v_max"]
    limit = aitken(speed)
    moving = math.isnan(limit) or limit >= vp.own_motion_keep * float(speed[-1])
    tol = _tolerance(pts[-1], scene)
    if not moving or float(speed[-1] * rows["dt"][-1]) <= tol:
        return None  # a motion that moves less than tol in a period is at rest
    measures = _measures(rows, scene)
    if dist.shape[0] >= vp.repeat_count and np.all(dist[-vp.repeat_count :] <= tol):
        how = f"its own section repeats within {float(np.max(dist[-vp.repeat_count :])):.3g} m"
        return MotionEvidence(SLIDE_CYCLE, True, _cycle_reason(how, measures), **measures)
    q = steady_ratio(dist, vp.own_ratios, vp)
    if math.isnan(q) or scene.observe:
        return None
    tail = float(dist[-1]) * q / (1.0 - q)
    rate = -math.log(q) / measures["own_period"]
    how = (
        f"its own section contracts by {q:.4g} per own period (Floquet rate {rate:.4g} 1/s), "
        f"travel left {tail:.3g} m (tolerance {tol:.3g} m)"
    )
    return MotionEvidence(
        SLIDE_CYCLE,
        tail <= tol,
        _cycle_reason(how, measures),
        floquet_ratio=q,
        decay_rate=rate,
        **measures,
    )


def _cycle_reason(how: str, measures: dict[str, float]) -> str:
    return (
        f"a pure-sliding limit cycle: {how}; own period {measures['own_period']:.6g} s, mean "
        f"radius {measures['mean_radius']:.6g} m, amplitude {measures['amplitude']:.4g} m"
    )


@dataclasses.dataclass(frozen=True)
class Envelopes:
    """The whole envelopes of the step-mean |r| (oldest first)."""

    periods: np.ndarray  # [s]
    depths: np.ndarray  # half the range of the step-mean |r| over each [m]
    middles: np.ndarray  # the time halfway through each [s]
    level: float  # the level whose upward crossings bound them [m]
    bounds: np.ndarray  # row index where each envelope starts, and where the last ends

    def mean(self, rows: np.ndarray, count: int) -> float:
        """Time mean of |r| over the newest `count` envelopes [m]."""
        part = rows[self.bounds[-count - 1] : self.bounds[-1]]
        return float(np.sum(part["r_mean"] * part["dt"]) / np.sum(part["dt"]))


def _peak(values: np.ndarray, i: int) -> float:
    """The vertex of the parabola through values[i - 1 : i + 2] (sampled once a whirl)."""
    if i <= 0 or i >= values.shape[0] - 1:
        return float(values[i])
    a, b, c = (float(v) for v in values[i - 1 : i + 2])
    curvature = a - 2.0 * b + c
    return b if curvature == 0.0 else b - (c - a) ** 2 / (8.0 * curvature)


def envelopes(rows: np.ndarray) -> Envelopes | None:
    """The envelopes between upward crossings of the step-mean |r| through its mean over
    the newer half of the regime; None with fewer than two crossings."""
    s = rows["r_mean"]
    t = rows["t"] - 0.5 * rows["dt"]
    mean = float(np.mean(s[s.shape[0] // 2 :]))
    up = np.flatnonzero((s[:-1] < mean) & (s[1:] >= mean)) + 1
    if up.shape[0] < 2:
        return None
    times = t[up - 1] + (mean - s[up - 1]) / (s[up] - s[up - 1]) * (t[up] - t[up - 1])
    depths = []
    for a, b in zip(up[:-1], up[1:], strict=True):
        part = s[a - 1 : b + 1]
        top = _peak(part, int(np.argmax(part)))
        low = -_peak(-part, int(np.argmin(part)))
        depths.append(0.5 * (top - low))
    middles = 0.5 * (times[:-1] + times[1:])
    return Envelopes(np.diff(times), np.array(depths), middles, mean, up)


def _aliased_ripple(rows: np.ndarray, scene: OwnScene) -> float:
    """Frequency [Hz] at which the layout ripple N |Omega - phidot| appears in a section
    taken once a whirl (NaN for the pin)."""
    if scene.arm <= 0.0 or scene.n_contacts < 2:
        return math.nan
    period = float(np.mean(rows["dt"]))
    spin = float(np.sum(rows["spin"]) / np.sum(rows["dt"]))
    ripple = scene.n_contacts * abs(2.0 * math.pi / period - spin) / (2.0 * math.pi)
    sampling = 1.0 / period
    return abs(ripple - round(ripple / sampling) * sampling)


def _band(rows: np.ndarray) -> tuple[float, float]:
    """(half the range of the step-mean |r|, the median half-range of |r| within a step)."""
    return 0.5 * float(np.ptp(rows["r_mean"])), float(np.median(rows["r_max"] - rows["r_min"])) / 2


def _ripple(rows, pts, dist, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
    """slide_cycle for a disk's whirl whose step-mean |r| stays, over the newest own_window
    steps, within the ripple of |r| inside one step (its discrete ring's, N |Omega - phidot|;
    averaged over a step a ripple can only shrink, while a modulation moves the step mean
    further than |r| moves within a step). Converged where that band is steady: within
    band_change of the band of the window before."""
    window = vp.own_window
    if scene.arm <= 0.0 or scene.n_contacts < 2 or rows.shape[0] < window:
        return None
    if float(rows["v_max"][-1] * rows["dt"][-1]) <= _tolerance(pts[-1], scene):
        return None  # at rest
    band, ripple = _band(rows[-window:])
    if band > ripple:
        return None
    converged = False
    how = f"its step-mean |r| stays within {band:.3g} m, inside the ripple of its ring"
    if rows.shape[0] >= 2 * window:
        before, _ = _band(rows[-2 * window : -window])
        converged = before <= vp.band_change * band and band <= vp.band_change * before
        how += f" ({ripple:.3g} m within an own period; {before:.3g} m the window before)"
    measures = _measures(rows, scene)
    measures["mean_radius"] = float(np.mean(rows["r_mean"][-window:]))
    return MotionEvidence(SLIDE_CYCLE, converged, _cycle_reason(how, measures), **measures)


def _envelope(rows, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
    """modulated, or slide_cycle for a ripple or a dying envelope (module docstring)."""
    env = envelopes(rows)
    if env is None or env.periods.shape[0] < vp.env_count:
        return None
    periods = env.periods[-vp.env_count :]
    depths = env.depths[-vp.env_count :]
    depth = float(depths[-1])
    period = float(periods[-1])
    mean = env.mean(rows, vp.env_count)
    depth_tol = max(scene.cycle_tol, vp.env_tol * depth)
    steady_period = np.ptp(periods) <= vp.env_tol * period
    steady_depth = np.ptp(depths) <= depth_tol
    deep = depth >= max(vp.env_min_depth * mean, 10.0 * scene.cycle_tol)
    alias = _aliased_ripple(rows[-max(8, int(period / rows["dt"][-1])) :], scene)
    layout = not math.isnan(alias) and abs(1.0 / period - alias) <= vp.layout_alias / period
    measures = _measures(rows, scene)
    shape = f"envelope period {period:.5g} s, depth {depth:.4g} m about {mean:.5g} m"
    if steady_period and steady_depth and (not deep or layout):
        why = "the layout ripple of the discrete ring" if layout else "a ripple"
        return MotionEvidence(
            SLIDE_CYCLE,
            True,
            _cycle_reason(f"its step-mean |r| only shows {why} ({shape})", measures),
            envelope_period=period,
            envelope_depth=depth,
            **measures,
        )
    if layout:
        return None
    count = env.depths.shape[0]
    read_ahead = count >= vp.env_trend_count and not scene.observe
    if read_ahead:
        # read before the depth test: a decay that has fallen below env_min_depth is still
        # the approach to the whirl, a growth from below it still leaves the whirl. Over
        # every envelope after the first env_count (the start's fast modes): near the
        # torus bifurcation ln(depth) wobbles by +-0.35 % with a period of ~20 envelopes,
        # which bends a shorter line by more than its errors say
        newest = max(vp.env_trend_count, count - vp.env_count)
        ahead = depth_trend(env.middles, env.depths, newest, vp.env_depth_precision)
        found = _trending(ahead, depth, depth_tol, period, measures, vp)
        if found is not None:
            return found
    if not deep:
        return None
    measures["mean_radius"] = mean  # of the cycle, not of the newest whirl
    trend = None
    if steady_period and steady_depth:
        trend = depth_trend(env.middles, env.depths, min(count, vp.env_trend_count))
    if trend is not None and _no_trend(trend, vp):
        return MotionEvidence(
            MODULATED,
            True,
            f"a modulated cycle: {vp.env_count} envelopes agree within {vp.env_tol:.3g} of "
            f"their period and depth, and the depth of {trend.count} changes by at most "
            f"{trend.change_bound(vp.env_trend_sigmas):.2g} over as long again "
            f"({trend.text()}; {shape}; own period {measures['own_period']:.5g} s)",
            envelope_period=period,
            envelope_depth=depth,
            **measures,
        )
    return _settling_envelope(env, depth_tol, measures, scene, vp, read_ahead)


def _no_trend(trend: DepthTrend, vp: VerdictParams) -> bool:
    """A depth shown steady: over env_trend_count envelopes no rate beyond its errors, and
    at the rate's bound it would change by at most env_tol in as long again (a slow growth
    or decay near the torus bifurcation keeps three envelopes within env_tol)."""
    if abs(trend.rate) > vp.env_trend_sigmas * trend.rate_error:
        return False  # a rate shown is a trend, however slow
    return trend.change_bound(vp.env_trend_sigmas) <= vp.env_tol


def _bend(trend: DepthTrend, vp: VerdictParams) -> str:
    sigmas = vp.env_trend_sigmas
    if not trend.bent(sigmas):
        return "straight within its errors"
    return f"its bend implying a limit of at most {trend.limit_share(sigmas):.2g} of the depth"


def _trending(trend: DepthTrend, depth, tol, period, measures, vp) -> MotionEvidence | None:
    """The envelope's trend read ahead (envelope_trend.py): a straight geometric decay is
    the approach to a whirl (slide_cycle), a growth leaves the whirl for a modulated
    cycle; None where the trend is within its errors."""
    sigmas = vp.env_trend_sigmas
    if trend.dies_out(sigmas, vp.env_trend_limit):
        ratio = math.exp(trend.rate * period)
        return MotionEvidence(
            SLIDE_CYCLE,
            depth <= tol,
            _cycle_reason(
                f"its envelope dies out geometrically ({trend.text()}, {_bend(trend, vp)}; "
                f"envelope period {period:.5g} s, depth {depth:.4g} m): the whirl is stable",
                measures,
            ),
            floquet_ratio=ratio,
            decay_rate=-trend.rate,
            rule=ENVELOPE_TREND,
            **measures,
        )
    if trend.grows(sigmas):
        return MotionEvidence(
            MODULATED,
            False,
            f"a modulated cycle, read ahead: its envelope grows ({trend.text()}; envelope "
            f"period {period:.5g} s, depth {depth:.4g} m), so the motion leaves the whirl",
            envelope_period=period,
            envelope_depth=depth,
            decay_rate=-trend.rate,
            rule=ENVELOPE_TREND,
            **measures,
        )
    return None


def _settling_envelope(
    env: Envelopes, tol, measures, scene, vp, read_ahead: bool
) -> MotionEvidence | None:
    """Envelope depths that settle geometrically: towards a depth (modulated) or to none
    (the approach to a whirl, slide_cycle); None otherwise or under evidence observe.
    Where the trend was read ahead and named nothing, Aitken's limit of three depths may
    only confirm a limit reached (within tol): read ahead from three depths that change by
    0.1 % an envelope it is noise (J_s 0.270313 near the torus bifurcation "settled
    towards" a depth 6 % below its newest while it decays)."""
    depths = env.depths
    if depths.shape[0] < 3 or scene.observe:
        return None
    limit = aitken(depths)
    if math.isnan(limit):
        return None
    rest = abs(float(depths[-1]) - limit)
    period = float(env.periods[-1])
    dies_out = limit <= vp.own_rest_zero * float(depths[-1])
    reached = float(depths[-1]) <= tol if dies_out else rest <= tol
    if read_ahead and not reached:
        return None
    if dies_out:
        ratio = float(depths[-1] / depths[-2])
        return MotionEvidence(
            SLIDE_CYCLE,
            float(depths[-1]) <= tol,
            _cycle_reason(
                f"its envelope dies out by {ratio:.3g} per envelope of {period:.5g} s", measures
            ),
            floquet_ratio=ratio,
            decay_rate=-math.log(ratio) / period,
            **measures,
        )
    if limit < max(vp.env_min_depth * measures["mean_radius"], 10.0 * scene.cycle_tol):
        return None
    return MotionEvidence(
        MODULATED,
        rest <= tol,
        f"a modulated cycle: its envelope depth settles towards {limit:.4g} m (newest "
        f"{float(depths[-1]):.4g} m, envelope period {period:.5g} s)",
        envelope_period=period,
        envelope_depth=limit,
        **measures,
    )


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
    for rule in (_rest, _cycle, _ripple):  # _cycle and _ripple need a motion that moves
        found = rule(regime, pts, dist, scene, vp)
        if found is not None:
            return found
    resting = float(regime["v_max"][-1] * regime["dt"][-1]) <= _tolerance(pts[-1], scene)
    found = None if resting else _envelope(regime, scene, vp)
    if found is not None:
        return found
    m = _measures(regime, scene)
    return MotionEvidence(
        "",
        False,
        f"its own section neither comes to rest, repeats, contracts steadily nor shows "
        f"steady envelopes over {regime.shape[0]} own periods (newest {m['own_period']:.4g} s, "
        f"mean radius {m['mean_radius']:.4g} m, newest step {float(dist[-1]):.3g} m)",
        **m,
    )
