"""Small frictions a user meets: what a converge-mode campaign prints about its horizon,
and the notebook of the motion atlas on the public API."""

from __future__ import annotations

import json
import re
from pathlib import Path

from frictiondisk.model.auto_numerics import for_campaign
from frictiondisk.model.scene import scene_from_dict

NOTEBOOK = Path(__file__).resolve().parents[1] / "notebooks" / "03_motion_atlas.ipynb"


def test_a_converge_mode_find_jump_names_t_max_not_t_decide():
    """Its runs end at t_max: the preflight line must not name t_decide, which bounds
    nothing there."""
    base = scene_from_dict({"scene": "pin", "numerics": {"mode": "converge", "t_max": 500.0}})
    line = for_campaign(base, {"params.x_ms": [0.1]}, 1e-3, {"mode": "converge"}).describe()
    assert "t_max 500 s" in line and "t_decide" not in line
    decide = scene_from_dict({"scene": "pin"})
    assert "t_decide" in for_campaign(decide, {"params.x_ms": [0.1]}, 1e-3, {}).describe()


def _code(path: Path) -> str:
    cells = json.loads(path.read_text())["cells"]
    return "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")


def test_the_atlas_notebook_uses_only_the_public_api():
    """Imports from frictiondisk name only frictiondisk/__init__.py's __all__."""
    import frictiondisk

    code = _code(NOTEBOOK)
    assert not re.search(r"\bfrictiondisk\.\w", code), "a sub-package of frictiondisk imported"
    names = re.findall(r"from frictiondisk import ([^\n#]+)", code)
    assert names, "the notebook imports nothing from frictiondisk"
    for name in (n.strip() for line in names for n in line.split(",")):
        assert name in frictiondisk.__all__, name


def test_the_atlas_notebook_counts_coexistence_only_between_named_motions():
    """A cell undetermined (or pending) from one start is no evidence of two motions."""
    code = _code(NOTEBOOK)
    assert '"undetermined"' in code and "differ = both &" in code
