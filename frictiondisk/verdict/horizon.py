"""The horizon rule: how far in simulated time a run may go, and its time unit.

A `converge` run follows the orbit until its limit cycle has converged, at most `t_max`; a
`decide` run only has to tell stick from not stick, at most `t_decide` (docs/model.md,
section 5). Dependency-free, so that campaign planning and figure captions can use it
without loading the kernel.
"""

from __future__ import annotations

import math


def horizon_key(mode: str) -> str:
    """The numerics field that bounds a run in numerics.mode `mode`: t_max or t_decide."""
    return "t_max" if mode == "converge" else "t_decide"


def horizon_of(config, mode: str | None = None) -> float:
    """The horizon [s] of a scene (`SceneConfig`) run in `mode` (default: its numerics.mode)."""
    num = config.numerics
    return float(getattr(num, horizon_key(mode or num.mode)))


def revolution(omega_m: float) -> float:
    """One master revolution 2 pi / omega_m [s]; 2 pi s for a master at rest (omega_m = 0)."""
    return 2.0 * math.pi / omega_m if omega_m > 0.0 else 2.0 * math.pi
