"""What the line figure of a find_jump campaign shows, read from results.nc and runs.nc
(no drawing): the points of the line (`JumpLine`), the further jumps of a prescan, the
runs shown and the mu range of the view (`ShownRuns`). figure_line.py draws them."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import xarray as xr

from frictiondisk.figures.shared import check_vars, padded
from frictiondisk.store.cf import flag_meanings
from frictiondisk.tasks.find_jump.figure_layers import failed_and_without

RUNS_VIEW = 2.0  # runs above this many times the largest bracket end are drawn at the top
RUN_VARS = ("point", "mu", "outcome")


def further_jumps(results: xr.Dataset, dim: str) -> dict[str, np.ndarray]:
    """The jumps of a prescanned find_jump line besides each point's primary one (the
    line): x, lo, hi and rising (bool) of each. Empty without a prescan."""
    empty = {key: np.empty(0) for key in ("x", "lo", "hi", "rising")}
    if "jump_mu_lo" not in results.variables:
        return empty
    lo = np.asarray(results["jump_mu_lo"].transpose(dim, "jump").values, dtype=float)
    hi = np.asarray(results["jump_mu_hi"].transpose(dim, "jump").values, dtype=float)
    rising = np.asarray(results["jump_rising"].transpose(dim, "jump").values) == 1
    x = np.broadcast_to(np.asarray(results[dim].values, dtype=float)[:, None], lo.shape)
    primary_lo = np.asarray(results["mu_lo"].values, dtype=float)[:, None]
    primary_hi = np.asarray(results["mu_hi"].values, dtype=float)[:, None]
    keep = np.isfinite(lo) & ~((lo == primary_lo) & (hi == primary_hi))
    return {"x": x[keep], "lo": lo[keep], "hi": hi[keep], "rising": rising[keep]}


def flagged(results: xr.Dataset, meaning: str) -> np.ndarray:
    """Where the `certification` flag of results.nc has `meaning` (all False without it)."""
    if "certification" not in results:
        return np.zeros(results["mu_star"].shape, bool)
    var = results["certification"]
    codes = [code for code, name in flag_meanings(var).items() if name == meaning]
    return np.isin(np.asarray(var.values), codes)


@dataclasses.dataclass(frozen=True)
class JumpLine:
    """The arrays of a find_jump line, in the Dataset's order; `order` sorts them by x."""

    dim: str
    x: np.ndarray
    mu_star: np.ndarray
    mu_lo: np.ndarray
    mu_hi: np.ndarray
    monotone: np.ndarray
    failed: np.ndarray  # status failed
    without: np.ndarray  # no jump on the point's grid (an answer)
    bracketed: np.ndarray  # both bracket ends finite
    ok: np.ndarray  # not failed, bracketed: on the line
    order: np.ndarray

    @classmethod
    def of(cls, results: xr.Dataset) -> JumpLine:
        (dim,) = results["mu_star"].dims
        x = np.asarray(results[dim].values, dtype=float)
        mu_lo = np.asarray(results["mu_lo"].values, dtype=float)
        mu_hi = np.asarray(results["mu_hi"].values, dtype=float)
        failed, without = failed_and_without(results)
        bracketed = np.isfinite(mu_lo) & np.isfinite(mu_hi)
        return cls(
            dim=dim,
            x=x,
            mu_star=np.asarray(results["mu_star"].values, dtype=float),
            mu_lo=mu_lo,
            mu_hi=mu_hi,
            monotone=np.asarray(results["monotone"].values).astype(int),
            failed=failed,
            without=without,
            bracketed=bracketed,
            ok=~failed & bracketed,
            order=np.argsort(x),
        )

    @property
    def on_line(self) -> np.ndarray:
        """Indices of the points on the line, sorted by x."""
        return self.order[self.ok[self.order]]


@dataclasses.dataclass(frozen=True)
class ShownRuns:
    """The runs of runs.nc shown (empty without --runs) and the mu range of the view."""

    x: np.ndarray
    mu: np.ndarray
    outcome: np.ndarray
    in_view: np.ndarray  # mu below the view's top (the rest are marked at the top)
    y_range: tuple[float, float]


def shown_runs(line: JumpLine, extra: dict[str, np.ndarray], runs: xr.Dataset | None) -> ShownRuns:
    """The runs to draw and the mu range shown: every bracket, and the runs up to RUNS_VIEW
    x the largest bracket end (a bracket widened towards the limits must not squash the
    line)."""
    b = line.bracketed
    ends = np.concatenate([line.mu_lo[b], line.mu_hi[b], extra["lo"], extra["hi"]])
    run_x = run_mu = run_outcome = np.empty(0)
    if runs is not None:
        check_vars(runs, RUN_VARS, "runs")
        # each run at its point's coordinate: a find_jump bisecting another key along mu
        # keeps the bisected values in runs.nc's `mu`, which then is not the coordinate
        run_x = line.x[np.asarray(runs["point"].values, dtype=int)]
        run_mu = np.asarray(runs["mu"].values, dtype=float)
        run_outcome = np.asarray(runs["outcome"].values).astype(str)
    cap = RUNS_VIEW * float(ends.max()) if ends.size else math.inf
    in_view = run_mu <= cap
    shown = np.concatenate([ends, run_mu[in_view]])
    shown = shown[np.isfinite(shown)]
    if shown.size:
        y_lo, y_hi = padded(float(shown.min()), float(shown.max()), 0.1)
        if shown.min() >= 0.0:
            y_lo = max(y_lo, 0.0)
    else:
        y_lo, y_hi = 0.0, 1.0
    return ShownRuns(run_x, run_mu, run_outcome, in_view, (y_lo, y_hi))
