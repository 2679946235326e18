"""What one setting found for one scene, read back from its find_jump campaign.

The campaign's results.nc holds the answer; the study also needs what the answer stands
on: every verdict it claims (`Found.claims`), which a dispute is settled against. Those
are the search's own decided values, so the search is rebuilt: a `JumpSearch` with the
campaign's settings, fed the runs of its runs.nc in the order it asks for them (the
engine's replay of a journal, from the campaign's own record of every run). The rebuilt
answer must be the one results.nc holds (`ReplayMismatch` otherwise).

Search internals this module reads (and no other module of the study):
frictiondisk.tasks.jump_search.jumps.JumpSearch (pending, feed, result, headline, known,
bisections[i].searches) and frictiondisk.tasks.jump_search.jump_result.NO_JUMP.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

from frictiondisk.studies.campaigns import results
from frictiondisk.tasks.jump_search.jump_result import NO_JUMP
from frictiondisk.tasks.jump_search.jumps import JumpSearch

CERTIFIED = ("certified", "recertified")


class ReplayMismatch(RuntimeError):
    """A campaign's search, rebuilt from its runs.nc, is not the one its results.nc holds."""


@dataclasses.dataclass(frozen=True)
class Found:
    """What one setting found for one scene."""

    status: str
    reason: str
    mu_star: float  # headline (NaN: none)
    mu_lo: float
    mu_hi: float
    n_jumps: int
    windows: tuple[tuple[float, float], ...]
    certification: str
    grid_share: float  # share of the grid below mu* with a decided verdict (NaN: no headline)
    resolution: float  # largest gap between decided mu below mu* (NaN: no headline)
    claims: tuple[tuple[float, bool], ...]  # every decided (mu, sticks) the answer stands on
    runs: int
    wall_s: float  # kernel wall time of every run [s]

    @property
    def certified(self) -> bool:
        return self.status in ("converged", NO_JUMP) and self.certification in CERTIFIED

    def to_json(self) -> dict[str, Any]:
        return dataclasses.asdict(self)

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Found:
        data = dict(data)
        data["windows"] = tuple(tuple(w) for w in data["windows"])
        data["claims"] = tuple(tuple(c) for c in data["claims"])
        return cls(**data)


def answer_claims(search: JumpSearch) -> tuple[tuple[float, bool], ...]:
    """(mu, sticks) that the search's answer stands on: its decided values at the point's
    numerics, except where certification moved a jump (those are superseded), and the ends
    of every final bracket at the level that certified it."""
    claims = dict(search.known())
    for bisection in search.bisections:
        res = bisection.result()
        if res.status != "converged" or res.certification == "vanished":
            continue
        base = bisection.searches[0].result()
        if len(bisection.searches) > 1 and base.status == "converged":
            lo, hi = min(base.mu_lo, res.mu_lo), max(base.mu_hi, res.mu_hi)
            claims = {mu: stick for mu, stick in claims.items() if not lo <= mu <= hi}
        claims[res.mu_lo] = not res.rising
        claims[res.mu_hi] = res.rising
    return tuple((float(mu), bool(stick)) for mu, stick in sorted(claims.items()))


def run_table(runs) -> dict[tuple[float, int, int], dict[str, Any]]:
    """(mu, retry level, certification level) -> the run's summary, from a runs.nc. Two
    requests that differ in mode only (a prescan value and a bisection run at the same mu)
    are the same scene, the same journal key and the same run."""
    skip = {"point", "mu", "level", "strict", "role", "mode", "key"}
    names = [name for name in runs.data_vars if name not in skip and runs[name].dims == ("run",)]
    columns = {name: runs[name].values for name in names}
    table: dict[tuple[float, int, int], dict[str, Any]] = {}
    for k in range(runs.sizes["run"]):
        key = (float(runs.mu.values[k]), int(runs.level.values[k]), int(runs.strict.values[k]))
        table[key] = {name: _plain(values[k]) for name, values in columns.items()}
    return table


def _plain(value: Any) -> Any:
    """A netCDF value as the journal's summary holds it (NaN: a measure the run lacks)."""
    if isinstance(value, bytes):
        return value.decode()
    if hasattr(value, "item"):
        value = value.item()
    if isinstance(value, float) and math.isnan(value):
        return None
    return value


def replay(campaign, runs) -> JumpSearch:
    """The campaign's search of its one point, fed from its runs.nc in the order it asks."""
    task = campaign.task
    prescan = task.prescan
    stride = prescan.stride
    if stride is None:
        from frictiondisk.tasks.jump_search.prescan import stride_of

        stride = stride_of(prescan, campaign.points()[0].config.numerics.stick_rule)
    search = JumpSearch(
        prescan.mu,
        task.tol,
        task.max_retries,
        prescan.mode,
        task.split,
        task.certify,
        task.root_finder,
        stride,
        prescan.persist,
    )
    table = run_table(runs)
    while not search.done and search.pending():
        request = search.pending()[0]
        key = (request.mu, request.level, request.strict)
        if key not in table:
            raise ReplayMismatch(f"{campaign.name}: the search asks for {request}, not in runs.nc")
        search.feed(request, table[key])
    return search


def read_found(folder: Path, campaign) -> Found:
    """What the find_jump campaign in `folder` (its one point) found."""
    runs = results(folder, "runs")
    search = replay(campaign, runs)
    result = search.result()
    stored = results(folder)
    same = (
        str(stored.status.values.ravel()[0]) == result.status
        and _same_float(stored.mu_lo.values.ravel()[0], result.mu_lo)
        and _same_float(stored.mu_hi.values.ravel()[0], result.mu_hi)
        and int(stored.n_runs.values.ravel()[0]) == len(result.runs)
    )
    if not same:
        raise ReplayMismatch(f"{folder}: the rebuilt search's answer differs from results.nc")
    head = search.headline()
    below = result.grid_below
    return Found(
        status=result.status,
        reason=result.reason,
        mu_star=head.mu_star if head is not None else math.nan,
        mu_lo=head.mu_lo if head is not None else math.nan,
        mu_hi=head.mu_hi if head is not None else math.nan,
        n_jumps=len(result.jumps),
        windows=tuple((float(w.lo), float(w.hi)) for w in result.windows),
        certification=result.certification,
        grid_share=below.share if below is not None else math.nan,
        resolution=below.resolution if below is not None else math.nan,
        claims=answer_claims(search),
        runs=len(result.runs),
        wall_s=float(sum(run.result.get("wall_s") or 0.0 for run in result.runs)),
    )


def _same_float(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or a == b
