"""The envelopes of a pure slide's step-mean |r| (docs/model.md section 6, "The modulated
cycle"): whole envelopes between upward crossings of its mean, and the layout ripple's
frequency as a section taken once a whirl aliases it. Facts only: modulated.py reads them.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .own_evidence import OwnScene


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


def peak(values: np.ndarray, i: int) -> float:
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
        top = peak(part, int(np.argmax(part)))
        low = -peak(-part, int(np.argmin(part)))
        depths.append(0.5 * (top - low))
    middles = 0.5 * (times[:-1] + times[1:])
    return Envelopes(np.diff(times), np.array(depths), middles, mean, up)


def aliased_ripple(rows: np.ndarray, scene: OwnScene) -> float:
    """Frequency [Hz] at which the layout ripple N |Omega - phidot| appears in a section
    taken once a whirl (NaN for the pin)."""
    if scene.arm <= 0.0 or scene.n_contacts < 2:
        return math.nan
    period = float(np.mean(rows["dt"]))
    spin = float(np.sum(rows["spin"]) / np.sum(rows["dt"]))
    ripple = scene.n_contacts * abs(2.0 * math.pi / period - spin) / (2.0 * math.pi)
    sampling = 1.0 / period
    return abs(ripple - round(ripple / sampling) * sampling)
