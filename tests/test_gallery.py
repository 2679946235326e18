"""The figures the repository ships (figures/*.png): each drawn by a generator of `make
gallery`, each from this code's numerics (read from the footer kept in the PNG's metadata,
so no pixels are read and nothing is simulated)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from matplotlib.figure import Figure
from PIL import Image

from frictiondisk.cli.gallery import GALLERY, outputs, seed
from frictiondisk.figures.footer import (
    FOOTER_KEY,
    add_footer,
    code_footer,
    footer_text,
    numerics_versions,
)
from frictiondisk.figures.plotting import save_figure
from frictiondisk.version import NUMERICS_VERSION, UNCHANGED_SINCE

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = sorted((ROOT / "figures").glob("*.png"))


def test_every_shipped_png_is_drawn_by_a_gallery_generator():
    written = outputs()
    assert len(written) == len(set(written)), "two generators write the same PNG"
    present = {path.name for path in SHIPPED}
    assert set(written) - present == set(), "the gallery writes PNGs figures/ lacks"
    assert present - set(written) == set(), "PNGs under figures/ that no generator draws"


def test_the_gallery_names_its_generators_once():
    names = [generator.name for generator in GALLERY]
    assert len(names) == len(set(names))


def numerics_problem(path: Path) -> str | None:
    """Why the PNG at `path` is not from this code's numerics, or None if it is: drawn at
    NUMERICS_VERSION, or at a version since which only scenes that no figure draws changed
    (UNCHANGED_SINCE, checked by the test below)."""
    footer = Image.open(path).text.get(FOOTER_KEY, "")
    if not footer:
        return f"{path.name} keeps no footer in its metadata: draw it with `make gallery`"
    versions = numerics_versions(footer)
    if not versions:
        return f"{path.name}'s footer names no numerics version: {footer!r}"
    if not set(versions) <= set(range(UNCHANGED_SINCE, NUMERICS_VERSION + 1)):
        return (
            f"{path.name} was drawn from numerics {sorted(set(versions))}, the code is at "
            f"{NUMERICS_VERSION} (its runs unchanged since {UNCHANGED_SINCE}): draw it "
            "again (`make gallery`)"
        )
    return None


def _newest_key_version(names) -> int:
    """The newest numerics version that changed a run of the campaigns `names`
    (store/journal_entry.key_version of their scenes; a disk also braked, as an axis may
    brake it); NUMERICS_VERSION where no campaign is named (the generator runs its own)."""
    import yaml

    from frictiondisk.model.scene import scene_from_dict
    from frictiondisk.store.journal_entry import key_version

    if not names:
        return NUMERICS_VERSION
    newest = UNCHANGED_SINCE
    for name in names:
        data = yaml.safe_load((ROOT / "campaigns" / f"{name}.yaml").read_text())
        scene = {key: data[key] for key in ("scene", "params", "contact") if key in data}
        variants = [scene]
        if scene.get("scene") == "disk":  # any brake along an axis: the braked scene too
            variants.append({**scene, "params": {**scene.get("params", {}), "beta_b": 0.005}})
        for variant in variants:
            newest = max(newest, key_version(scene_from_dict(variant).canonical()))
    return newest


@pytest.mark.parametrize("generator", GALLERY, ids=lambda generator: generator.name)
def test_no_figure_is_older_than_the_runs_it_draws(generator):
    """A figure drawn at numerics v is current only if no run it draws changed after v."""
    newest = _newest_key_version(generator.campaigns)
    for name in generator.outputs:
        footer = Image.open(ROOT / "figures" / name).text.get(FOOTER_KEY, "")
        versions = numerics_versions(footer)
        assert versions and min(versions) >= newest, (
            f"{name} was drawn from numerics {sorted(set(versions))}, but its runs changed "
            f"at {newest}: draw it again (`make gallery`)"
        )


@pytest.mark.parametrize("path", SHIPPED, ids=lambda path: path.name)
def test_a_shipped_figure_names_this_code_s_numerics_version(path):
    assert numerics_problem(path) is None, numerics_problem(path)


@pytest.mark.parametrize("footer", ["", "no version here", "numerics 7, numba"])
def test_the_check_flags_a_figure_of_other_numerics(tmp_path, footer):
    fig = Figure(figsize=(4.0, 3.0), layout="constrained")
    fig.add_subplot()
    text = footer.replace("numerics 7", f"numerics {UNCHANGED_SINCE - 1}")
    if text:
        add_footer(fig, text)
    assert numerics_problem(save_figure(fig, tmp_path / "old.png")) is not None


def test_save_figure_keeps_the_footer_in_the_png(tmp_path):
    fig = Figure(figsize=(4.0, 3.0), layout="constrained")
    fig.add_subplot().plot([0, 1], [0, 1])
    footer = code_footer("a test")
    add_footer(fig, footer)
    drawn = footer_text(fig)
    assert drawn.replace("\n", " | ") == footer  # wrapped to the width at its separators only
    text = Image.open(save_figure(fig, tmp_path / "f.png")).text[FOOTER_KEY]
    assert text == drawn
    assert numerics_versions(text) == [NUMERICS_VERSION]


def test_the_footer_of_a_figure_with_an_empty_log_axis_is_found(tmp_path):
    fig = Figure(figsize=(4.0, 3.0), layout="constrained")
    fig.add_subplot().set_yscale("log")  # no data: its ticks cannot be computed
    add_footer(fig, "a log axis | numerics 7")
    assert footer_text(fig) == "a log axis | numerics 7"


def test_a_figure_without_a_footer_keeps_none(tmp_path):
    fig = Figure(figsize=(2.0, 2.0))
    fig.add_subplot()
    assert footer_text(fig) is None
    assert FOOTER_KEY not in Image.open(save_figure(fig, tmp_path / "g.png")).text


def test_numerics_versions_reads_the_kernel_version_text():
    assert numerics_versions("frictiondisk 0.1.0 | numerics 12, numba 0.1") == [12]
    assert numerics_versions("numerics rodas4, rtol 1e-06 | numerics 7, numba") == [7]


def test_seed_copies_only_complete_run_folders_that_out_lacks(tmp_path):
    runs, out = tmp_path / "runs", tmp_path / "out"
    for name, state in (("done", "complete"), ("half", "running"), ("mine", "complete")):
        (runs / name).mkdir(parents=True)
        (runs / name / "status.json").write_text(json.dumps({"state": state}))
        (runs / name / "lock").write_text("")
    (out / "mine").mkdir(parents=True)  # resumed as it is, never overwritten
    seed(("done", "half", "mine", "absent"), runs, out)
    assert (out / "done" / "status.json").is_file()
    assert not (out / "done" / "lock").exists()  # the writer's lock stays with its folder
    assert not (out / "half").exists() and not (out / "absent").exists()
    assert not (out / "mine" / "status.json").exists()
