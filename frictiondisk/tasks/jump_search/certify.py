"""Certification of a located jump: its bracket re-checked with stricter numerics. Pure Python.

A bisection ends with a bracket [mu_lo, mu_hi] whose ends were decided with the point's
numerics. `CertifiedBisection` then re-runs both ends at the next certification level
(rtol and atol x `Certify.rtol`, horizon budget x `Certify.horizon`, docs/model.md section 7):

* both verdicts hold: the jump is `certified` (`recertified` after a re-search);
* an end flips: the jump moved. While a stricter level is left, the search starts again
  at the stricter level from the end that flipped (its strict run is reused as a bracket
  end) and is certified again;
* an end flips at the last level, both ends flip, or a strict run stays undetermined:
  `uncertain`, with the best bracket kept. A check's horizon budget reaches as far as its
  last retry would (`RunRequest.reach`): one whose budget ran out is not retried (a retry
  would restart from t = 0 and compute the same motion again before looking further);
  one that ended at a horizon no budget extends (mode converge) is;
* the re-search finds no jump within the bracket's limits: `vanished` (a jump that existed
  only because of the short horizon; a prescan drops it).

A cold search (`guided=True`: no predicted bracket) opens with the stick end alone. Where
its friction reserve agrees with its verdict, the reserve's zero (unit slope) is run next
instead of the bracket's other end: a not-stick there is the bracket's lower end, far
closer to the jump than the user's `lo` (which is never run); a stick there becomes the
upper end, and `lo` is checked as usual. Verdicts alone set the bracket; the guide only
picks which mu to run (docs/model.md section 7).

Like `Bisection` it is a state machine (`pending`, `feed`, `done`, `result`) that knows
nothing of simulation, so the same object drives a live campaign and its replay.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from frictiondisk.model.search_settings import OFF, Certify
from frictiondisk.tasks.jump_search.bisection import (
    STICK,
    UNDETERMINED,
    Bisection,
    BisectionResult,
    BisectionSettings,
    RunRecord,
    RunRequest,
)
from frictiondisk.tasks.jump_search.expanding import PLAIN
from frictiondisk.tasks.jump_search.watch import check_watch
from frictiondisk.verdict.deciding_rule import BUDGET_RAN_OUT, INTEGRATOR_FAILED

# how much a flag weighs when a point with several jumps is summed up in one flag
_RANK = {"off": 0, "certified": 1, "vanished": 1, "recertified": 2, "uncertain": 3, "failed": 4}


def point_certification(flags) -> str:
    """One flag for a point from its jumps' flags: the weakest of them (`failed` if none)."""
    kept = [flag for flag in flags if flag != "vanished"]
    return max(kept, key=_RANK.__getitem__) if kept else "failed"


class CertifiedBisection:
    """A `Bisection` whose converged bracket is re-checked at stricter numerics."""

    def __init__(
        self,
        bracket: tuple[float, float],
        settings: BisectionSettings,
        certify: Certify = OFF,
        guided: bool = False,
        outer: tuple[float, float] | None = None,
    ):
        """`settings` are the rules of its first search (a re-search at stricter numerics
        differs in its level and limits alone, _research); `guided` opens with the stick
        end and the reserve's zero (module docstring); `outer` is where a re-search may
        look besides settings.limits."""
        limits = settings.limits
        self.settings = settings
        self.tol = settings.tol
        self.strict = settings.strict  # level of its first search (a repair goes on there)
        self.between = settings.between  # the two sides of the boundary (sides.py)
        self.limits = limits
        # where a re-search at stricter numerics may look: a jump that leaves its prescan
        # cell (the cell's end flips too) is followed into the next cells, not lost
        self.outer = (
            limits if outer is None else (min(outer[0], limits[0]), max(outer[1], limits[1]))
        )
        self.max_retries = settings.max_retries
        self.rising = settings.rising
        self.split = settings.split
        self.certify = certify
        self.root_finder = settings.root_finder
        self.expanding = settings.expanding  # how its first search reaches past a miss
        self.reserve_offset = settings.reserve_offset  # reserve at the jump per unit mu
        self.search = Bisection(bracket, self.settings)
        self.searches: list[Bisection] = [self.search]
        # the guided opening (module docstring): the stick end, then the reserve's zero
        self._opening = guided and settings.rising and settings.interpolates
        self._opening = self._opening and settings.between.uses_reserve
        self._opened: list[RunRecord] = []  # its runs
        self._checks: dict[float, RunRecord] = {}  # mu -> decided strict run of this check
        self._check_level: dict[float, int] = {}  # mu -> retry level to ask for next
        self._check_runs: list[RunRecord] = []
        self._own_method: set[float] = set()  # ends checked again with the point's integrator
        self._issued: dict[RunRequest, tuple] = {}
        self._checking = False
        self._verdict: str | None = None  # set when done
        self._watched_flip: float | None = None  # an end whose watching check flipped

    # ---- what to run ------------------------------------------------------------------
    @property
    def done(self) -> bool:
        return self._verdict is not None

    def pending(self) -> list[RunRequest]:
        if self.done:
            return []
        if self._opening:
            return [RunRequest(self._guide() if self._opened else self.search.hi)]
        if not self._checking:
            return self.search.pending()
        # a check's horizon budget covers the retry levels above its own: where the budget
        # extends a run (mode decide) it is not restarted from t = 0 to look further (it
        # would compute the same motion again), it looks as far as its last retry would
        strict = self.search.strict + 1
        requests = []
        for mu in (self.search.lo, self.search.hi):
            if mu not in self._checks:
                level = self._check_level.get(mu, 0)
                reach = self.max_retries - level
                requests.append(
                    RunRequest(
                        mu,
                        level,
                        strict=strict,
                        watch=check_watch(self.search, mu, self.certify, self.between),
                        reach=reach,
                        own_method=mu in self._own_method,
                    )
                )
        for request in requests:
            self._issued.setdefault(request, (len(self.searches), request.level, request.mu))
        return requests

    def schedule_key(self, request: RunRequest) -> tuple | None:
        for index, search in enumerate(self.searches):
            key = search.schedule_key(request)
            if key is not None:
                return (index, 0, *key)
        if any(run.request == request for run in self._opened):
            return (-1, 0, request.mu)
        key = self._issued.get(request)
        return None if key is None else (key[0] - 1, 1, *key[1:])

    # ---- what came back ---------------------------------------------------------------
    def feed(self, request: RunRequest, result: dict[str, Any]) -> None:
        if self._opening:
            if request not in self.pending():
                raise ValueError(f"unexpected run {request}")
            self._open(RunRecord(request, result))
            return
        if not self._checking:
            self.search.feed(request, result)
            if self.search.done:
                self._after_search()
            return
        if request not in self.pending():
            raise ValueError(f"unexpected run {request}")
        record = RunRecord(request, result)
        self._check_runs.append(record)
        if (
            result.get("decided_by") == INTEGRATOR_FAILED
            and not request.own_method
            and self.certify.method != "rodas4"
        ):
            # certify.method's integrator failed (a step-size underflow): a longer horizon
            # would compute the same failure again; the point's own integrator checks it
            self._own_method.add(request.mu)
            return
        # an undetermined check whose budget ran out looked as far as its retries would; one
        # that ended at its horizon without a budget to extend it (mode converge: t_max) or
        # on an error is retried with a longer horizon
        if (
            self.between.side(result["outcome"]) is None
            and request.level < self.max_retries
            and result.get("decided_by") != BUDGET_RAN_OUT
        ):
            self._check_level[request.mu] = request.level + 1
            return
        self._checks[request.mu] = record
        if len(self._checks) == 2:
            self._after_check()

    def _guide(self) -> float:
        """Where to run after the stick end: the reserve's zero, at most hi - tol (so that a
        not-stick there closes the bracket), or lo where the reserve says nothing."""
        hi = self._opened[0]
        lo, tol = self.search.lo, self.tol
        reserve = hi.result.get("reserve")
        if hi.outcome != STICK or reserve is None or not math.isfinite(reserve):
            return lo
        reserve -= self.reserve_offset * hi.request.mu  # its zero at the jump (learned)
        if reserve <= 0:
            return lo
        guide = min(hi.request.mu - reserve, hi.request.mu - tol * (1.0 - 1e-6))
        return guide if guide > lo else lo

    def _open(self, record: RunRecord) -> None:
        """Take a run of the guided opening; once it is over, the search goes on as a
        Bisection whose decided ends are fed to it (an undetermined run ends the opening:
        the Bisection retries it)."""
        self._opened.append(record)
        lo, hi = self.search.lo, self.search.hi
        if len(self._opened) == 1 and record.outcome != UNDETERMINED and self._guide() != lo:
            return  # run the guide next
        self._opening = False
        ends = self._opened[:1]  # the stick end (or its undetermined run: retried)
        guide = self._opened[1] if len(self._opened) == 2 else None
        if guide is not None and guide.outcome == STICK:  # the jump lies below the guide
            hi, ends = guide.request.mu, [guide]
        elif guide is not None and guide.outcome != UNDETERMINED:  # a not-stick: the bracket
            lo, ends = guide.request.mu, self._opened
        self.search = Bisection((lo, hi), self.settings)
        self.searches = [self.search]
        for run in ends:
            self.search.pending()
            self.search.feed(RunRequest(run.request.mu), run.result)
        if self.search.done:
            self._after_search()

    def abort(self, reason: str) -> None:
        if not self.done:
            self.search.abort(reason)
            self._finish("failed")

    def _after_search(self) -> None:
        found = self.search.result()
        if found.status != "converged":
            # a re-search that finds no change within the limits: the jump was an artefact;
            # one that stalls on a run the stricter numerics cannot decide: uncertain
            if len(self.searches) == 1:
                self._finish("failed")
            else:
                self._finish("uncertain" if self.search.stalled_at is not None else "vanished")
        elif not self.certify.enabled:
            self._finish("off")
        else:
            self._checking = True
            self._checks = {}
            self._check_level = {}

    def _after_check(self) -> None:
        lo, hi = self.search.lo, self.search.hi
        runs = (self._checks[lo], self._checks[hi])
        if any(self.between.side(run.outcome) is None for run in runs):
            self._finish("uncertain")
            return
        lo_stick, hi_stick = (self.between.is_high(run.outcome) for run in runs)
        want_lo, want_hi = (False, True) if self.rising else (True, False)
        lo_holds, hi_holds = lo_stick == want_lo, hi_stick == want_hi
        if lo_holds and hi_holds:
            self._finish("certified" if len(self.searches) == 1 else "recertified")
            return
        strict = self.search.strict + 1
        if (not lo_holds and not hi_holds) or strict >= self.certify.levels:
            self._finish("uncertain")
            return
        flipped = runs[1] if not hi_holds else runs[0]
        if flipped.request.watch > 0.0:
            # watching refuted the verdict that decided this end: the re-search watches
            # every run as long (else it would decide the values beside it by the same
            # rule, unwatched, and bracket the difference between watching and not)
            self._watched_flip = flipped.request.mu
        self._research(strict, hi_flipped=not hi_holds, watch=flipped.request.watch)

    def _research(self, strict: int, hi_flipped: bool, watch: float = 0.0) -> None:
        """Search again at `strict` from the end that flipped: it joins the other side.
        Every run of the new search watches until `watch` [s] (0: none)."""
        old = self.search
        step = max(2.0 * (old.hi - old.lo), 2.0 * self.tol)
        limits = self.outer
        if hi_flipped:
            near = old.hi
            far = min(limits[1], near + step)
            bracket = (near, far)
        else:
            near = old.lo
            far = max(limits[0], near - step)
            bracket = (far, near)
        self._checking = False
        if bracket[1] - bracket[0] <= self.tol * (1 + 1e-9):
            self._finish("vanished")
            return
        search = Bisection(
            bracket,
            dataclasses.replace(
                self.settings, limits=limits, strict=strict, expanding=PLAIN, watch=watch
            ),
        )
        self.search = search
        self.searches.append(search)
        # the strict run at the end that flipped is this search's check of that end
        record = self._checks[near]
        search.pending()
        search.feed(RunRequest(near, 0, strict=strict, watch=watch), record.result)
        if search.done:
            self._after_search()

    def _finish(self, verdict: str) -> None:
        self._verdict = verdict
        self._checking = False

    # ---- the answer -------------------------------------------------------------------
    def result(self) -> BisectionResult:
        if not self.done:
            raise ValueError("bisection not finished")
        final = self.search.result()
        if self._verdict == "vanished" and len(self.searches) > 1:
            final = self.searches[-2].result()
        elif final.status != "converged" and len(self.searches) > 1:
            first = self.searches[0].result()
            final = dataclasses.replace(
                final,
                reason=f"its bracket [{first.mu_lo:.6g}, {first.mu_hi:.6g}] did not hold at "
                f"stricter numerics, and the search there stalled: {final.reason}",
            )
        seen: set[int] = set()
        runs: list[RunRecord] = []
        searched = (r for s in self.searches for r in s.result().runs)
        for record in [*self._opened, *searched, *self._check_runs]:
            if id(record.result) not in seen:  # a reused strict run counts once
                seen.add(id(record.result))
                runs.append(record)
        # in the order requested, not the order results arrived: independent of timing
        runs.sort(key=lambda run: self.schedule_key(run.request))
        # a check's run reused as a re-search's bracket end is named by the request that
        # ran (its reach included), so that it can be found by it (tasks/trace)
        ran = {id(check.result): check.request for check in self._check_runs}
        runs = [RunRecord(ran.get(id(run.result), run.request), run.result) for run in runs]
        reason = final.reason
        if self._verdict not in ("off", "failed"):
            reason = f"{reason}; {self._verdict} ({self._describe()})"
        if self._watched_flip is not None:
            reason = (
                f"{reason}: watched, the end mu = {self._watched_flip:.10g} flipped, so the "
                "verdict that decided it did not hold; searched again from it, every run "
                f"watched until {self.searches[-1].settings.watch:.4g} s"
            )
        return dataclasses.replace(
            final,
            reason=reason,
            runs=tuple(runs),
            certification=self._verdict,
        )

    def _describe(self) -> str:
        level = self.search.strict + (1 if self._verdict != "vanished" else 0)
        reach = f", reaching as far as {self.max_retries} retries" if self.max_retries else ""
        finer = f"eps x {self.certify.eps**level:g}, " if self.certify.eps != 1.0 else ""
        return (
            f"ends re-run at rtol and atol x {self.certify.rtol**level:g}, {finer}"
            f"horizon budget x {self.certify.horizon**level:g}{reach}"
        )
