"""Every jump of one parameter point: scan mu first, then bisect each change. Pure Python.

Where the sticking set in mu is not an interval (a disk starting at rest, a Stribeck
pin, docs/model.md section 7), a single bisection reports one jump as if it were the only
one. `JumpSearch` runs a prescan over given values of mu, then bisects every pair of
neighbouring decided values whose outcomes differ in stick / not stick: a *rising* jump
(not stick below, stick above) or a *falling* one (stick below, not stick above). With
`stride` > 1 the prescan is adaptive (prescan.py): every stride-th value first, more only
where the verdicts and friction reserves do not explain an interval.

The headline is the lowest rising jump whose sticking side persists, and it comes with a
verdict at every prescan value below it:

* persistence (headline.py): a run at mu_hi + `persist` tol must stick too. If it does
  not, the sticking set above that jump is a *window* narrower than the persistence
  width: its falling edge is bisected, the search goes on above, and the window is
  reported (`JumpSearchResult.windows`), never the headline;
* the grid below: every prescan value below the headline that the adaptive prescan
  skipped is run (an interval skipped on the friction reserve alone is unexamined), and a
  change it reveals is bisected like any other (`JumpSearchResult.grid_below`). The
  adaptive prescan saves runs above the headline only;
* no jump: where the prescan finds no change and no value sticks, every grid value runs,
  and a point on whose whole grid nothing sticks has the answer `no_jump` (mu* lies
  above the grid), not a failure; its `grid_below` is the whole grid.

With `certify` enabled every jump's bracket is re-checked at stricter numerics
(certify.py), and the point is certified only with the whole grid below its headline
decided.

Like `Bisection` it is a state machine (`pending`, `feed`, `done`, `result`) that knows
nothing of simulation, I/O or Dask. Its `pending()` lists every run that can go now, so a
driver may run them in parallel. Prescan runs may use their own numerics.mode (e.g.
`converge`, for size-versus-mu curves); the bisections always decide.
"""

from __future__ import annotations

from typing import Any

from frictiondisk.model.search_settings import OFF, Certify
from frictiondisk.tasks.jump_search.bisection import RunRecord, RunRequest
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.certify import CertifiedBisection
from frictiondisk.tasks.jump_search.headline import Persistence, never_sticks
from frictiondisk.tasks.jump_search.jump_result import (
    RUN_ROLES,
    JumpSearchResult,
    JumpSearchState,
    RunOrder,
    compose_result,
    run_role,
)
from frictiondisk.tasks.jump_search.prescan import AdaptiveGrid, MotionRefinement, motion_runs
from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK, Between

__all__ = ["RUN_ROLES", "JumpSearch", "JumpSearchResult", "run_role"]


class JumpSearch:
    """Prescan `mus` (all of them, or adaptively from every `stride`-th), bisect every
    stick / not-stick change to `tol`, check that the headline persists over `persist` tol
    and run every prescan value below it."""

    def __init__(
        self,
        mus: tuple[float, ...],
        tol: float,
        max_retries: int,
        scan_mode: str | None = None,
        split: int = 2,
        certify: Certify = OFF,
        root_finder: str = "itp",
        stride: int = 1,
        persist: float = 3.0,
        between: Between = NOT_STICK_STICK,
        resolution: float = 0.0,
    ):
        if len(mus) < 2 or len(set(mus)) != len(mus):
            raise ValueError(f"a prescan needs at least 2 distinct values of mu, got {mus}")
        self.mus = tuple(sorted(mus))
        self.tol = tol
        self.max_retries = max_retries
        self.scan_mode = scan_mode
        self.split = split  # parts per bisection round (bisection.Bisection)
        self.certify = (
            certify  # every jump's bracket is certified (frictiondisk.tasks.jump_search.certify)
        )
        self.root_finder = root_finder  # how each jump's bisection picks its runs
        self.persist = persist  # [tol] a headline sticks this far above its bracket
        # the boundary's two sides (sides.py): "stick" below reads side B, "not stick" A
        self.between = between
        self.resolution = resolution  # [mu] no bracket is split below it (bisection_settings.py)
        self._scan_runs: list[RunRecord] = []  # every prescan run, retries included
        self._failure: str | None = None
        self._level: dict[float, int] = {}  # mu -> retry level to ask for next
        self._grid = AdaptiveGrid(self.mus, stride, between)  # which prescan values to run
        self._index = {mu: k for k, mu in enumerate(self.mus)}
        self.bisections: list[CertifiedBisection] = []
        self._covered: set[tuple[float, float]] = set()  # pairs a bisection was started on
        self._bisection_runs: list[RunRecord] = []
        self._issued: set[RunRequest] = set()  # prescan requests asked for
        # what the headline stands on: its persistence and the grid below it
        self._checks: dict[float, RunRecord] = {}  # mu -> settled persistence or fill run
        self._check_runs: list[RunRecord] = []  # every such run, retries included
        self._waiting: set[float] = set()  # persistence / fill values without a settled run
        self.persistence = Persistence(persist * tol)  # which jump is the headline
        self.unjudged = (
            self.persistence.unjudged
        )  # rising jumps whose persistence run stayed undetermined
        self._filled = False  # every grid value below the headline asked for
        # runs between neighbours below the headline that name different motions
        self._motions = MotionRefinement(len(self.mus), persist * tol, between)
        self._complete = False  # nothing left to run (set by _advance)
        self._pending: list[RunRequest] | None = None  # pending() until the next change

    # ---- what to run ------------------------------------------------------------------
    @property
    def scanning(self) -> bool:
        return self._failure is None and bool(self._grid.waiting)

    @property
    def done(self) -> bool:
        return self._failure is not None or self._complete

    def pending(self) -> list[RunRequest]:
        """Every run that can go now (do not modify the list: it is kept until the next
        feed, since a driver asks for it after every result of every point)."""
        if self._pending is None:
            if self.scanning:
                mus = [self.mus[k] for k in sorted(self._grid.waiting)]
                self._pending = [
                    RunRequest(mu, self._level.get(mu, 0), self.scan_mode) for mu in mus
                ]
                self._issued.update(self._pending)
            else:
                # two jumps that share a bracket end (a window's) ask for its runs once
                wanted = [r for b in self.bisections if not b.done for r in b.pending()]
                wanted += [self._check_request(mu) for mu in sorted(self._waiting)]
                self._pending = list(dict.fromkeys(wanted))
        return self._pending

    def _check_request(self, mu: float) -> RunRequest:
        """A persistence run (off the grid: the bisections' numerics) or a grid value below
        the headline (the prescan's)."""
        prescan = mu in self._index or mu in self._motions.asked
        return RunRequest(mu, self._level.get(mu, 0), self.scan_mode if prescan else None)

    # ---- what came back ---------------------------------------------------------------
    def feed(self, request: RunRequest, result: dict[str, Any]) -> None:
        if request not in self.pending():
            raise ValueError(f"unexpected run {request}")
        self._pending = None
        record = RunRecord(request, result)
        if self.scanning:
            self._scan_runs.append(record)
            if self._settled(request, result):
                self._grid.settle(self._index[request.mu], result)
            if not self.scanning and not self._grid.refine():
                self._advance()
            return
        if request.mu in self._waiting and request == self._check_request(request.mu):
            self._check_runs.append(record)
            if self._settled(request, result):
                self._checks[request.mu] = record
                self._waiting.discard(request.mu)
        else:
            self._bisection_runs.append(record)
            for bisection in self.bisections:
                if not bisection.done and request in bisection.pending():
                    bisection.feed(request, result)
        if not self._waiting and all(b.done for b in self.bisections):
            self._advance()

    def _settled(self, request: RunRequest, result: dict[str, Any]) -> bool:
        """Determined, or undetermined after every retry; else the next retry is due."""
        decided = self.between.side(result["outcome"]) is not None
        if decided or request.level >= self.max_retries:
            return True
        self._level[request.mu] = request.level + 1
        return False

    def abort(self, reason: str) -> None:
        """End as failed without more runs (e.g. its worker kept dying)."""
        self._failure = reason
        self._pending = None
        self._waiting.clear()
        for bisection in self.bisections:
            bisection.abort(reason)

    # ---- the search's next step --------------------------------------------------------
    def _advance(self) -> None:
        """Once nothing runs: bisect every change not bisected yet, else check the lowest
        rising jump's persistence, else run the grid below the headline, else finish."""
        self._pending = None
        if self._failure is not None:
            return
        changes = self._new_changes()
        for lo, hi, rising in changes:
            self._bisect(lo, hi, rising)
        if changes:
            if all(b.done for b in self.bisections):
                self._advance()  # every new bisection ended on its fed ends (a failure)
            return
        wanted = self.persistence.wanted(self.bisections, dict(self.known()), self._checks)
        if not wanted and not self._filled:
            self._filled = True
            wanted = self._fill_wanted()
        if not wanted:
            scan, prescan = self._last_scan(), set(self._index) | self._motions.asked
            outcomes, undetermined = motion_runs(scan, self._checks, prescan, self.between)
            no_jump = not self.bisections and never_sticks(
                scan.values(), self._checks.values(), self.between
            )
            top = grid_top(self._headline(), self.bisections, no_jump)
            wanted = self._motions.wanted(outcomes, top, undetermined)
        if wanted:
            self._waiting.update(wanted)
        else:
            self._complete = True

    def known(self) -> list[tuple[float, bool]]:
        """(mu, sticks) of every decided value at the point's own numerics: prescan values,
        persistence and fill runs, and the ends of the brackets the bisections converged to
        before certification; increasing in mu. (A certified bracket may have moved at
        stricter numerics; the changes between these values are all at one level.)"""
        high = self.between.is_high
        return sorted((mu, high(run["outcome"])) for mu, run in self._decided().items())

    def _decided(self) -> dict[float, dict[str, Any]]:
        """mu -> the decided run behind it (known)."""
        found: dict[float, dict[str, Any]] = {}
        for source in (self._last_scan(), self._checks):
            for mu, run in source.items():
                if self.between.side(run.outcome) is not None:
                    found[mu] = run.result
        for base in self._base_brackets():
            for mu, which in ((base.mu_lo, "lo"), (base.mu_hi, "hi")):
                end = base.end_result(which)
                if end is not None:
                    found.setdefault(mu, end)
        return found

    def _base_brackets(self):
        """The converged bracket of each finished bisection at the point's own numerics
        (its first search), unless its jump vanished at stricter numerics."""
        for bisection in self.bisections:
            if bisection.done and bisection.result().certification != "vanished":
                base = bisection.searches[0]
                if base.done and base.result().status == "converged":
                    yield base.result()

    def _new_changes(self) -> list[tuple[float, float, bool]]:
        """Neighbouring decided values that differ and no bisection was started on."""
        known = self.known()
        bracketed = {(r.mu_lo, r.mu_hi) for r in self._base_brackets()}
        return [
            (mu_a, mu_b, stick_b)
            for (mu_a, stick_a), (mu_b, stick_b) in zip(known, known[1:], strict=False)
            if stick_a != stick_b
            and (mu_a, mu_b) not in self._covered
            and (mu_a, mu_b) not in bracketed
        ]

    def _bisect(self, mu_a: float, mu_b: float, rising: bool) -> None:
        rules = BisectionSettings(
            self.tol,
            (mu_a, mu_b),
            self.max_retries,
            rising,
            self.split,
            root_finder=self.root_finder,
            between=self.between,
            resolution=self.resolution,
        )
        bisection = CertifiedBisection(
            (mu_a, mu_b), rules, self.certify, outer=(self.mus[0], self.mus[-1])
        )
        # its end checks are runs already made: fed, not run again
        decided = self._decided()
        for mu in (mu_a, mu_b):
            bisection.feed(RunRequest(mu, 0), decided[mu])
        self.bisections.append(bisection)
        self._covered.add((mu_a, mu_b))

    def headline(self):
        """The lowest rising jump that persists, else (`persists_nowhere`) the lowest rising
        jump; None without one."""
        found = self._headline()
        return None if found is None else found[1]

    def _headline(self):
        """(bisection index, result) of the headline, or None."""
        return self.persistence.headline(self.bisections, dict(self.known()), self._checks)

    def _fill_wanted(self) -> set[float]:
        """Every grid value below the headline not run yet; the whole grid where the
        prescan found no change and every value it ran does not stick (the answer "no
        jump" stands on the whole grid, as a headline on the grid below it)."""
        ran = set(self._last_scan()) | set(self._checks)
        found = self._headline()
        if found is None:
            scan, checks = self._last_scan().values(), self._checks.values()
            if not self.bisections and never_sticks(scan, checks, self.between):
                return {mu for mu in self.mus if mu not in ran}
            return set()
        base = self.bisections[found[0]].searches[0].result()
        below = min(found[1].mu_lo, base.mu_lo)  # certification may have moved the bracket
        return {mu for mu in self.mus if mu < below and mu not in ran}

    # ---- the answer -------------------------------------------------------------------
    def result(self) -> JumpSearchResult:
        if not self.done:
            raise ValueError("jump search not finished")
        return compose_result(self.snapshot())

    def snapshot(self) -> JumpSearchState:
        """What the finished search found, as its answer is composed from it."""
        last = self._last_scan()
        order = RunOrder(
            frozenset(self._issued),
            frozenset(run.request for run in self._check_runs),
            frozenset(self.mus) | frozenset(self._motions.asked),
            tuple(self.bisections),
        )
        runs = tuple(
            sorted([*self._scan_runs, *self._bisection_runs, *self._check_runs], key=order.key)
        )
        known, checks = dict(self.known()), self._checks
        found = self.persistence.headline(self.bisections, known, checks)
        nowhere = self.persistence.nowhere(self.bisections, known, checks)
        return JumpSearchState(
            mus=self.mus,
            tol=self.tol,
            persist=self.persist,
            certified=self.certify.enabled,
            found=tuple(b.result() for b in self.bisections),
            last_scan=last,
            checks=dict(checks),
            never_ran=tuple(k for k in self._grid.wanted if self.mus[k] not in last),
            failure=self._failure,
            headline=None if found is None else found[1],
            # its persistence run was decided (not undetermined) and showed it persists
            headline_judged=found is None or (found[0] not in self.unjudged and not nowhere),
            persists_nowhere=nowhere,
            never_sticks=never_sticks(last.values(), checks.values(), self.between),
            runs=runs,
            prescan_runs=tuple(sorted(self._scan_runs, key=order.key)),
            roles={run.request: order.role(run.request) for run in runs},
            between=self.between,
            motion_runs=len(self._motions.asked),
        )

    def _last_scan(self) -> dict[float, RunRecord]:
        """mu -> its last prescan run (the one at the highest retry level)."""
        return {run.request.mu: run for run in self._scan_runs}


def grid_top(found, bisections, no_jump: bool) -> float:
    """Where the grid the headline stands on ends (`found`: (index, result) of the
    headline, or None): below its bracket, also below the bracket at the point's own
    numerics; the whole grid (inf) for the answer "no jump"; -inf where neither stands yet."""
    if found is None:
        return float("inf") if no_jump else -float("inf")
    base = bisections[found[0]].searches[0].result()
    return min(found[1].mu_lo, base.mu_lo)
