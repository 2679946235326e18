"""Binomial statistics of basin fractions: estimate, standard error, Wilson interval.

A fraction p = k / n of n sampled initial states. Its standard error is the binomial
sqrt(p (1 - p) / n); its 95 % interval is Wilson's score interval (scipy.stats.binomtest),
which, unlike p +- 1.96 SE, stays inside [0, 1] and does not collapse to a point when every
sample agrees (Menck et al., Nature Physics 2013 report the SE; Wilson is the usual
interval for small k or n - k).
"""

from __future__ import annotations

import math

CONFIDENCE = 0.95
# scipy.stats is imported where it is used: importing it costs about 1 s, which every
# `frictiondisk run` paid at start-up when the planners imported this module, basin or not


def fraction(k: int, n: int) -> float:
    """k / n; NaN for n = 0."""
    return k / n if n else math.nan


def standard_error(k: int, n: int) -> float:
    """Binomial standard error sqrt(p (1 - p) / n) of p = k / n; NaN for n = 0."""
    if not n:
        return math.nan
    p = k / n
    return math.sqrt(p * (1.0 - p) / n)


def wilson_interval(k: int, n: int, confidence: float = CONFIDENCE) -> tuple[float, float]:
    """Wilson score interval (no continuity correction) of p = k / n; NaNs for n = 0."""
    if not n:
        return math.nan, math.nan
    from scipy.stats import binomtest

    ci = binomtest(k, n).proportion_ci(confidence_level=confidence, method="wilson")
    return float(ci.low), float(ci.high)


def stopping_error(k: int, n: int, confidence: float = CONFIDENCE) -> float:
    """The error an adaptive basin run compares with `target_se`: the Wilson interval's
    half-width over z (z = 1.96 at 95 %). For large n it equals `standard_error`; unlike
    it, it does not vanish when every sample so far has the same outcome (k = 0 or n),
    so a first batch that happens to agree does not stop the sampling at once."""
    from scipy.stats import norm

    lo, hi = wilson_interval(k, n, confidence)
    return 0.5 * (hi - lo) / norm.ppf(0.5 + 0.5 * confidence)


def samples_for_error(p: float, target_se: float) -> int:
    """Samples n with sqrt(p (1 - p) / n) <= target_se (at most 1 / (4 target_se^2))."""
    return max(1, math.ceil(p * (1.0 - p) / target_se**2))
