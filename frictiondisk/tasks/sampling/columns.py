"""The columns of runs.nc every task with sampled starts shares (basin, map): each run's
point, its index there, mu, the columns of every campaign's runs.nc, and the value of each
sampled initial-state key; and the attribute that records the sampled keys."""

from __future__ import annotations

from typing import Any

import numpy as np

from frictiondisk.model.yamlio import dump_yaml
from frictiondisk.store.campaign_datasets import key_attrs, run_columns
from frictiondisk.tasks.sampling.draws import sample_values
from frictiondisk.tasks.sampling.runs import SampleRequest


def sample_yaml(task) -> str:
    """The task's `sample` mapping as YAML (the `sample_yaml` attribute)."""
    return dump_yaml({k: d.canonical() for k, d in task.sample.items()})


def sampled_run_columns(
    campaign, points, rows, key_of, point_text: str, sample_text: str
) -> dict[str, Any]:
    """runs.nc's variables over `run` for `rows` ((point, sample index, result) each):
    `point` and `sample` (their long names given), mu, run_columns, and one column per
    sampled key (named by its last part)."""
    data_vars: dict[str, Any] = {
        "point": ("run", np.asarray([r[0] for r in rows], np.int64), {"long_name": point_text}),
        "sample": ("run", np.asarray([r[1] for r in rows], np.int64), {"long_name": sample_text}),
        "mu": (
            "run",
            np.asarray([points[r[0]].config.params.mu for r in rows], float),
            {"units": "1", "long_name": "mu"},
        ),
    }
    keys = [key_of(i, SampleRequest(j)) for i, j, _ in rows]
    data_vars.update(
        run_columns(campaign, points, [r[0] for r in rows], [r[2] for r in rows], keys)
    )
    task = campaign.task
    blocks: dict[int, dict] = {}  # point -> its draw blocks
    samples = [
        sample_values(task, points[i].coords, j, blocks.setdefault(i, {})) for i, j, _ in rows
    ]
    for key in task.sample:
        values = [sample[key] for sample in samples]
        attrs = {**key_attrs(key), "long_name": "sampled " + key_attrs(key)["long_name"]}
        data_vars[key.split(".")[-1]] = ("run", np.asarray(values, float), attrs)
    return data_vars
