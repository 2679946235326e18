"""The map's refinement (frictiondisk/tasks/map/cells.py): a boundary between motions is
resolved to the grid step as a dense map shows it, with fewer runs, whatever the order the
motions come back in; an undetermined cell is refined around."""

from __future__ import annotations

import itertools
import random

from frictiondisk.tasks.map.cells import CellRefinement


def motion_of(cell):
    """A plane with a curved boundary between two motions and a third in a corner."""
    i, j = cell
    if i > 25 and j > 25:
        return "modulated"
    return "stick" if (i - 8) ** 2 + 0.5 * (j - 12) ** 2 < 90 else "slide_cycle"


def refined_map(shape, strides, seed=None, motion=motion_of):
    cells = CellRefinement(shape, strides)
    rng = random.Random(seed)
    while cells.waiting:
        waiting = sorted(cells.waiting)
        if seed is not None:
            rng.shuffle(waiting)
        for cell in waiting:
            cells.settle(cell, motion(cell))
        cells.refine()
    found = {**cells.inferred(), **cells.motions}
    return found, len(cells.motions)


def test_the_refined_map_equals_the_dense_map_with_fewer_runs():
    shape = (33, 31)
    found, runs = refined_map(shape, (8, 6))
    dense = {c: motion_of(c) for c in itertools.product(*(range(n) for n in shape))}
    assert found == dense
    assert runs < 0.5 * len(dense)


def test_the_map_does_not_depend_on_the_order_motions_arrive_in():
    reference = refined_map((20, 17), (5, 4))
    for seed in range(3):
        assert refined_map((20, 17), (5, 4), seed) == reference


def test_an_undetermined_cell_is_refined_around_never_inferred_over():
    def motion(cell):
        return "undetermined" if cell == (8, 8) else "stick"

    cells = CellRefinement((9, 9), (8, 8))
    while cells.waiting:
        for cell in sorted(cells.waiting):
            cells.settle(cell, motion(cell))
        cells.refine()
    assert cells.motions[(8, 8)] == "undetermined"
    # the blocks around it were split to the grid step: its neighbours ran
    assert {(7, 7), (7, 8), (8, 7)} <= cells.motions.keys()
    assert set(cells.inferred().values()) == {"stick"}


def _map_problems(body: str) -> str:
    import pytest

    from frictiondisk.model.scene import ConfigError
    from frictiondisk.tasks.campaign import campaign_from_text

    with pytest.raises(ConfigError) as info:
        campaign_from_text(f"name: m\nscene: pin\nmap:\n{body}")
    return str(info.value)


def test_a_map_file_names_every_problem():
    text = _map_problems(
        "  over: {params.omega_m: [1.0, 1.5], params.bogus: [1]}\n  seed: 3\n  mode: fast\n"
    )
    assert "map.over.params.bogus" in text
    assert "map.seed: only used with map.sample" in text
    assert "map.mode" in text
    text = _map_problems(
        "  over: {params.omega_m: [1.0, 1.5], params.x0: [0.0, 0.1]}\n"
        "  sample: {params.x0: {uniform: [0.0, 0.1]}}\n"
    )
    assert "map.samples: missing" in text and "cannot also be sampled" in text


def test_a_sampled_map_draws_its_starts_as_a_basin_does():
    from frictiondisk.tasks.campaign import campaign_from_text
    from frictiondisk.tasks.map.planner import MapPlanner
    from frictiondisk.tasks.sampling.draws import sample_values

    campaign = campaign_from_text(
        "name: m\nscene: pin\nmap:\n  over: {params.omega_m: [1.0, 1.5]}\n"
        "  sample: {params.x0: {uniform: [0.0, 0.1]}}\n  samples: 3\n  seed: 5\n"
    )
    planner = MapPlanner(campaign)
    assert len(planner.requests()) == 2 * 3
    point = planner.points[1]
    drawn = sample_values(campaign.task, point.coords, 2)
    assert planner.config_for(1, planner.requests()[-1][1]).params.x0 == drawn["params.x0"]


# SimulationResult fields that are no measure of the motion: timing, integration bookkeeping
# and the energy balance's parts (runs.nc keeps its residual)
NOT_MEASURES = {"wall_s", "n_rejected", "energy_in", "energy_dissipated", "slip_total"}


def test_every_measure_a_run_reports_has_its_units_for_the_map():
    """The map writes, per cell, every measure of store/measures.py RUN_MEASURES (the one
    place their units live): a numeric field a verdict adds to SimulationResult appears in
    the map (and runs.nc) once it is listed there, with no change to the map."""
    import dataclasses

    from frictiondisk.simulation.result import SimulationResult
    from frictiondisk.store.measures import RUN_MEASURES

    numeric = {
        f.name
        for f in dataclasses.fields(SimulationResult)
        if f.type in ("float", "int", float, int)
    }
    missing = sorted(numeric - NOT_MEASURES - set(RUN_MEASURES))
    assert not missing, f"give {missing} units and a long name in store/measures.py RUN_MEASURES"
