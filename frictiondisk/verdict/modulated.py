"""The evidence of a modulated cycle, or of a whirl's ripple or dying envelope, from the
envelopes of the step-mean |r| (envelopes.py; docs/model.md section 6, "The modulated
cycle").

* modulated: env_count whole envelopes agree in period and depth within env_tol, their
  depth shows no trend (envelope_trend.py: no rate beyond its errors over up to
  env_trend_count envelopes, and at its bound a change within env_tol over as long again),
  the depth at least env_min_depth of the mean radius and env_min_depth_tols cycle_tol,
  and not at the layout's aliased ripple frequency (the layout guard: a ring of N contacts
  makes |r| ripple at N |Omega - phidot|, which a section taken once a whirl aliases into
  a slow beat). Or the depths settle geometrically towards a limit that keeps that depth
  (Aitken), converged where the rest is within tol. Or, read ahead over at least
  env_trend_count envelopes (rule envelope_trend), the depth grows: the motion leaves the
  whirl.
* slide_cycle: steady envelopes shallower than that, or at the aliased ripple, of a size
  shown steady (slide_cycle.py `shown`: else a spiral dying out or leaving); or an
  envelope that dies out geometrically (Aitken, or that trend falling on a line that does
  not bend towards a limit): the approach to a whirl.
"""

from __future__ import annotations

import math

import numpy as np

from .envelope_trend import DepthTrend, depth_trend
from .envelopes import Envelopes, aliased_ripple, envelopes
from .outcomes import MODULATED, SLIDE_CYCLE
from .own_evidence import ENVELOPE_TREND, MotionEvidence, OwnScene, aitken, cycle_reason
from .own_evidence import measures as own_measures
from .params import VerdictParams
from .slide_cycle import shown


def envelope(rows, scene: OwnScene, vp: VerdictParams) -> MotionEvidence | None:
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
    deep = depth >= max(vp.env_min_depth * mean, vp.env_min_depth_tols * scene.cycle_tol)
    alias = aliased_ripple(rows[-max(vp.alias_min_steps, int(period / rows["dt"][-1])) :], scene)
    layout = not math.isnan(alias) and abs(1.0 / period - alias) <= vp.layout_alias / period
    measures = own_measures(rows, scene, vp)
    shape = f"envelope period {period:.5g} s, depth {depth:.4g} m about {mean:.5g} m"
    if steady_period and steady_depth and (not deep or layout):
        why = "the layout ripple of the discrete ring" if layout else "a ripple"
        found = MotionEvidence(
            SLIDE_CYCLE,
            True,
            cycle_reason(f"its step-mean |r| only shows {why} ({shape})", measures),
            envelope_period=period,
            envelope_depth=depth,
            **measures,
        )
        return shown(rows, found, scene, vp)
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
            cycle_reason(
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
            cycle_reason(
                f"its envelope dies out by {ratio:.3g} per envelope of {period:.5g} s", measures
            ),
            floquet_ratio=ratio,
            decay_rate=-math.log(ratio) / period,
            **measures,
        )
    if limit < max(
        vp.env_min_depth * measures["mean_radius"], vp.env_min_depth_tols * scene.cycle_tol
    ):
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
