"""The methods rodas4, rodas4-fixed and rodas5: the scene packed into the step loop's
records, the numba step loop (simulation/loop.py), the energy diagnostic and the labelled
result."""

from __future__ import annotations

import time

from frictiondisk.kernel import energy as ken
from frictiondisk.model.limits import record_rows_limit
from frictiondisk.simulation.buffers import RunBuffers
from frictiondisk.simulation.pack import (
    initial_modes,
    initial_state,
    new_options,
    new_rules,
    pack_parameters,
    record_capacity,
)
from frictiondisk.simulation.result import SimulationResult, Trajectory
from frictiondisk.simulation.result_builder import build_result
from frictiondisk.verdict.horizon import horizon_of, revolution
from frictiondisk.verdict.params import VerdictParams


def simulate_rodas(
    config,
    record: bool = False,
    dt_out: float = 0.0,
    *,
    dense_lu: bool = False,
    verdict: VerdictParams | None = None,
) -> SimulationResult:
    """Run one scene with the numba kernel, RODAS4 (adaptive, or fixed steps of
    numerics.dt for rodas4-fixed) or RODAS5 (adaptive), and label it (arguments:
    simulation/simulate.py)."""
    verdict = verdict or VerdictParams()
    p, pts = pack_parameters(config)
    y0 = initial_state(config)
    modes = initial_modes(p, pts, y0)

    limit = record_rows_limit(y0.shape[0], pts.shape[0])
    span = horizon_of(config) + revolution(config.params.omega_m)
    cap = record_capacity(span, dt_out, limit) if record else 1
    options = new_options(config.numerics, record, dt_out, dense_lu)
    rules = new_rules(config)
    run = RunBuffers.allocate(
        y0, modes, cap, p, pts, thresholds=verdict, options=options, rules=rules
    )

    energy_0 = float(ken.stored_energy(p, pts, y0))
    wall0 = time.perf_counter()
    run.run()  # the loop integrates run.y in place: it holds the final state afterwards
    wall = time.perf_counter() - wall0
    energy = energy_balance(
        energy_0,
        float(ken.stored_energy(p, pts, run.y)),
        run.work_in,
        run.work_dissipated,
    )

    trajectory = None
    if record:
        nq = 3 if config.scene == "disk" else 2
        trajectory = Trajectory.from_states(*run.recorded_rows(), nq, run.truncated)
    return build_result(config, run, wall, trajectory, energy, verdict=verdict)


def energy_balance(
    energy_0: float, energy_end: float, work_in: float, work_diss: float
) -> dict[str, float]:
    """Energy diagnostic of a run (kernel/energy.py): `energy_in`, `energy_dissipated` [J]
    and the relative residual of  E(t_end) - E(0) = W_in - W_diss.

    The residual is divided by the largest of |W_in|, W_diss and |E(t_end) - E(0)|: the
    size of the terms being balanced. Starting from rest the stored energy can be 0, and
    on a limit cycle W_in and W_diss grow with the run while E stays bounded, so dividing
    by E would say nothing; the largest term makes it an error per joule put through the
    system, comparable across run lengths. It is 0 when no energy moves at all.
    """
    delta = energy_end - energy_0
    scale = max(abs(work_in), abs(work_diss), abs(delta))
    residual = (delta - work_in + work_diss) / scale if scale > 0.0 else 0.0
    return {
        "energy_in": work_in,
        "energy_dissipated": work_diss,
        "energy_residual": residual,
    }
