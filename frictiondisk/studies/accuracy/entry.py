"""What `frictiondisk accuracy` (cli/accuracy.py) asks of the accuracy study: a study of a
campaign whose task bisects mu* at each point (`mu_star_grid`, read through the campaign's
task entry, so no task is named), run on frictiondisk.engine.local."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any


class AccuracyEntry:
    """What `frictiondisk accuracy` asks of the accuracy study."""

    name = "accuracy"

    def applies_to(self, campaign: Any) -> list[str]:
        """[] if the study can bisect the campaign's mu*, else why not."""
        if campaign.entry.mu_star_grid:
            return []
        kind = campaign.kind
        return [
            f"{kind}: the accuracy study needs a find_jump task (it bisects mu*); "
            f"this campaign has a {kind} task"
        ]

    def option_problems(
        self, campaign: Any, point: int, tol: float, knobs: Sequence[str]
    ) -> list[str]:
        """One line per bad option: the point, the tol, the knobs."""
        from frictiondisk.studies.accuracy.ladder import check_knobs

        problems = []
        n_points = math.prod(campaign.shape)
        if not 0 <= point < n_points:
            problems.append(
                f"--point: {point} is out of range: the campaign has {n_points} points "
                f"(0 ... {n_points - 1})"
            )
        width = campaign.task.bracket[1] - campaign.task.bracket[0]
        if not (math.isfinite(tol) and 0.0 < tol < width):
            problems.append(
                f"--tol: {tol!r} is out of range: must be > 0 and < {width:g} "
                "(the width of find_jump.bracket)"
            )
        return problems + check_knobs(knobs, campaign.base.scene)

    def study(self, campaign: Any, point: int, knobs: Sequence[str], tol: float, quick: bool):
        """The study (an AccuracyStudy: its searches and its Dataset)."""
        from frictiondisk.studies.accuracy.study import AccuracyStudy

        return AccuracyStudy(campaign, point, knobs, tol, quick)

    def figure(self, ds: Any) -> Any:
        """The work-precision figure of accuracy.nc."""
        from frictiondisk.studies.accuracy.figure import work_precision_figure

        return work_precision_figure(ds)

    def table(self, ds: Any) -> str:
        """One line per row of accuracy.nc."""
        from frictiondisk.studies.accuracy.table import summary_table

        return summary_table(ds)
