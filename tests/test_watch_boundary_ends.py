"""studies/watch_boundary_ends.py: both ends of every certified bracket of a `between`
campaign watched again, each sorted confirmed, contradicted or open by the side it names."""

from __future__ import annotations

import dataclasses
import sys

from frictiondisk.engine.runner import run_campaign
from frictiondisk.simulation import simulate as simulate_module
from frictiondisk.studies import watch_boundary_ends
from frictiondisk.tasks.campaign import campaign_from_text

sys.path.insert(0, "tests")
from fake_simulate import install  # noqa: E402
from test_figure_labels import BETWEEN, RENAMED  # noqa: E402  (a two-motion campaign)


def _renamed(monkeypatch, names):
    fake = install(monkeypatch)

    def renamed(config, record=False, dt_out=0.0):
        result = fake(config, record, dt_out)
        return dataclasses.replace(result, outcome=names.get(result.outcome, result.outcome))

    monkeypatch.setattr(simulate_module, "simulate", renamed)


def test_every_end_of_a_true_boundary_is_confirmed(tmp_path, monkeypatch, capsys):
    _renamed(monkeypatch, RENAMED)
    run_campaign(campaign_from_text(BETWEEN), tmp_path, workers=1, progress=False)
    assert watch_boundary_ends.main([str(tmp_path), "--factor", "3"]) == 0
    out = capsys.readouterr().out
    assert "6 certified ends watched to 3 x the horizon: 6 confirmed, 0 contradicted, 0 open" in out


def test_an_end_that_names_the_other_side_is_contradicted(tmp_path, monkeypatch, capsys):
    _renamed(monkeypatch, RENAMED)
    run_campaign(campaign_from_text(BETWEEN), tmp_path, workers=1, progress=False)
    # watched longer, the boundary's sides swap: every end names the other side
    _renamed(monkeypatch, {"stick": "self_centring", "stick_slip": "slide_cycle"})
    assert watch_boundary_ends.main([str(tmp_path)]) == 1
    assert "0 confirmed, 6 contradicted, 0 open" in capsys.readouterr().out


def test_the_watch_runs_the_campaign_numerics_at_a_longer_horizon():
    point = campaign_from_text(BETWEEN).points()[0].config
    numerics = {"mode": "decide", "t_decide": 30.0, "rtol": 1e-6}
    config = watch_boundary_ends.watched_config(point, numerics, "params.mu", 0.125, 3.0)
    assert config.numerics.t_decide == 90.0 and config.numerics.rtol == 1e-6
    assert config.params.mu == 0.125
    converge = {"mode": "converge", "t_max": 100.0}
    config = watch_boundary_ends.watched_config(point, converge, "params.mu", 0.1, 3.0)
    assert config.numerics.t_max == 300.0


def test_uncertain_brackets_are_watched_only_when_asked():
    import xarray as xr

    results = xr.Dataset(
        {
            "certification": ("point", [1, 3, 0, 2]),
            "mu_lo": ("point", [0.1, 0.2, 0.3, 0.4]),
            "mu_hi": ("point", [0.11, 0.21, 0.31, 0.41]),
        }
    )
    assert [i for i, *_ in watch_boundary_ends.ends_of(results)] == [0, 3]
    assert [i for i, *_ in watch_boundary_ends.ends_of(results, uncertain=True)] == [0, 1, 3]
