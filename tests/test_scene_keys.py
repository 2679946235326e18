"""A scene holds only the keys it uses: a key the chosen scene does not use is refused,
naming the key and the scene, wherever a scene key can be named (scene file, `--set`,
a campaign's base scene, its varied, sampled and mapped keys), and `show-defaults`
lists only the scene's keys."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from frictiondisk.cli import main
from frictiondisk.model.scene import ConfigError, load_scene, scene_from_dict
from frictiondisk.tasks.campaign import campaign_from_dict, load_campaign
from frictiondisk.tasks.registry import TASKS

CAMPAIGNS = Path(__file__).resolve().parents[1] / "campaigns"

# the keys of a slave disk that a pin has no use for, with a value each would take
DISK_ONLY = {
    "params.J_s": 0.03,
    "params.beta_b": 0.01,
    "params.phidot0": 1.1,
    "contact.ring_radius": 0.08,
}
PIN_WORDS = "is not allowed for scene 'pin'"


def _nested(key: str, value) -> dict:
    section, name = key.split(".")
    return {section: {name: value}}


def _problems(call) -> list[str]:
    with pytest.raises(ConfigError) as info:
        call()
    return info.value.problems


def _line(found: list[str], start: str) -> str:
    lines = [line for line in found if line.startswith(start)]
    assert len(lines) == 1, (start, found)
    return lines[0]


@pytest.mark.parametrize("key", DISK_ONLY)
def test_a_disk_key_in_a_pin_scene_file_is_refused_naming_key_and_scene(tmp_path, key):
    value = DISK_ONLY[key]
    path = tmp_path / "pin.yaml"
    path.write_text(yaml.safe_dump({"scene": "pin", **_nested(key, value)}))
    found = _problems(lambda: load_scene(path))
    line = _line(found, f"{key}: ")
    assert line.startswith(f"{key}: {value} {PIN_WORDS}: "), line
    assert "scene: disk" in line  # what is allowed: remove it, or make it a disk
    assert len(found) == 1, found
    # the same key on a disk is a valid scene
    assert scene_from_dict({"scene": "disk", **_nested(key, value)}).scene == "disk"


@pytest.mark.parametrize("key", DISK_ONLY)
def test_a_disk_key_set_on_a_pin_is_refused_and_names_the_override(tmp_path, key):
    path = tmp_path / "pin.yaml"
    path.write_text("scene: pin\n")
    found = _problems(lambda: load_scene(path, [f"{key}={DISK_ONLY[key]}"]))
    line = _line(found, f"{key}: ")
    assert PIN_WORDS in line and f"(from --set {key}={DISK_ONLY[key]})" in line, line


def test_the_messages_of_a_pin_read_alike():
    """contact.points was refused before these keys were: one format for both."""
    found = _problems(
        lambda: scene_from_dict(
            {"scene": "pin", "params": {"beta_b": 0.01}, "contact": {"points": 12}}
        )
    )
    assert _line(found, "contact.points: 12 ").startswith(f"contact.points: 12 {PIN_WORDS}: ")
    assert _line(found, "params.beta_b: ").startswith(f"params.beta_b: 0.01 {PIN_WORDS}: ")


def test_other_problems_are_reported_next_to_an_unused_key():
    found = _problems(
        lambda: scene_from_dict({"scene": "pin", "params": {"beta_b": 0.01, "mu": -1.0}})
    )
    assert len(found) == 2, found
    _line(found, "params.beta_b: ")
    _line(found, "params.mu: -1.0 is out of range")


def test_a_ring_radius_is_refused_on_a_disk_whose_contacts_are_not_on_a_ring():
    contact = {"layout": "annulus", "inner_radius": 0.06, "outer_radius": 0.09}
    found = _problems(
        lambda: scene_from_dict({"scene": "disk", "contact": {**contact, "ring_radius": 0.05}})
    )
    assert found == ["contact.ring_radius: 0.05 is not allowed: only used by layout 'ring'"]


# --- campaigns ------------------------------------------------------------------------


def _campaign(task: str, spec: dict, scene: str = "pin", **base) -> dict:
    return {"name": "t", "scene": scene, **base, task: spec}


JUMP = {"bracket": [0.05, 0.3], "tol": 1.0e-2}
BASIN = {"sample": {"params.x0": {"uniform": [-0.05, 0.05]}}, "samples": 4}


@pytest.mark.parametrize("key", DISK_ONLY)
def test_a_disk_key_in_a_pin_campaign_s_base_scene_is_refused(key):
    data = _campaign("find_jump", {**JUMP, "along": {"params.x_ms": [0.1]}}, **_nested(key, 0.5))
    found = _problems(lambda: campaign_from_dict(data))
    assert PIN_WORDS in _line(found, f"{key}: ")


@pytest.mark.parametrize(
    ("task", "spec", "at"),
    [
        ("find_jump", {**JUMP, "along": {"params.beta_b": [0.0, 0.01]}}, "find_jump.along"),
        ("scan", {"mu": [0.1, 0.2], "along": {"params.J_s": [0.02, 0.03]}}, "scan.along"),
        ("basin", {**BASIN, "along": {"contact.ring_radius": [0.05, 0.06]}}, "basin.along"),
        (
            "basin",
            {"sample": {"params.phidot0": {"uniform": [0, 1]}}, "samples": 4},
            "basin.sample",
        ),
        ("basin", {"grid": {"params.phidot0": [0.0, 1.0]}}, "basin.grid"),
    ],
)
def test_a_disk_key_varied_sampled_or_mapped_on_a_pin_is_refused_once(task, spec, at):
    """The issue's example: `along: {params.beta_b: [0.0, 0.01]}` on a pin gave the same
    mu* at both points, exit 0. Refused at the key, once (not once per value)."""
    found = _problems(lambda: campaign_from_dict(_campaign(task, spec)))
    (key,) = [k for k in DISK_ONLY if f"{at}.{k}" in " ".join(found)]
    line = _line(found, f"{at}.{key}")
    assert re.match(rf"{re.escape(at)}\.{re.escape(key)}: not allowed for scene 'pin': ", line)
    # on a disk the same task is valid
    assert campaign_from_dict(_campaign(task, spec, scene="disk")).name == "t"


def test_the_cli_refuses_a_pin_campaign_along_a_disk_key_with_exit_2(tmp_path):
    spec = tmp_path / "c.yaml"
    spec.write_text(
        yaml.safe_dump(_campaign("find_jump", {**JUMP, "along": {"params.beta_b": [0.0, 0.01]}}))
    )
    result = CliRunner().invoke(main, ["run", str(spec), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    assert "find_jump.along.params.beta_b: not allowed for scene 'pin'" in result.output
    assert not (tmp_path / "out").exists()


def test_the_cli_refuses_a_disk_key_set_on_a_pin_with_exit_2(tmp_path):
    scene = tmp_path / "pin.yaml"
    scene.write_text("scene: pin\n")
    result = CliRunner().invoke(main, ["simulate", str(scene), "--set", "params.phidot0=1.1"])
    assert result.exit_code == 2, result.output
    assert f"params.phidot0: 1.1 {PIN_WORDS}" in result.output


# --- the pin's own keys -----------------------------------------------------------------


def test_show_defaults_of_a_pin_lists_only_the_pin_s_keys(tmp_path):
    out = CliRunner().invoke(main, ["show-defaults", "--scene", "pin"]).output
    shown = yaml.safe_load(out)
    for key in DISK_ONLY:
        section, name = key.split(".")
        assert name not in shown[section], key
    for name in ("inner_radius", "outer_radius", "positions", "weights"):
        assert name not in shown["contact"], name
    disk = yaml.safe_load(CliRunner().invoke(main, ["show-defaults", "--scene", "disk"]).output)
    assert {"J_s", "beta_b", "phidot0"} <= set(disk["params"])
    assert "ring_radius" in disk["contact"]


def test_a_pin_s_canonical_form_round_trips_without_the_disk_keys(tmp_path):
    pin = scene_from_dict({"scene": "pin", "params": {"mu": 0.2}})
    canonical = pin.canonical()
    assert not {"J_s", "beta_b", "phidot0"} & set(canonical["params"])
    assert "ring_radius" not in canonical["contact"]
    path = tmp_path / "again.yaml"
    path.write_text(pin.to_yaml())
    assert load_scene(path).content_hash() == pin.content_hash()
    # a varied point of a pin campaign is built without them too
    campaign = campaign_from_dict(_campaign("find_jump", {**JUMP, "along": {"params.x0": [0.01]}}))
    assert campaign.points()[0].config.canonical()["params"].keys() == canonical["params"].keys()


def _is_campaign(path: Path) -> bool:
    data = yaml.safe_load(path.read_text())
    return any(task in data for task in TASKS)


@pytest.mark.parametrize("path", sorted(CAMPAIGNS.glob("*.yaml")), ids=lambda p: p.name)
def test_every_shipped_file_sets_only_keys_its_scene_uses(path):
    if _is_campaign(path):
        assert load_campaign(path).name
    else:
        assert load_scene(path).scene
