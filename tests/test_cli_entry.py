"""The console script leaves without interpreter teardown (frictiondisk/cli/entry.py): its
exit codes and its output must still arrive whole through a pipe."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from frictiondisk.cli.run_and_exit import exit_code as _exit_code
from frictiondisk.version import __version__

ROOT = Path(__file__).resolve().parents[1]


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "frictiondisk.cli", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=300,
    )


@pytest.mark.parametrize(("code", "status"), [(None, 0), (0, 0), (2, 2), (143, 143), ("x", 1)])
def test_system_exit_codes_become_exit_statuses(code, status):
    assert _exit_code(code) == status


def test_version_and_success_exit_zero():
    done = _cli("--version")
    assert done.returncode == 0
    assert __version__ in done.stdout


def test_a_bad_file_exits_2_with_its_message(tmp_path):
    done = _cli("simulate", str(tmp_path / "missing.yaml"))
    assert done.returncode == 2
    assert "not found" in done.stderr


def test_a_json_summary_arrives_whole_through_a_pipe():
    done = _cli("simulate", "campaigns/demo_pin.yaml", "--json", "--set", "numerics.t_decide=2")
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)  # flushed before the process left
    assert summary["outcome"] in {"stick", "creep", "stick_slip", "slide", "undetermined"}
