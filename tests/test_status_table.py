"""What `status` and `run` print of a campaign's answer: the mu* table of a find_jump
(a failed point with its reason, never as a number that looks valid) and the outcome and
size per point of a scan."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.tasks.find_jump.table import mu_star_table
from frictiondisk.tasks.registry import TASKS
from frictiondisk.tasks.scan.table import scan_table

REASON = "prescan undetermined at mu = 0.065 after every retry"


def _line(x_ms, mu_lo, mu_hi, status, reason):
    mu_lo, mu_hi = np.asarray(mu_lo, float), np.asarray(mu_hi, float)
    return xr.Dataset(
        {
            "mu_star": ("x_ms", 0.5 * (mu_lo + mu_hi)),
            "mu_lo": ("x_ms", mu_lo),
            "mu_hi": ("x_ms", mu_hi),
            "n_runs": ("x_ms", [14] * len(x_ms)),
            "status": ("x_ms", status),
            "reason": ("x_ms", reason),
        },
        coords={"x_ms": ("x_ms", x_ms, {"units": "m"})},
        attrs={"task": "find_jump", "tol": 1e-4},
    )


def test_a_failed_point_shows_no_mu_star_and_says_why():
    """The issue's example: a failed point printed `0.072274 [0.072224, 0.072324] ...
    failed`, its reason only in results.nc."""
    ds = _line(
        [0.05, 0.06],
        [0.063200, 0.072224],
        [0.063300, 0.072324],
        ["converged", "failed"],
        ["bracket ok", REASON],
    )
    lines = mu_star_table(ds)
    good, bad = lines[2].split(), lines[3].split()
    assert good[:2] == ["0.05", "0.063250"]
    assert bad == ["0.06", "-", "-", "14", "failed"], lines
    assert "0.072" not in " ".join(lines[:4])  # no number that reads as a result
    assert f"  x_ms = 0.06: {REASON}" in lines, lines
    assert any(line.startswith("failed points") for line in lines), lines


def test_a_point_without_a_jump_is_an_answer_with_its_reason_not_a_failure():
    why = "no jump: no value from mu = 0.03 to 0.6 sticks; 58 of 58 grid values decided"
    ds = _line(
        [0.05, 0.06],
        [0.0632, np.nan],
        [0.0633, np.nan],
        ["converged", "no_jump"],
        ["bracket ok", why],
    )
    lines = mu_star_table(ds)
    assert lines[3].split() == ["0.06", "-", "-", "14", "no_jump"], lines
    assert any(line.startswith("points without a jump on their grid (1)") for line in lines)
    assert f"  x_ms = 0.06: {why}" in lines, lines
    assert not any(line.startswith("failed points") for line in lines), lines


def test_a_table_without_failures_lists_no_reasons():
    ds = _line([0.05], [0.0632], [0.0633], ["converged"], ["bracket ok"])
    lines = mu_star_table(ds)
    assert len(lines) == 3 and "bracket ok" not in " ".join(lines)


def test_a_scan_table_shows_outcome_and_size_per_point():
    ds = xr.Dataset(
        {
            "outcome": (("mu", "x0"), [["stick_slip", "stick"], ["undetermined", "stick"]]),
            "reason": (
                ("mu", "x0"),
                [["cycle converged", "stuck"], ["still settling at the horizon", "stuck"]],
            ),
            "size": (("mu", "x0"), [[0.2838, 0.1], [np.nan, 0.09]], {"units": "m"}),
            "a": (("mu", "x0"), [[0.04, np.nan], [np.nan, np.nan]], {"units": "m"}),
        },
        coords={
            "mu": ("mu", [0.12, 0.13], {"units": "1"}),
            "x0": ("x0", [0.0, 0.01], {"units": "m"}),
        },
        attrs={"task": "scan"},
    )
    lines = scan_table(ds)
    assert lines[0] == "outcome per point:"
    assert lines[1].split() == ["mu", "x0", "[m]", "outcome", "size", "[m]", "a", "[m]"]
    rows = [line.split() for line in lines[2:6]]
    assert rows[0] == ["0.12", "0", "stick_slip", "0.2838", "0.04"]
    assert rows[1] == ["0.12", "0.01", "stick", "0.1", "-"]
    assert rows[2] == ["0.13", "0", "undetermined", "-", "-"]
    assert "  mu = 0.13, x0 = 0.01" not in lines  # a stick needs no reason
    assert "  mu = 0.13, x0 = 0: still settling at the horizon" in lines, lines
    assert TASKS["find_jump"].run_lines(ds.assign_attrs(task="find_jump")) == []  # its own


FAILING = """\
name: fail_line
scene: pin
numerics: {t_decide: 20.0}
find_jump:
  bracket: [0.2, 0.3]
  limits: [0.15, 0.35]
  tol: 1.0e-2
  along: {params.x_ms: [0.1]}
"""
SCAN = """\
name: small_scan
scene: pin
numerics: {t_decide: 20.0}
scan: {mu: [0.05, 0.2], mode: decide}
"""
JUMP = """\
name: small_line
scene: pin
numerics: {t_decide: 20.0}
find_jump:
  bracket: [0.05, 0.3]
  tol: 1.0e-2
  along: {params.x_ms: [0.1]}
"""


@pytest.mark.parametrize(
    ("text", "run_says", "status_says"),
    [
        (FAILING, "stick down to the limit", "stick down to the limit"),
        (JUMP, "mu* per point", "mu* per point"),
        (SCAN, "outcome per point", "stick"),
    ],
)
def test_run_and_status_print_the_answer(tmp_path, text, run_says, status_says):
    spec = tmp_path / "c.yaml"
    spec.write_text(text)
    out = tmp_path / "out"
    ran = CliRunner().invoke(main, ["run", str(spec), "-o", str(out)])
    assert ran.exit_code == 0, ran.output
    assert run_says in ran.output, ran.output
    status = CliRunner().invoke(main, ["status", str(out)])
    assert status.exit_code == 0, status.output
    assert status_says in status.output, status.output
    if text is SCAN:  # one row per mu, with its outcome
        rows = [line.split() for line in status.output.splitlines() if line.startswith("  0.")]
        assert [row[0] for row in rows] == ["0.05", "0.2"], status.output
        assert rows[1][1] == "stick", status.output
