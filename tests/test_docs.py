"""The documentation lives in the repository: docs/model.md, and `show-defaults`."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.model.scene import Params, load_scene, scene_from_dict

ROOT = Path(__file__).resolve().parents[1]


def test_model_document_names_every_scene_parameter():
    text = (ROOT / "docs" / "model.md").read_text()
    for section in ("## 3. Friction law", "## 5. Defaults", "## 6. Outcomes"):
        assert section in text
    missing = [key for key in Params.model_fields if f"`params.{key}`" not in text]
    assert not missing, f"docs/model.md section 5 lacks {missing}"
    for outcome in ("`stick`", "`creep`", "`stick_slip`", "`slide`", "`undetermined`"):
        assert outcome in text


def test_nothing_points_outside_the_repository():
    files = subprocess.run(
        ["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=False
    ).stdout.split()
    if not files:
        pytest.skip("not a git checkout")
    bad = []
    for name in files:
        path = ROOT / name
        if (
            path.suffix not in (".py", ".md", ".yaml", ".ipynb", ".toml", ".txt", "")
            or not path.is_file()
        ):
            continue
        text = path.read_text(errors="replace")
        if "shared/MODEL" in text or "MODEL.md" in text or "../shared" in text:
            bad.append(name)
    bad = [b for b in bad if b != "tests/test_docs.py"]
    assert not bad, f"these files point outside the repository: {bad}"


@pytest.mark.parametrize("scene", ["pin", "disk"])
def test_show_defaults_prints_a_loadable_resolved_scene(scene, tmp_path):
    result = CliRunner().invoke(main, ["show-defaults", "--scene", scene])
    assert result.exit_code == 0, result.output
    data = yaml.safe_load(result.output)
    assert data["scene"] == scene
    assert data["contact"]["points"] == (1 if scene == "pin" else 12)
    assert data["params"]["omega_m"] == 1.1 and data["contact"]["stiffness"] == 2.53e5
    path = tmp_path / "defaults.yaml"
    path.write_text(result.output)
    assert load_scene(path).canonical() == scene_from_dict({"scene": scene}).canonical()


def test_show_defaults_rejects_an_unknown_scene():
    result = CliRunner().invoke(main, ["show-defaults", "--scene", "wheel"])
    assert result.exit_code == 2
    assert "--scene" in result.output


def test_show_defaults_is_wired_to_the_console_script():
    out = subprocess.run(
        [sys.executable, "-m", "frictiondisk.cli", "show-defaults"],
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
    ).stdout
    assert out.startswith("contact:")
