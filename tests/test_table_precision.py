"""Tables show the precision asked for (issue 48): every task that prints a mu prints it
to two decimals below its tol's place (tol 1e-8 -> 10), so the two ends of a bracket 1e-8
wide differ on screen; at tol 1e-4 the tables keep today's look. Coordinates print with
the digits that keep neighbouring grid values apart. Synthetic results, no simulation."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from frictiondisk.store.tables import distinct_spec, mu_decimals
from frictiondisk.studies.accuracy.table import summary_table
from frictiondisk.tasks.basin.table import summary_lines
from frictiondisk.tasks.find_jump.table import mu_star_table
from frictiondisk.tasks.scan.table import scan_table
from frictiondisk.tasks.trace.table import trace_lines

LO, HI = 0.0760340586, 0.0760340686  # a bracket 1e-8 wide (the pin line, x_ms 0.06)


@pytest.mark.parametrize(
    ("tol", "places"), [(1e-8, 10), (1e-4, 6), (1e-3, 6), (2e-5, 7), (1e-10, 12), (None, 6)]
)
def test_decimals_are_two_below_the_tols_place_and_never_fewer_than_today(tol, places):
    assert mu_decimals(tol) == places


def test_distinct_values_print_distinctly_and_a_coarse_grid_keeps_g():
    assert distinct_spec([0.05, 0.075, 0.1]) == ".6g"
    spec = distinct_spec([0.1, 0.1 + 1e-8, 0.1 + 2e-8])
    assert len({f"{v:{spec}}" for v in [0.1, 0.1 + 1e-8, 0.1 + 2e-8]}) == 3


def _jump_line(tol: float, lo: float, hi: float) -> xr.Dataset:
    return xr.Dataset(
        {
            "mu_star": ("x_ms", [0.5 * (lo + hi)]),
            "mu_lo": ("x_ms", [lo]),
            "mu_hi": ("x_ms", [hi]),
            "n_runs": ("x_ms", [12]),
            "status": ("x_ms", ["converged"]),
        },
        coords={"x_ms": ("x_ms", [0.06], {"units": "m"})},
        attrs={"task": "find_jump", "tol": tol},
    )


def test_find_jump_shows_both_ends_of_a_bracket_1e8_wide():
    row = mu_star_table(_jump_line(1e-8, LO, HI))[2].split()
    assert row[:3] == ["0.06", "0.0760340636", "[0.0760340586,"], row
    assert row[3] == "0.0760340686]"


def test_find_jump_at_tol_1e4_keeps_todays_six_decimals():
    row = mu_star_table(_jump_line(1e-4, 0.063268, 0.063368))[2].split()
    assert row[:4] == ["0.06", "0.063318", "[0.063268,", "0.063368]"], row


def _trace(tol: float, mus: list[float]) -> xr.Dataset:
    flags = {"flag_values": [0, 1], "flag_meanings": "certified uncertain"}
    return xr.Dataset(
        {
            "point_curve": ("point", [0] * len(mus)),
            "x_ms": ("point", [0.06 + 0.01 * k for k in range(len(mus))]),
            "mu_star": ("point", mus),
            "certification": ("point", [0] * len(mus), flags),
            "curve_first_point": ("curve", [0]),
            "curve_points": ("curve", [len(mus)]),
            "curve_closed": ("curve", [0]),
            "curve_first_end": ("curve", ["edge"]),
            "curve_last_end": ("curve", ["edge"]),
        },
        coords={"fold": ("fold", np.arange(0))},
        attrs={"trace_key_var": "x_ms", "trace_key": "params.x_ms", "tol": tol},
    )


def test_trace_shows_mu_to_its_tol():
    row = trace_lines(_trace(1e-8, [LO, HI]))[2]
    assert "0.0760340586 -> 0.0760340686" in row, row


def test_a_trace_fold_shows_its_mu_bracket_to_its_tol():
    window = {"flag_values": [0, 1], "flag_meanings": "sticking_window_closes gap_closes"}
    flags = {"flag_values": [0, 1], "flag_meanings": "certified uncertain"}
    fold = {
        "fold_curve": ("fold", [0]),
        "fold_x_ms": ("fold", [0.07]),
        "fold_x_ms_in": ("fold", [0.0699]),
        "fold_x_ms_out": ("fold", [0.0701]),
        "fold_mu": ("fold", [0.5 * (LO + HI)]),
        "fold_mu_lo": ("fold", [LO]),
        "fold_mu_hi": ("fold", [HI]),
        "fold_window": ("fold", [0], window),
        "fold_certification": ("fold", [0], flags),
        "fold_status": ("fold", ["converged"]),
        "fold_reason": ("fold", [""]),
    }
    fine = trace_lines(_trace(1e-8, [LO, HI]).drop_vars("fold").assign(fold))
    assert "0.0760340636 [0.0760340586, 0.0760340686]" in fine[-1], fine
    coarse = trace_lines(_trace(1e-4, [LO, HI]).drop_vars("fold").assign(fold))
    assert "0.076034064 [0.076034059, 0.076034069]" in coarse[-1], coarse  # today's .8g


def test_trace_at_tol_1e4_keeps_todays_six_significant_digits():
    row = trace_lines(_trace(1e-4, [0.0760341, 0.1267234]))[2]
    assert "0.0760341 -> 0.126723" in row, row


def test_scan_and_basin_coordinates_1e8_apart_differ_on_screen():
    mus = [LO, HI]
    scan = xr.Dataset(
        {
            "outcome": ("mu", ["stick_slip", "stick"]),
            "size": ("mu", [0.1, 0.0], {"units": "m"}),
            "a": ("mu", [0.04, np.nan], {"units": "m"}),
        },
        coords={"mu": ("mu", mus, {"units": "1"})},
        attrs={"task": "scan"},
    )
    rows = [line.split()[0] for line in scan_table(scan)[2:4]]
    assert rows[0] != rows[1], rows
    coarse = scan.assign_coords(mu=("mu", [0.05, 0.2], {"units": "1"}))
    assert [line.split()[0] for line in scan_table(coarse)[2:4]] == ["0.05", "0.2"]
    # a file without the measures has no columns for them (it once failed to print)
    assert scan_table(scan.drop_vars(["size", "a"]))[2].split()[1:] == ["stick_slip"]
    basin = xr.Dataset(
        {"n_samples": ("mu", [0, 0]), "status": ("mu", ["pending", "pending"])},
        coords={"mu": ("mu", mus), "outcome": ("outcome", ["stick"])},
        attrs={"basin_mode": "points"},
    )
    lines = summary_lines(basin)
    assert lines[0] != lines[1] and lines[0].startswith("mu = 0.0760340"), lines


def _accuracy(tol: float) -> xr.Dataset:
    rows = {
        "knob": ["rtol", "rtol"],
        "label": ["rtol 1e-6", "rtol 1e-10"],
        "is_reference": [False, True],
        "error": [1e-8, 0.0],
        "mu_star": [LO, HI],
        "n_steps": [100, 1000],
        "wall_s": [0.1, 1.0],
        "status": ["converged", "converged"],
        "reason": ["", ""],
    }
    return xr.Dataset({k: ("setting", v) for k, v in rows.items()}, attrs={"tol": tol})


def test_accuracy_shows_mu_to_two_decimals_below_its_tol():
    lines = summary_table(_accuracy(1e-10)).splitlines()
    assert "0.076034058600" in lines[1] and "0.076034068600" in lines[2], lines
    today = summary_table(_accuracy(1e-8)).splitlines()  # 10 decimals, as before
    assert "0.0760340586 " in today[1], today
