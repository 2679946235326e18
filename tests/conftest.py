"""Shared test helpers: the Coulomb oracle of the pin (docs/model.md section 6)."""

from __future__ import annotations

import math


def g_factor(
    omega_m: float = 1.1, c_s: float = 1.0, beta_s: float = 0.1, m_s: float = 1.0
) -> float:
    """g = sqrt((c_s - m_s omega_m^2)^2 + (beta_s omega_m)^2) [N/m]: the force per metre of
    radius that a circle co-rotating at omega_m asks of the contact (defaults: the default
    scene's parameters)."""
    return math.hypot(c_s - m_s * omega_m**2, beta_s * omega_m)


def coulomb_mu_star(
    radius: float, x_ms: float = 0.1, F_n: float = 1.0, c_s: float = 1.0, **kw
) -> float:
    """The pin's Coulomb oracle: the least mu at which a sticking circle of `radius` [m]
    holds, mu F_n = c_s x_ms + g radius (other parameters as `g_factor`)."""
    return (c_s * x_ms + g_factor(c_s=c_s, **kw) * radius) / F_n


def pytest_configure(config) -> None:
    """The tests' subprocesses never meet a warm server (`frictiondisk serve`) left
    running by the developer: they look for one in a fresh private directory."""
    import os
    import tempfile

    os.environ["FRICTIONDISK_SERVER_DIR"] = tempfile.mkdtemp(prefix="frictiondisk-test-servers-")
