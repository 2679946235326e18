"""Shared test helpers: the Coulomb oracle of the pin (docs/model.md section 6), and a
campaign subprocess that a test stops with a real signal."""

from __future__ import annotations

import gc
import math
import os
import signal
import sys
import warnings
from pathlib import Path


def _one_blas_thread_per_test_process() -> None:
    """Two test workers on two cores, each with OpenBLAS's own thread per core, oversubscribe
    them: OpenBLAS's threads spin while they wait, and with other work on the cores a
    126 x 126 solve took 6 s instead of 0.04 s. The limit is read when numpy loads, so it
    is set before (a campaign's Dask workers get the same from distributed's nanny)."""
    if "numpy" in sys.modules:
        warnings.warn(
            "numpy was imported before tests/conftest.py: BLAS may use several threads",
            stacklevel=2,
        )
    for variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(variable, "1")


_one_blas_thread_per_test_process()


def _stop_signals_at_their_defaults() -> None:
    """The tests stop campaign subprocesses with SIGINT and SIGHUP, which a campaign leaves
    ignored when it inherits them ignored (nohup, a background job: cli/campaign.py). A suite
    started that way (`nohup make test &`, some CI runners) must still test the stops."""
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    if hasattr(signal, "SIGHUP") and signal.getsignal(signal.SIGHUP) is signal.SIG_IGN:
        signal.signal(signal.SIGHUP, signal.SIG_DFL)


_stop_signals_at_their_defaults()


def pytest_sessionfinish(session) -> None:
    """Collect the session's garbage before a pytest-xdist worker reports that it finished.
    Once it has, execnet gives the worker's remaining teardown 5 s and then sends it a
    SIGINT; pytest's own last gc pass (its unraisable-exception check, after this) took
    longer on a busy machine, and the KeyboardInterrupt landed in a weakref callback and
    ended the suite's output with its traceback."""
    gc.collect()


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


# 48 points at tol 1e-8, one at a time: time enough to stop it mid-way (the stop tests run
# it on the fake simulate, tests/fake_simulate.py, each run a few tens of ms). On the kernel
# its numerics are fixed far looser than tol 1e-8 needs (numerics auto would pick tighter
# ones and take a third of the runs), so every point re-searches at the stricter
# certification levels, about 30 runs a point.
LONG_CAMPAIGN = """\
name: stop_line
scene: pin
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-8
  lanes: 1
  along: {params.x_ms: {start: 0.05, stop: 0.15, num: 48}}
"""


# [s] bounds a hang only: a wait for a campaign subprocess polls its progress, and a busy
# machine (a niced suite beside two studies) took more than 120 s to reach a mid-way goal
HANG_S = 600.0


def wait_until(ready, proc=None, what: str = "the campaign's progress", timeout: float = HANG_S):
    """Poll `ready()` every 20 ms until it is true. Fails, naming `what`, if subprocess
    `proc` ends first or `timeout` s pass, so a test never goes on to signal or kill a
    campaign that has not reached the state it needs."""
    import time

    deadline = time.monotonic() + timeout
    while not ready():
        assert proc is None or proc.poll() is None, f"the campaign ended before {what}"
        assert time.monotonic() < deadline, f"no {what} within {timeout:.0f} s"
        time.sleep(0.02)


def points_done(out) -> int:
    """points_done in out/status.json (0 while there is none)."""
    import json

    try:
        return json.loads((out / "status.json").read_text()).get("points_done", 0)
    except (OSError, ValueError):
        return 0


def wait_for_cpu(pid: int, seconds: float, timeout: float = 300.0) -> None:
    """Return once process `pid` has used `seconds` more CPU time (user + system, all its
    threads) than when called: "it has been working for a while" on any machine, where a
    sleep of as many seconds means less work the busier the machine is. Returns early if
    the process ends."""
    import time

    import psutil

    process = psutil.Process(pid)
    try:
        start = sum(process.cpu_times()[:2])
        deadline = time.monotonic() + timeout
        while sum(process.cpu_times()[:2]) - start < seconds and time.monotonic() < deadline:
            time.sleep(0.05)
    except psutil.NoSuchProcess:
        return


FAKE_CLI = Path(__file__).resolve().parent / "fake_cli.py"


def cli_command(fake_delay: float | None = None) -> list[str]:
    """The command line of `frictiondisk`; with `fake_delay` [s], that of tests/fake_cli.py:
    the same commands on the fake simulate (tests/fake_simulate.py), each run that long."""
    import sys

    if fake_delay is None:
        return [sys.executable, "-m", "frictiondisk.cli"]
    return [sys.executable, str(FAKE_CLI)]


def start_campaign_until(spec, out, points: int = 2, until=None, fake_delay=None):
    """`frictiondisk run spec -o out` as a subprocess (stdout and stderr piped, text),
    returned once `points` points are done (or once `until()`, if given, is true); fails
    if it ended before. spec: one campaign file, or a list of them (a folder of campaigns).
    fake_delay: run on the fake simulate, each run taking that many seconds (cli_command)."""
    import os
    import subprocess

    specs = [str(path) for path in spec] if isinstance(spec, list | tuple) else [str(spec)]
    env = dict(os.environ, FAKE_SIMULATE_DELAY_S=str(fake_delay or 0.0))
    proc = subprocess.Popen(
        [*cli_command(fake_delay), "run", *specs, "-o", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    ready = until or (lambda: points_done(out) >= points)
    wait_until(ready, proc, "the state the signal needs")
    assert proc.poll() is None, "the campaign finished before the signal"
    return proc


def outside_the_figure(fig) -> list[str]:
    """The drawn texts (legend entries, labels, notes, captions) whose extent, after a
    draw, reaches past an edge of the figure."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    width, height = canvas.get_width_height()
    # tick labels: the tight box below holds those drawn (a tick outside the view is not)
    ticks = {
        id(label)
        for ax in fig.get_axes()
        for axis in (ax.xaxis, ax.yaxis)
        for tick in axis.get_major_ticks() + axis.get_minor_ticks()
        for label in (tick.label1, tick.label2)
    }
    bad = []
    for text in fig.findobj(Text):
        if id(text) in ticks or not text.get_visible() or not text.get_text().strip():
            continue
        box = text.get_window_extent(renderer)
        if box.x0 < -0.5 or box.y0 < -0.5 or box.x1 > width + 0.5 or box.y1 > height + 0.5:
            bad.append(f"{text.get_text()[:50]!r} at {box.bounds}")
    tight = fig.get_tightbbox(renderer)  # every drawn artist, ticks only if drawn
    inches = fig.bbox_inches
    if tight.x0 < -0.01 or tight.y0 < -0.01 or tight.x1 > inches.x1 + 0.01:
        bad.append(f"drawn content {tight.bounds} beyond the figure {inches.bounds}")
    if tight.y1 > inches.y1 + 0.01:
        bad.append(f"drawn content {tight.bounds} beyond the figure {inches.bounds}")
    return bad


def pytest_collection_modifyitems(config, items) -> None:
    """The slow tests (marker `slow`, over ~10 s each) first, in their order: with two
    workers (make test) a long test that starts last keeps one worker busy while the other
    has nothing left to take."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)
