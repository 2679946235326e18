"""numerics.preset: fast | default | reference (issue 5, item 2)."""

import pytest

from frictiondisk.model.scene import (
    NUMERICS_PRESETS,
    ConfigError,
    Numerics,
    load_scene,
    scene_from_dict,
)
from frictiondisk.store.journal_entry import run_key
from frictiondisk.tasks.campaign import campaign_from_text

PRESET_KEYS = ("method", "rtol", "atol", "dt", "h_max")


def _numerics(**numerics):
    return scene_from_dict({"scene": "pin", "numerics": numerics})


def test_default_preset_is_the_field_defaults_and_changes_no_key():
    for key in PRESET_KEYS:
        assert NUMERICS_PRESETS["default"][key] == Numerics.model_fields[key].default, key
    plain, named = _numerics(), _numerics(preset="default")
    assert named.canonical() == plain.canonical()
    assert named.content_hash() == plain.content_hash()
    assert run_key(named) == run_key(plain)
    assert "preset" not in plain.canonical()["numerics"]


@pytest.mark.parametrize("name", ["fast", "reference"])
def test_preset_resolves_to_concrete_values(name):
    config = _numerics(preset=name)
    for key in PRESET_KEYS:
        assert getattr(config.numerics, key) == NUMERICS_PRESETS[name][key], key
    explicit = _numerics(**NUMERICS_PRESETS[name])
    # the same numerics give the same key, however they were written
    assert config.canonical() == explicit.canonical()
    assert run_key(config) == run_key(explicit)
    assert config.content_hash() != _numerics().content_hash()


def test_presets_order_by_tolerance():
    rtol = [NUMERICS_PRESETS[name]["rtol"] for name in ("fast", "default", "reference")]
    assert rtol == sorted(rtol, reverse=True) and len(set(rtol)) == 3


def test_explicit_keys_win(tmp_path):
    config = _numerics(preset="fast", rtol=1.0e-5)
    assert config.numerics.rtol == 1.0e-5
    assert config.numerics.atol == NUMERICS_PRESETS["fast"]["atol"]
    path = tmp_path / "scene.yaml"
    path.write_text("scene: pin\nnumerics:\n  rtol: 1.0e-7\n")
    config = load_scene(path, ["numerics.preset=reference"])
    assert config.numerics.rtol == 1.0e-7  # the file's explicit value
    assert config.numerics.atol == NUMERICS_PRESETS["reference"]["atol"]
    config = load_scene(path, ["numerics.preset=reference", "numerics.rtol=1e-8"])
    assert config.numerics.rtol == 1.0e-8


def test_with_overrides_switches_preset():
    base = _numerics(rtol=1.0e-7)
    fast = base.with_overrides({"numerics.preset": "fast"})
    for key in PRESET_KEYS:
        assert getattr(fast.numerics, key) == NUMERICS_PRESETS["fast"][key], key
    assert fast.numerics.preset == "fast"
    mixed = base.with_overrides({"numerics.preset": "fast", "numerics.h_max": 0.05})
    assert mixed.numerics.h_max == 0.05 and mixed.numerics.rtol == 1.0e-4
    # other overrides keep the resolved values
    assert fast.with_overrides({"params.mu": 0.2}).numerics == fast.numerics


def test_canonical_round_trip(tmp_path):
    config = _numerics(preset="fast", t_decide=10.0)
    path = tmp_path / "canonical.yaml"
    path.write_text(config.to_yaml())
    again = load_scene(path)
    assert again.content_hash() == config.content_hash()
    assert again.numerics.rtol == NUMERICS_PRESETS["fast"]["rtol"]


def test_campaign_base_and_points_use_the_preset():
    text = (
        "name: p\nscene: pin\nnumerics: {preset: reference}\n"
        "find_jump:\n  bracket: [0.05, 0.3]\n  along: {params.x_ms: [0.05, 0.1]}\n"
    )
    campaign = campaign_from_text(text)
    assert campaign.base.numerics.rtol == NUMERICS_PRESETS["reference"]["rtol"]
    assert all(p.config.numerics.atol == 1.0e-12 for p in campaign.points())
    assert "preset" not in campaign.canonical()["numerics"]


@pytest.mark.parametrize(
    "value, shown",
    [("turbo", "'turbo'"), (None, "null"), (3, "3"), (["fast"], "['fast']")],
)
def test_bad_preset_names_the_field(value, shown):
    with pytest.raises(ConfigError) as info:
        _numerics(preset=value)
    assert info.value.problems == [
        f"numerics.preset: {shown} is not allowed: must be one of 'fast', 'default', 'reference'"
    ]


def test_misspelt_preset_is_suggested():
    with pytest.raises(ConfigError) as info:
        _numerics(prest="fast")
    (problem,) = info.value.problems
    assert problem.startswith("numerics.prest: unknown key; allowed keys under numerics:")
    assert problem.endswith("preset (did you mean 'preset'?)")
