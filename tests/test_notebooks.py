"""The notebooks in notebooks/ run top to bottom, so they never rot.

Each notebook is executed with nbclient in a fresh kernel, from the repository root, with
FRICTIONDISK_NOTEBOOK_FAST=1 (small, fast settings: 02_paper_figures then runs shrunken
copies of the campaigns in campaigns/ instead of reading out/figures).

The kernel is this test's own interpreter (`sys.executable`, i.e. the venv's python): the
test writes a throwaway kernel spec naming it into a temporary directory and starts the
kernel from there, so neither a `python3` kernel spec installed elsewhere (user or system
Jupyter directories) nor `ipykernel install` is needed.
"""

from __future__ import annotations

import json
import os
import re
import sys
from pathlib import Path

import nbformat
import pytest
from jupyter_client.kernelspec import KernelSpecManager
from jupyter_client.manager import AsyncKernelManager
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
KERNEL_NAME = "frictiondisk-test"
CELL_TIMEOUT = 300  # s


def _kernel_manager(tmp_path: Path) -> AsyncKernelManager:
    spec_dir = tmp_path / "kernels" / KERNEL_NAME
    spec_dir.mkdir(parents=True)
    spec = {
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": f"frictiondisk test ({sys.executable})",
        "language": "python",
    }
    (spec_dir / "kernel.json").write_text(json.dumps(spec))
    specs = KernelSpecManager(kernel_dirs=[str(tmp_path / "kernels")])
    return AsyncKernelManager(kernel_name=KERNEL_NAME, kernel_spec_manager=specs)


def run_notebook(name: str, tmp_path: Path) -> nbformat.NotebookNode:
    """Execute notebooks/`name` in FAST mode from the repository root; return it with outputs.
    A cell that raises fails the test (nbclient raises CellExecutionError)."""
    nb = nbformat.read(NOTEBOOKS / name, as_version=4)
    env = dict(os.environ, FRICTIONDISK_NOTEBOOK_FAST="1")
    env.pop("MPLBACKEND", None)  # the notebooks select the inline backend themselves
    client = NotebookClient(
        nb,
        km=_kernel_manager(tmp_path),
        timeout=CELL_TIMEOUT,
        allow_errors=False,
        resources={"metadata": {"path": str(ROOT)}},
    )
    client.execute(env=env)
    return nb


def _code_cells(nb):
    return [cell for cell in nb.cells if cell.cell_type == "code"]


def _images(nb) -> int:
    return sum(
        1
        for cell in _code_cells(nb)
        for output in cell.get("outputs", [])
        if "image/png" in output.get("data", {})
    )


def _text(cell) -> str:
    parts = []
    for output in cell.get("outputs", []):
        if output.get("output_type") == "stream":
            parts.append(output.get("text", ""))
        elif "text/plain" in output.get("data", {}):
            parts.append(output["data"]["text/plain"])
    return "".join(parts)


def _check_ran_cleanly(nb) -> None:
    for cell in _code_cells(nb):
        assert cell.execution_count is not None, f"cell did not run:\n{cell.source}"
        errors = [out for out in cell.get("outputs", []) if out.get("output_type") == "error"]
        assert not errors, f"cell raised {errors[0].get('ename')}:\n{cell.source}"
    assert _images(nb) >= 1, "the notebook drew no figure"


@pytest.mark.parametrize(
    "name", ["01_getting_started.ipynb", "02_paper_figures.ipynb", "03_motion_atlas.ipynb"]
)
def test_notebook_is_committed_without_outputs(name):
    nb = nbformat.read(NOTEBOOKS / name, as_version=4)
    nbformat.validate(nb)
    for cell in _code_cells(nb):
        assert cell.outputs == [] and cell.execution_count is None, (
            f"{name}: strip the outputs before committing (cell:\n{cell.source})"
        )


@pytest.mark.slow  # > 10 s on 2 shared cores (selected out by -m 'not slow')
def test_getting_started_runs(tmp_path):
    nb = run_notebook("01_getting_started.ipynb", tmp_path)
    _check_ran_cleanly(nb)
    oracle = [cell for cell in _code_cells(nb) if "oracle" in cell.metadata.get("tags", [])]
    assert len(oracle) == 1, "exactly one cell is tagged 'oracle'"
    assert "oracle check passed" in _text(oracle[0])
    assert _images(nb) >= 2  # the orbit and the bifurcation line


@pytest.mark.slow  # > 10 s on 2 shared cores (selected out by -m 'not slow')
def test_paper_figures_runs(tmp_path):
    nb = run_notebook("02_paper_figures.ipynb", tmp_path)
    _check_ran_cleanly(nb)
    summary = [cell for cell in _code_cells(nb) if "summary" in cell.metadata.get("tags", [])]
    assert len(summary) == 1, "exactly one cell is tagged 'summary'"
    text = _text(summary[0])
    # FAST mode always runs the demo campaigns: at least a jump line and a scan are drawn.
    assert "drawn: " in text and "demo_line" in text and "demo_scan" in text, text
    assert _images(nb) >= 2


@pytest.mark.slow  # > 10 s on 2 shared cores (selected out by -m 'not slow')
def test_motion_atlas_runs(tmp_path):
    nb = run_notebook("03_motion_atlas.ipynb", tmp_path)
    _check_ran_cleanly(nb)
    text = "".join(_text(cell) for cell in _code_cells(nb))
    # numbers are printed rounded: no float repr such as 0.13999999999999999
    assert not re.search(r"\d\.\d{12,}", text), text
    assert "two motions coexist" in text and "undetermined or slide from at least one start" in text
    summary = [cell for cell in _code_cells(nb) if "summary" in cell.metadata.get("tags", [])]
    assert len(summary) == 1, "exactly one cell is tagged 'summary'"
    text = _text(summary[0])
    assert "map_pin_omega_mu: start rest" in text and "map_pin_omega_mu_cycle: start given" in text
    assert _images(nb) >= 2  # the two maps
