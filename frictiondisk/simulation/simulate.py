"""The one door from Python into a run: `simulate`, and the registry of integration methods.

METHODS maps each numerics.method to the function that runs it (scipy `_ivp`'s METHODS
table is the model); each takes (config, record, dt_out, *, dense_lu, verdict) and
returns a labelled SimulationResult. A new method is a module and one line here. The
entries are "module:function" paths, imported on first use, so a process that runs only
the numba kernel never imports scipy's integrators.
"""

from __future__ import annotations

import functools
import importlib

from frictiondisk.simulation.result import SimulationResult
from frictiondisk.verdict.params import VerdictParams

METHODS = {
    "rodas4": "frictiondisk.simulation.rodas_method:simulate_rodas",
    "rodas4-fixed": "frictiondisk.simulation.rodas_method:simulate_rodas",
    "rodas5": "frictiondisk.simulation.rodas_method:simulate_rodas",
    "scipy-radau": "frictiondisk.simulation.radau:simulate_radau",
    "coulomb": "frictiondisk.simulation.coulomb:simulate_coulomb",
}


# the default thresholds, made once (a frozen record; its numba record is cached by value)
DEFAULT_VERDICT = VerdictParams()


@functools.cache
def method_function(name: str):
    """The function that runs numerics.method `name` (METHODS), imported once."""
    module, function = METHODS[name].split(":")
    return getattr(importlib.import_module(module), function)


def simulate(
    config,
    record: bool = False,
    dt_out: float = 0.0,
    *,
    dense_lu: bool = False,
    verdict: VerdictParams | None = None,
) -> SimulationResult:
    """Run one scene and label its long-term motion.

    record: keep the trajectory (dense-output samples every dt_out seconds plus every
    switching instant; dt_out = 0 records every step). dense_lu: factor the Rosenbrock
    stage matrix densely, O(N^3) per step, instead of by its arrow structure, O(N)
    (kernel/linalg.py); for comparisons (benchmarks/bench_layouts.py) only. verdict: the
    thresholds of what a run is (verdict/params.py); None: the defaults, with which every
    result and journal key is as it was.
    """
    run = method_function(config.numerics.method)
    verdict = DEFAULT_VERDICT if verdict is None else verdict
    return run(config, record, dt_out, dense_lu=dense_lu, verdict=verdict)
