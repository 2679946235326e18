"""Every jump of one parameter point: scan mu first, then bisect each change. Pure Python.

Where the sticking set in mu is not an interval (a disk starting at rest, docs/model.md
section 7), a single bisection reports one jump as if it were the only one. `JumpSearch`
runs a prescan over given values of mu, then bisects every pair of neighbouring prescan
values whose outcomes differ in stick / not stick: a *rising* jump (not stick below,
stick above) or a *falling* one (stick below, not stick above). Jumps narrower than the
prescan spacing are not seen; the spacing is the campaign's resolution and is reported.
With `stride` > 1 the prescan is adaptive (frictiondisk.search.prescan): every stride-th value
first, more only where the verdicts and friction reserves do not explain an interval.

Like `Bisection` it is a state machine (`pending`, `feed`, `done`, `result`) that knows
nothing of simulation, I/O or Dask. Its `pending()` lists every run that can go now: the
whole prescan at once, then the current round of every jump's bisection together, so a
driver may run them in parallel. Prescan runs may use their own numerics.mode (e.g.
`converge`, for size-versus-mu curves); the bisections always decide.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.model.search_settings import OFF, Certify
from frictiondisk.search.bisection import (
    STICK,
    UNDETERMINED,
    BisectionResult,
    RunRecord,
    RunRequest,
)
from frictiondisk.search.certify import CertifiedBisection, point_certification
from frictiondisk.search.prescan import AdaptiveGrid

RUN_ROLES = ("search", "prescan", "certification")


def run_role(request: RunRequest) -> str:
    """The role of a run of a bisection: `certification` at stricter numerics, else `search`."""
    return "certification" if request.strict > 0 else "search"


@dataclasses.dataclass(frozen=True)
class JumpSearchResult:
    """All jumps of one point. The attributes of `BisectionResult` describe the *primary*
    jump (the lowest rising one, else the lowest jump), so code written for one jump
    keeps working; `jumps` holds every one, in increasing mu."""

    status: str  # "converged" if the prescan settled and every jump converged
    reason: str
    jumps: tuple[BisectionResult, ...]
    scan: tuple[RunRecord, ...]  # the prescan runs, one per mu (its last retry level)
    runs: tuple[RunRecord, ...]  # every run made: prescan, then each bisection's own
    primary: BisectionResult | None
    prescan_runs: tuple[RunRecord, ...] = ()  # every prescan run, retries included

    @property
    def mu_lo(self) -> float:
        return self.primary.mu_lo if self.primary else float("nan")

    @property
    def mu_hi(self) -> float:
        return self.primary.mu_hi if self.primary else float("nan")

    @property
    def mu_star(self) -> float:
        return 0.5 * (self.mu_lo + self.mu_hi)

    @property
    def contradictions(self) -> tuple[tuple[float, float], ...]:
        return tuple(c for jump in self.jumps for c in jump.contradictions)

    @property
    def monotone(self) -> bool:
        """One rising jump and nothing that contradicts it."""
        return len(self.jumps) == 1 and self.jumps[0].rising and not self.contradictions

    def end_result(self, which: str) -> dict[str, Any] | None:
        return self.primary.end_result(which) if self.primary else None

    def role(self, request: RunRequest) -> str:
        """`prescan`, `certification` (stricter numerics) or `search` (bisection)."""
        if any(run.request == request for run in self.prescan_runs):
            return "prescan"
        return run_role(request)

    @property
    def certification(self) -> str:
        """The weakest certification of the point's jumps (`failed` if it has none)."""
        if self.status != "converged":
            return "failed"
        return point_certification(j.certification for j in self.jumps)


class JumpSearch:
    """Prescan `mus` (all of them, or adaptively from every `stride`-th), then bisect
    every stick / not-stick change to `tol`."""

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
    ):
        if len(mus) < 2 or len(set(mus)) != len(mus):
            raise ValueError(f"a prescan needs at least 2 distinct values of mu, got {mus}")
        self.mus = tuple(sorted(mus))
        self.tol = tol
        self.max_retries = max_retries
        self.scan_mode = scan_mode
        self.split = split  # parts per bisection round (bisection.Bisection)
        self.certify = certify  # every jump's bracket is certified (frictiondisk.search.certify)
        self.root_finder = root_finder  # how each jump's bisection picks its runs
        self._scan_runs: list[RunRecord] = []  # every prescan run, retries included
        self._failure: str | None = None
        self._level: dict[float, int] = {}
        self._grid = AdaptiveGrid(self.mus, stride)  # which prescan values to run
        self._index = {mu: k for k, mu in enumerate(self.mus)}
        self.bisections: list[CertifiedBisection] = []
        self._bisection_runs: list[RunRecord] = []
        self._issued: set[RunRequest] = set()  # prescan requests asked for
        self._pending: list[RunRequest] | None = None  # pending() until the next change

    # ---- what to run ------------------------------------------------------------------
    @property
    def scanning(self) -> bool:
        return self._failure is None and bool(self._grid.waiting)

    @property
    def done(self) -> bool:
        return not self.scanning and all(b.done for b in self.bisections)

    def pending(self) -> list[RunRequest]:
        """Every run that can go now (do not modify the list: it is kept until the next
        feed, since a driver asks for it after every result of every point)."""
        if self._pending is None:
            if self.scanning:
                self._pending = [
                    RunRequest(self.mus[k], self._level.get(self.mus[k], 0), self.scan_mode)
                    for k in sorted(self._grid.waiting)
                ]
                self._issued.update(self._pending)
            else:
                self._pending = [r for b in self.bisections if not b.done for r in b.pending()]
        return self._pending

    # ---- what came back ---------------------------------------------------------------
    def feed(self, request: RunRequest, result: dict[str, Any]) -> None:
        if request not in self.pending():
            raise ValueError(f"unexpected run {request}")
        self._pending = None
        if self.scanning:
            self._scan_runs.append(RunRecord(request, result))
            if result["outcome"] != UNDETERMINED or request.level >= self.max_retries:
                # settled: determined, or undetermined after every retry
                self._grid.settle(self._index[request.mu], result)
            else:
                self._level[request.mu] = request.level + 1
            if not self.scanning and not self._grid.refine():
                self._start_bisections()
            return
        self._bisection_runs.append(RunRecord(request, result))
        for bisection in self.bisections:
            if not bisection.done and request in bisection.pending():
                bisection.feed(request, result)

    def abort(self, reason: str) -> None:
        """End as failed without more runs (e.g. its worker kept dying)."""
        self._failure = reason
        self._pending = None
        for bisection in self.bisections:
            bisection.abort(reason)

    def _start_bisections(self) -> None:
        """One bisection per neighbouring pair of determined prescan values that differ."""
        last = self._last_scan()
        known = [
            (mu, last[mu].outcome == STICK)
            for mu in self.mus
            if mu in last and last[mu].outcome != UNDETERMINED
        ]
        for (mu_a, stick_a), (mu_b, stick_b) in zip(known, known[1:], strict=False):
            if stick_a == stick_b:
                continue
            bisection = CertifiedBisection(
                (mu_a, mu_b),
                self.tol,
                (mu_a, mu_b),
                self.max_retries,
                stick_b,
                self.split,
                self.certify,
                self.root_finder,
            )
            # its end checks are the prescan runs: fed, not run again
            for mu in (mu_a, mu_b):
                bisection.feed(RunRequest(mu, 0), last[mu].result)
            self.bisections.append(bisection)

    # ---- the answer -------------------------------------------------------------------
    def result(self) -> JumpSearchResult:
        if not self.done:
            raise ValueError("jump search not finished")
        found = tuple(b.result() for b in self.bisections)
        # a jump that stricter numerics showed to be an artefact of the short horizon is dropped
        jumps = tuple(j for j in found if j.certification != "vanished")
        vanished = len(found) - len(jumps)
        last = self._last_scan()
        scan = tuple(last[mu] for mu in self.mus if mu in last)
        lost = [k for k in self._grid.wanted if self.mus[k] not in last]
        # an undetermined prescan value inside a converged jump's bracket is that jump's
        # slow approach (bisection.Bisection.undecided), not a gap in the scan
        undetermined = [
            r.request.mu
            for r in scan
            if r.outcome == UNDETERMINED
            and not any(j.status == "converged" and j.mu_lo < r.request.mu < j.mu_hi for j in jumps)
        ]
        failed = [j for j in jumps if j.status != "converged"]
        rising = [j for j in jumps if j.rising]
        primary = (rising or list(jumps) or [None])[0]
        problems = []
        if self._failure:
            problems.append(self._failure)
        if lost:
            problems.append(f"{len(lost)} prescan value(s) never ran")
        if undetermined:
            mus = ", ".join(f"{mu:.6g}" for mu in undetermined)
            problems.append(f"prescan undetermined at mu = {mus} after every retry")
        problems += [f"jump in [{j.mu_lo:.6g}, {j.mu_hi:.6g}]: {j.reason}" for j in failed]
        if not jumps and not problems:
            kinds = {r.outcome == STICK for r in scan}
            which = "stick" if kinds == {True} else "not stick"
            problems.append(
                f"no jump: every prescan value from mu = {self.mus[0]:.6g} to "
                f"{self.mus[-1]:.6g} gave {which}"
            )
        if not jumps and vanished and not problems:
            problems.append(
                f"no jump: the {vanished} jump(s) of the prescan vanished at stricter numerics"
            )
        if problems:
            status, reason = "failed", "; ".join(problems)
        else:
            kinds = ", ".join(
                f"{'rising' if j.rising else 'falling'} at {j.mu_star:.6g}"
                + ("" if j.certification == "off" else f" ({j.certification})")
                for j in jumps
            )
            status = "converged"
            reason = f"{len(jumps)} jump(s) to tol {self.tol:.3g}: {kinds}"
            if len(scan) < len(self.mus):
                reason += f"; adaptive prescan ran {len(scan)} of {len(self.mus)} values"
            if vanished:
                reason += f"; {vanished} more vanished at stricter numerics"
        runs = tuple(sorted([*self._scan_runs, *self._bisection_runs], key=self._order))
        return JumpSearchResult(
            status,
            reason,
            jumps,
            scan,
            runs,
            primary,
            tuple(sorted(self._scan_runs, key=self._order)),
        )

    def _last_scan(self) -> dict[float, RunRecord]:
        """mu -> its last prescan run (the one at the highest retry level)."""
        return {run.request.mu: run for run in self._scan_runs}

    def _order(self, run: RunRecord) -> tuple:
        """Prescan runs first (by retry level, then mu), then each bisection's runs in its
        own schedule order: fixed by the campaign, not by the order results arrived in."""
        request = run.request
        if request in self._issued:
            return (0, request.level, request.mu)
        for index, bisection in enumerate(self.bisections):
            key = bisection.schedule_key(request)
            if key is not None:
                return (1, index, *key)
        return (2, request.level, request.mu)
