"""The trend of a pure-sliding motion's size: ln(extent) of the newest own periods fitted
against time (envelope_trend.py's line, numpy after the run; docs/model.md section 6, "The
pure-sliding motions").

Near a rest point a slide's linearisation is a slow complex pair: the spiral about the rest
point grows or decays as exp(rate t), rate = Re(lambda) of that pair, and a Hopf point is
where it changes sign. There a spiral's section repeats within any tolerance for long
(the braked disk at omega_m 1.455, 48 points: 3.8e-4 1/s, 1e-7 m a period) while its size
falls tenfold over 6 000 s; the trend of ln(size) shows the rate with its standard error
within a few dozen own periods. So a `slide_cycle` needs its size shown steady: no rate
beyond amp_trend_sigmas errors (or a change over the fitted span below amp_precision, the
precision of an extent) and, at the rate's bound, a change of at most amp_steady_change
over as long again. A decay on a line that does not bend towards a limit (as
envelope_trend.py's `dies_out`) is a spiral dying out (`self_centring` at its rate); a
growth leaves the rest point (the Hopf point's other side).
"""

from __future__ import annotations

import numpy as np

from .envelope_trend import DepthTrend, depth_trend
from .own_evidence import sizes
from .params import VerdictParams

FALLS = "falls"  # a straight decay: a spiral dying out
GROWS = "grows"  # the size grows: the motion leaves its rest point
STEADY = "steady"  # no trend within its errors and its bound: a cycle's size
UNCLEAR = ""  # too few periods, a bent decay, or a bound too loose to call it steady


def size_trend(rows: np.ndarray, vp: VerdictParams) -> DepthTrend | None:
    """The trend of ln(size) over the newer half of the regime's rows, at least
    amp_trend_count of them; None with fewer rows or a size that is not positive."""
    count = max(vp.amp_trend_count, rows.shape[0] // 2)
    if rows.shape[0] < count:
        return None
    return depth_trend(rows["t"] - 0.5 * rows["dt"], sizes(rows), count)


def resolved(trend: DepthTrend, vp: VerdictParams) -> bool:
    """A rate beyond its errors that changes the size by more than amp_precision over the
    fitted span."""
    rate = abs(trend.rate)
    return rate > vp.amp_trend_sigmas * trend.rate_error and rate * trend.span > vp.amp_precision


def kind(trend: DepthTrend | None, vp: VerdictParams) -> str:
    """FALLS, GROWS, STEADY or UNCLEAR (module docstring)."""
    if trend is None:
        return UNCLEAR
    sigmas = vp.amp_trend_sigmas
    if resolved(trend, vp):
        if trend.rate > 0.0:
            return GROWS
        return FALLS if trend.dies_out(sigmas, vp.env_trend_limit) else UNCLEAR
    if trend.change_bound(sigmas) <= vp.amp_steady_change:
        return STEADY
    return UNCLEAR


def describe(trend: DepthTrend) -> str:
    return (
        f"ln(size) changes at {trend.rate:.4g} \u00b1 {trend.rate_error:.2g} 1/s over "
        f"{trend.count} own periods ({trend.span:.4g} s)"
    )
