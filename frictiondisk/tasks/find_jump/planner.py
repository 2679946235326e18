"""Which runs a `find_jump` campaign needs next (pure Python; the planner contract is
frictiondisk.tasks.protocol.Planner).

A planner turns a campaign into requests `(point index, RunRequest)` and takes their
results back (`requests`, `feed`: the driver answers them from the journal), and hands
out the work the journal cannot answer as jobs (`jobs`, `complete`, `fail`: the driver
runs them on Dask). It does no I/O and knows nothing of Dask, and the results do not
depend on worker count or timing: every decision depends only on outcomes, never on the
order they arrive in.

Warm start (find_jump), along the last varied dimension ("a row"), coarse to fine: the
row's two ends start cold, then its midpoint, then the midpoints of the two halves, and so
on (`refinement`). A point starts once the two points that bound its interval are done
and fewer than `lanes` points of its row are in flight. Its bracket is predicted by
interpolation: linear between those two, quadratic with the end of the interval they
were cut from, half-width tol / 2, or 2 |quadratic - linear| where that is larger, so
that a point of a smooth line costs two runs before certification. A prediction that
misses widens x8, x64, ... up to the campaign bracket, and an undetermined run at a
prediction waits for the horizon ladder until nothing else can close the bracket
(jump_search/expanding.py). The campaign's first point starts alone: every other point
waits until it is done and corrects its friction reserves by the offset at the jump that
point shows, so that its probes aim at the jump and not at the reserve's zero
(jump_search/reserve_offset.py; an offset under tol is ignored). Which points a
prediction or an offset uses is fixed by the campaign, never by timing, so 1 and 2
workers give identical results.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from frictiondisk.tasks.find_jump.results import FindJumpResults
from frictiondisk.tasks.in_order import feed_in_order
from frictiondisk.tasks.jobs import Job, JobTable, RunScenes, RunSearch, Sizing, halves
from frictiondisk.tasks.jump_search.bisection import BisectionResult, RunRequest, cold_run_count
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.certify import CertifiedBisection
from frictiondisk.tasks.jump_search.expanding import PREDICTED, Expanding
from frictiondisk.tasks.jump_search.jumps import JumpSearch, JumpSearchResult, run_role
from frictiondisk.tasks.jump_search.prescan import stride_of
from frictiondisk.tasks.jump_search.requests import PointScenes, run_config
from frictiondisk.tasks.jump_search.reserve_offset import learned_offset
from frictiondisk.tasks.protocol import Planner

WARM_ERROR_FACTOR = 2.0  # half-width of a quadratic prediction: this x |quadratic - linear|
COLD = Expanding(defer=True)  # a cold point: its bracket is the user's, its probes predict


class JumpPlanner(Planner):
    """find_jump: one bisection per point, warm-started along lanes; with a prescan, one
    `JumpSearch` per point instead (every jump bisected; no warm start: the prescan
    fixes the runs).

    Work units are smaller than a point: every run a point can start now (a prescan, the
    rounds of its jumps, the k - 1 points of a multisection round) is handed out on its
    own, in batches across points; a point whose next step fits in one task (a single
    run, or as many short runs as a batch holds) is handed out whole, as a chain
    (jobs.RunSearch) that goes on for the task's time budget."""

    def __init__(self, campaign):
        self.campaign = campaign
        self.task = campaign.task
        self.points = campaign.points()
        self.shape = campaign.shape
        self.bisections: dict[int, CertifiedBisection | JumpSearch] = {}
        self.results: dict[int, BisectionResult | JumpSearchResult] = {}
        self.warm: dict[int, bool] = {}
        self.chained: set[int] = set()  # points whose search is out on a worker
        self.out: dict[int, set[RunRequest]] = {}  # point -> its runs out in batches
        # point -> results back from a batch that its search does not take yet
        self.arrived: dict[int, dict[RunRequest, dict[str, Any]]] = {}
        self._jobs = JobTable()  # job -> ("chain", i) | ("runs", units)
        self._canonicals: dict[tuple[int, RunRequest], dict] = {}  # the driver computed these
        row_order, self._tree = refinement(self.shape[-1])
        width = self.shape[-1]
        rows = len(self.points) // width
        self._start_order = [row * width + pos for pos in row_order for row in range(rows)]

    def remember_canonical(self, i: int, request: RunRequest, canonical: dict) -> None:
        """Keep a run's canonical scene the driver already built (saves ~1 ms a run)."""
        self._canonicals[(i, request)] = canonical

    def config_for(self, i: int, request: RunRequest):
        task = self.task
        return run_config(
            self.points[i].config, request, task.horizon_factor, task.certify, task.parameter_key
        )

    @property
    def done(self) -> bool:
        return len(self.results) == len(self.points)

    def requests(self) -> list[tuple[int, RunRequest]]:
        """Runs the started points need now and nobody is computing."""
        for i in self._start_order:
            if i not in self.bisections and self._ready(i):
                self._start(i)
        return [
            (i, req)
            for i, bis in sorted(self.bisections.items())
            if not bis.done and i not in self.chained
            for req in bis.pending()
            if req not in self.out.get(i, ()) and req not in self.arrived.get(i, {})
        ]

    def feed(self, i: int, request: RunRequest, result: dict[str, Any]) -> None:
        """Take a result, fed in the search's own order (tasks/in_order.py; a RunSearch
        runs them in that order); one the point no longer waits for is dropped."""
        bis = self.bisections[i]
        if bis.done or i in self.chained or request not in bis.pending():
            return
        feed_in_order(bis, self.arrived.setdefault(i, {}), request, result)
        if bis.done:
            self.results[i] = bis.result()
            del self.arrived[i]

    def jobs(self, sizing: Sizing | None = None) -> list[tuple[int, RunSearch | RunScenes]]:
        """(job, what to run) for the runs the journal could not answer: chains (RunSearch,
        which reads any later run the journal holds) and batches of independent runs
        (RunScenes), in point order."""
        sizing = sizing or Sizing(chain_s=float("inf"))
        limit = math.inf if sizing.max_jobs is None else sizing.max_jobs
        out: list[tuple[int, RunSearch | RunScenes]] = []
        pool: list[tuple[int, RunRequest]] = []
        self.requests()  # start the points that are ready
        steps = []  # (point, its pending runs, those not out yet)
        for i, bis in sorted(self.bisections.items()):
            if not bis.done and i not in self.chained:
                pending = bis.pending()
                busy = {*self.out.get(i, ()), *self.arrived.get(i, {})}
                steps.append((i, pending, [req for req in pending if req not in busy]))
        # With enough runs to keep every worker busy in full batches, a step of several
        # short runs goes whole (fewer tasks); otherwise its runs spread over idle workers.
        ready_runs = sum(len(ready) for _, _, ready in steps)
        saturated = ready_runs >= sizing.workers * sizing.batch_runs
        for i, pending, ready in steps:
            if len(out) >= limit:
                break
            fits = len(pending) == 1 or (saturated and len(pending) <= sizing.batch_runs)
            if sizing.chain_s is not None and ready and len(ready) == len(pending) and fits:
                self.chained.add(i)
                canonical = self.points[i].config.canonical()
                budget = None if math.isinf(sizing.chain_s) else sizing.chain_s
                scenes = PointScenes(
                    canonical, self.task.horizon_factor, self.task.certify, self.task.parameter_key
                )
                job = RunSearch(self.bisections[i], scenes, budget)
                out.append((self._jobs.add(("chain", i)), job))
            else:
                pool += [(i, req) for req in ready]
        size = max(1, min(sizing.batch_runs, -(-len(pool) // max(1, sizing.workers))))
        for start in range(0, len(pool), size):
            if len(out) >= limit:
                break
            units = pool[start : start + size]
            for i, req in units:
                self.out.setdefault(i, set()).add(req)
            configs = [
                self._canonicals.pop((i, req), None) or self.config_for(i, req).canonical()
                for i, req in units
            ]
            out.append((self._jobs.add(("runs", units)), RunScenes(tuple(configs))))
        return out

    def complete(self, job: int, value) -> list[tuple[int, RunRequest, dict[str, Any]]]:
        """Take a finished job back; returns the runs it made, for the journal."""
        kind, what = self._jobs.pop(job)
        if kind == "chain":
            bis, made = value
            self.chained.discard(what)
            self.bisections[what] = bis
            if bis.done:
                self.results[what] = bis.result()
            return [(what, request, result) for request, result in made]
        made = []
        for (i, request), result in zip(what, value, strict=True):
            self.out[i].discard(request)
            self.feed(i, request, result)
            made.append((i, request, result))
        return made

    def split(self, job: int, work: Job) -> list[tuple[int, RunScenes]] | None:
        """A failed batch of runs in halves (a chain is retried whole: its runs go one
        after the other, and it journals each as it goes)."""
        kind, what = self._jobs[job]
        if kind != "runs":
            return None
        self._jobs.pop(job)
        return [(self._jobs.add(("runs", units)), half) for units, half in halves(what, work)]

    def fail(self, job: int, reason: str) -> None:
        """A job that never came back (its worker kept dying): its points fail with that
        reason; no run is invented for them."""
        kind, what = self._jobs.pop(job)
        if kind == "chain":
            self.chained.discard(what)
            points = [what]
        else:
            for i, request in what:
                self.out[i].discard(request)
            points = sorted({i for i, _ in what})
        for i in points:
            self.arrived.pop(i, None)
            bis = self.bisections[i]
            bis.abort(reason)
            self.results[i] = bis.result()

    # ---- warm-start order -------------------------------------------------------------
    def _row_pos(self, i: int) -> tuple[int, int]:
        return divmod(i, self.shape[-1])

    def _ready(self, i: int) -> bool:
        if self.task.prescan is not None:
            return True
        first = self._start_order[0]
        if i != first and first not in self.results:
            return False  # every other point learns the reserve's offset from it
        row, pos = self._row_pos(i)
        first = row * self.shape[-1]
        bounds = self._tree[pos]
        if bounds is not None and any(first + j not in self.results for j in bounds[:2]):
            return False
        in_flight = sum(
            1
            for j in range(first, first + self.shape[-1])
            if j in self.bisections and j not in self.results
        )
        return in_flight < self.task.lanes

    def _start(self, i: int) -> None:
        prescan = self.task.prescan
        if prescan is not None:
            self.warm[i] = False
            self.bisections[i] = JumpSearch(
                prescan.mu,
                self.task.tol,
                self.task.max_retries,
                prescan.mode,
                self.task.split,
                self.task.certify,
                self.task.root_finder,
                stride_of(prescan, self.points[i].config.numerics.stick_rule, self.task.sides),
                prescan.persist,
                self.task.sides,
                self._resolution(),
            )
            return
        bracket = self._predicted_bracket(i)
        self.warm[i] = bracket is not None
        full = tuple(self.task.bracket)
        rules = BisectionSettings(
            self.task.tol,
            tuple(self.task.limits),
            self.task.max_retries,
            split=self.task.split,
            root_finder=self.task.root_finder,
            # a prediction that misses widens x8, x64, ... up to the full bracket, and the
            # ladder waits where a probe elsewhere may make it unnecessary (expanding.py)
            expanding=dataclasses.replace(PREDICTED, full=full) if bracket else COLD,
            between=self.task.sides,
            reserve_offset=self._reserve_offset(i),
            resolution=self._resolution(),
        )
        # cold (guided): open with the stick end and its reserve
        self.bisections[i] = CertifiedBisection(
            bracket or full, rules, self.task.certify, guided=bracket is None
        )

    def _resolution(self) -> float:
        """The narrowest bracket the numerics resolve: their expected mu* error (0 where
        unknown); a tol below it ends a point `failed` there (bisection_settings.py)."""
        choice = self.campaign.numerics_choice
        expected = None if choice is None else choice.expected
        return 0.0 if expected is None or self.task.parameter != "mu" else float(expected)

    def _reserve_offset(self, i: int) -> float:
        """The reserve's offset at the jump learned from the first point (reserve_offset.py):
        0 for that point itself, which starts before any other."""
        first = self._start_order[0]
        return 0.0 if i == first else learned_offset(self.results.get(first), self.task.tol)

    def _predicted_bracket(self, i: int) -> tuple[float, float] | None:
        row, pos = self._row_pos(i)
        bounds = self._tree[pos]
        if bounds is None:
            return None
        first = row * self.shape[-1]
        used = [first + j for j in bounds if j is not None]
        if any(self.results[j].status != "converged" for j in used[:2]):
            return None
        dim = self.campaign.dims[-1]
        x = self.points[i].coords[dim]
        known = [
            (self.points[j].coords[dim], self.results[j].mu_star)
            for j in used
            if self.results[j].status == "converged"
        ]
        linear = _extrapolate(known[:2], x)
        mu_hat, half = linear, 0.5 * self.task.tol
        if len(known) == 3:
            mu_hat = _extrapolate(known, x)
            half = max(half, WARM_ERROR_FACTOR * abs(mu_hat - linear))
        lo = max(self.task.limits[0], mu_hat - half)
        hi = min(self.task.limits[1], mu_hat + half)
        return (lo, hi) if lo < hi else None

    def snapshot(self) -> FindJumpResults:
        """What the planner has found so far (every point not finished: None)."""
        return FindJumpResults(
            self.campaign,
            tuple(self.points),
            tuple(self.results.get(i) for i in range(len(self.points))),
            tuple(self.warm.get(i, False) for i in range(len(self.points))),
            self.runs_saved(),
        )

    def progress(self) -> tuple[int, int]:
        """(points finished, points)."""
        return len(self.results), len(self.points)

    def runs_saved(self) -> int:
        """Search runs a cold bisection from the campaign bracket would have made, minus
        the search runs the warm-started points made (certification runs are the same
        either way; points that failed are not counted). Never negative: a warm point
        that needed more than a cold one saved nothing."""
        saved = 0
        for i, res in self.results.items():
            if self.warm.get(i) and res.status == "converged":
                search = sum(1 for run in res.runs if run_role(run.request) == "search")
                cold = cold_run_count(tuple(self.task.bracket), self.task.tol)
                saved += max(0, cold - search)
        return saved


def _extrapolate(known: list[tuple[float, float]], x: float) -> float:
    """The Lagrange polynomial through `known` (x_k, mu_k) pairs, evaluated at x."""
    total = 0.0
    for k, (x_k, mu_k) in enumerate(known):
        weight = 1.0
        for m, (x_m, _) in enumerate(known):
            if m != k:
                weight *= (x - x_m) / (x_k - x_m)
        total += weight * mu_k
    return total


def refinement(n: int) -> tuple[list[int], list[tuple[int, int, int | None] | None]]:
    """The coarse-to-fine order of a row of n points and, for each position, the two
    positions that bound its interval and the far end of the interval that was cut
    (None: an end of the row, or the first cut), or None for the row's ends."""
    order = [0] if n == 1 else [0, n - 1]
    tree: list[tuple[int, int, int | None] | None] = [None] * n
    queue = [(0, n - 1, None)]
    while queue:
        a, b, outer = queue.pop(0)
        if b - a < 2:
            continue
        mid = (a + b) // 2
        order.append(mid)
        tree[mid] = (a, b, outer)
        queue += [(a, mid, b), (mid, b, a)]
    return order, tree
