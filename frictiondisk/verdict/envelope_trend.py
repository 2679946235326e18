"""The trend of a modulation's depth: ln(depth) of the newest whole envelopes fitted against
time by least squares (numpy, after the run; docs/model.md section 6, "The modulated
cycle").

Near the whirl the slow complex pair of its linearisation makes the envelope depth grow or
decay as exp(rate t): rate = Re(lambda) of that pair. Near the torus bifurcation this rate
is tiny (~1e-5 1/s at 1e-3 of J_s from it), so envelopes one after another look steady
while the fitted line over several of them shows the rate with its standard error. A
straight line (no curvature beyond its error) is a geometric growth or decay that
continues; a decay whose line bends as one towards a nonzero depth would (its rate
weakening as it nears that depth: a decay towards a modulation, or the power law of a
cubic decay) is not extrapolated to zero. Near the torus bifurcation ln(depth) wobbles
about its line by +-0.35 % with a period of ~20 envelopes (measured), which bends a line
over fewer envelopes by more than its residuals say: the motion evidence fits every
envelope but the start's (at least twelve), and the bend's error has a floor from the
depth's precision.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np


@dataclasses.dataclass(frozen=True)
class DepthTrend:
    """ln(depth) against time over the newest envelopes."""

    rate: float  # slope of ln(depth) [1/s]
    rate_error: float  # its standard error [1/s]
    curvature: float  # second derivative of a parabola through ln(depth) [1/s^2]
    curvature_error: float  # its standard error, at least the depth precision's [1/s^2]
    span: float  # time from the first to the last envelope's middle [s]
    count: int  # envelopes fitted

    def grows(self, sigmas: float) -> bool:
        """The depth grows: the rate exceeds `sigmas` standard errors."""
        return self.rate > sigmas * self.rate_error

    def limit_share(self, sigmas: float) -> float:
        """The depth a decay tends to, as a share of the depth, implied by the bend at its
        bound (value + `sigmas` errors) [1]: for depth = L + C exp(b t) the rate of
        ln(depth) weakens as it nears L, curvature / rate^2 = L / (depth - L) =: x, so
        L / depth = x / (1 + x) (0 for a bend the other way)."""
        x = max(self.curvature + sigmas * self.curvature_error, 0.0) / self.rate**2
        return x / (1.0 + x)

    def bent(self, sigmas: float) -> bool:
        """The line bends as a decay towards a limit would, beyond `sigmas` errors."""
        return self.curvature > sigmas * self.curvature_error

    def dies_out(self, sigmas: float, limit: float) -> bool:
        """The depth falls towards nothing: a rate below -`sigmas` standard errors on a line
        that does not bend towards a limit beyond `sigmas` errors, or whose bend implies a
        limit below `limit` of the depth at its bound."""
        falls = self.rate < -sigmas * self.rate_error
        return falls and (not self.bent(sigmas) or self.limit_share(sigmas) <= limit)

    def change_bound(self, sigmas: float) -> float:
        """The most the depth may change, as a share, over another `span` at the rate's
        bound |rate| + sigmas errors [1]."""
        return math.expm1((abs(self.rate) + sigmas * self.rate_error) * self.span)

    def text(self) -> str:
        return (
            f"rate {self.rate:.3g} \u00b1 {self.rate_error:.2g} 1/s over {self.count} "
            f"envelopes ({self.span:.4g} s)"
        )


def depth_trend(
    middles: np.ndarray, depths: np.ndarray, count: int, precision: float = 0.0
) -> DepthTrend | None:
    """The trend of the newest `count` envelopes (middle times [s], depths [m]); None with
    fewer envelopes, fewer than four, or a depth that is not positive. `precision` [1]: the
    relative precision of one depth, a floor on the curvature's error (the residuals of a
    few envelopes do not show a wobble slower than they span)."""
    if count < 4 or depths.shape[0] < count or np.any(depths[-count:] <= 0.0):
        return None
    t = middles[-count:] - float(np.mean(middles[-count:]))
    y = np.log(depths[-count:])
    line, line_cov = np.polyfit(t, y, 1, cov=True)
    bend, bend_cov = np.polyfit(t, y, 2, cov=True)
    design = np.vander(t, 3)
    floor = precision * math.sqrt(float(np.linalg.inv(design.T @ design)[0, 0]))
    return DepthTrend(
        rate=float(line[0]),
        rate_error=math.sqrt(max(float(line_cov[0, 0]), 0.0)),
        curvature=2.0 * float(bend[0]),
        curvature_error=2.0 * max(math.sqrt(max(float(bend_cov[0, 0]), 0.0)), floor),
        span=float(t[-1] - t[0]),
        count=count,
    )
