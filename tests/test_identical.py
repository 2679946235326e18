"""studies/identical.py: the comparison that proves a refactor changes no result must see a
difference where there is one, whether it is given two roots of campaign folders or two
campaign folders, and must never call "identical" what it did not compare."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from frictiondisk.studies.identical import compare


def _campaign(folder: Path, mu_star: float, wall_s: float) -> Path:
    folder.mkdir(parents=True)
    xr.Dataset(
        {"mu_star": ("point", np.array([mu_star, 0.2])), "wall_s": ("point", [wall_s, 1.0])},
        attrs={"title": "test", "wall_s": wall_s},
    ).to_netcdf(folder / "results.nc")
    return folder


def test_a_changed_value_is_found_in_a_campaign_folder_and_under_a_root(tmp_path):
    before = _campaign(tmp_path / "a" / "line", 0.1, 1.0)
    after = _campaign(tmp_path / "b" / "line", 0.1 + 1e-12, 2.0)
    for pair in ((before, after), (before.parent, after.parent)):
        lines = compare(*pair, allow=set())
        assert len(lines) == 1 and "mu_star" in lines[0], lines


def test_timings_alone_are_identical(tmp_path):
    before = _campaign(tmp_path / "a" / "line", 0.1, 1.0)
    after = _campaign(tmp_path / "b" / "line", 0.1, 5.0)
    assert compare(before, after, allow=set()) == []


def test_nothing_to_compare_is_an_error_not_identical(tmp_path):
    (tmp_path / "empty" / "journal").mkdir(parents=True)
    with pytest.raises(SystemExit, match="no netCDF file"):
        compare(tmp_path / "empty", tmp_path, allow=set())
