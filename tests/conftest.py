"""Shared test helpers: the Coulomb oracle of the pin (docs/model.md section 6), and a
campaign subprocess that a test stops with a real signal."""

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


# 24 points at tol 1e-8: long enough (about 5 s) to be stopped after its second point
# Long: its numerics are fixed far looser than tol 1e-8 needs (numerics auto would pick
# tighter ones and take a third of the runs), so every point re-searches at the stricter
# certification levels, about 30 runs a point: time enough (48 points) to stop it mid-way.
LONG_CAMPAIGN = """\
name: stop_line
scene: pin
numerics: {rtol: 1.0e-6, atol: 1.0e-9}
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-8
  lanes: 1
  along: {params.x_ms: {start: 0.05, stop: 0.15, num: 48}}
"""


def points_done(out) -> int:
    """points_done in out/status.json (0 while there is none)."""
    import json

    try:
        return json.loads((out / "status.json").read_text()).get("points_done", 0)
    except (OSError, ValueError):
        return 0


def start_campaign_until(spec, out, points: int = 2, env=None, cwd=None):
    """`frictiondisk run spec -o out` as a subprocess (stdout and stderr piped, text),
    returned once `points` points are done; fails if it ended before."""
    import subprocess
    import sys
    import time

    proc = subprocess.Popen(
        [sys.executable, "-m", "frictiondisk.cli", "run", str(spec), "-o", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=cwd,
    )
    t0 = time.time()
    while time.time() - t0 < 120 and proc.poll() is None and points_done(out) < points:
        time.sleep(0.02)
    assert proc.poll() is None, "the campaign finished before the signal"
    return proc
