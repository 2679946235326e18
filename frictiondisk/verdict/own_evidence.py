"""What every rule of the pure-sliding motions shares (docs/model.md section 6, "The
pure-sliding motions"): the scene they read, the evidence record they return, and the
plain measures of the own-section rows (kernel/own_section.py, kernel/records.py OWN_STEP).

Section point p_k = (x, y, xdot / w0, ydot / w0, l phidot / w0) [m] (w0 = sqrt(c_s / m_s)
the support's own frequency, or omega_m without a spring; l the longest arm), d_k =
|p_k - p_k-1|, tol_k = max(cycle_tol, atol + rtol |p_k|_inf) (as the section evidence),
V_k the largest speed |rdot| over step k, and the motion's size over step k its extent:
a quarter of the x and y ranges of the centre's path, summed (the radius of a circle;
the amplitude of a spiral about any rest point, on the axis or off it).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .params import VerdictParams

ENVELOPE_TREND = "envelope_trend"  # the rule that reads an envelope's trend ahead
AMPLITUDE_TREND = "amplitude_trend"  # the rule that reads the size's trend ahead


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
    decay_rate: float = math.nan  # -ln(ratio) / own period [1/s] (< 0: it grows)
    r_eq_x: float = math.nan  # the rest point (self-centring) [m]
    r_eq_y: float = math.nan
    r_eq: float = math.nan  # its radius [m]
    r_eq_angle: float = math.nan  # its angle from +x, counter-clockwise [rad]
    envelope_period: float = math.nan  # the modulation's period [s]
    envelope_depth: float = math.nan  # half its range of the step-mean |r| [m]
    rule: str = ""  # ENVELOPE_TREND or AMPLITUDE_TREND where a trend read ahead named it


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


def sizes(rows: np.ndarray) -> np.ndarray:
    """The motion's size over each step: a quarter of its x and y ranges, summed [m]."""
    return 0.25 * ((rows["x_max"] - rows["x_min"]) + (rows["y_max"] - rows["y_min"]))


def centre(row: np.void) -> np.ndarray:
    """The middle of the centre's path over one step (x, y) [m]."""
    return np.array([0.5 * (row["x_min"] + row["x_max"]), 0.5 * (row["y_min"] + row["y_max"])])


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


def measures(rows: np.ndarray, scene: OwnScene, vp: VerdictParams) -> dict[str, float]:
    """own_period (over the newest own_period_rows), mean_radius, amplitude, spin_rate."""
    last = rows[-1]
    newest = rows[-min(rows.shape[0], vp.own_period_rows) :]
    spin = float(last["spin"] / last["dt"]) if scene.arm > 0.0 else math.nan
    return {
        "own_period": float(np.mean(newest["dt"])),
        "mean_radius": float(last["r_mean"]),
        "amplitude": 0.5 * float(last["r_max"] - last["r_min"]),
        "spin_rate": spin,
    }


def tolerance(point: np.ndarray, scene: OwnScene) -> float:
    """tol_k of a section point [m] (module docstring)."""
    return max(scene.cycle_tol, scene.atol + scene.rtol * float(np.max(np.abs(point))))


def at_rest(rows: np.ndarray, tol: float) -> bool:
    """Whether the newest step moved less than tol [m] (its largest speed times its time)."""
    return float(rows["v_max"][-1] * rows["dt"][-1]) <= tol


def cycle_reason(how: str, m: dict[str, float]) -> str:
    return (
        f"a pure-sliding limit cycle: {how}; own period {m['own_period']:.6g} s, mean "
        f"radius {m['mean_radius']:.6g} m, amplitude {m['amplitude']:.4g} m"
    )


def rest_point(rest: np.ndarray) -> dict[str, float]:
    """The rest point's measures from (x, y) [m]."""
    x, y = float(rest[0]), float(rest[1])
    return {"r_eq_x": x, "r_eq_y": y, "r_eq": math.hypot(x, y), "r_eq_angle": math.atan2(y, x)}
