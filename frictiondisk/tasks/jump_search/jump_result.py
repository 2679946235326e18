"""What a `JumpSearch` found at one point: its jumps, windows, headline and how much of the
grid below the headline is certified (`compose_result`, from the search's public snapshot,
`JumpSearchState`). Pure Python."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from frictiondisk.tasks.jump_search.bisection import BisectionResult, RunRecord, RunRequest
from frictiondisk.tasks.jump_search.certify import point_certification
from frictiondisk.tasks.jump_search.jump_reason import (
    converged_reason,
    motion_note,
    problems_of,
    tail_notes,
)
from frictiondisk.tasks.jump_search.prescan import motion_boundaries
from frictiondisk.tasks.jump_search.sides import NOT_STICK_STICK, Between

RUN_ROLES = ("search", "prescan", "certification")
# a point's status: "converged" (a headline), NO_JUMP (no value of the whole grid sticks,
# every one decided: mu* lies above it) or "failed" (no answer)
NO_JUMP = "no_jump"


def run_role(request: RunRequest) -> str:
    """The role of a run of a bisection: `certification` at stricter numerics, else `search`."""
    return "certification" if request.strict > 0 else "search"


@dataclasses.dataclass(frozen=True)
class RunOrder:
    """The role of each run of a jump search and the order its runs are reported in: prescan
    runs first (by retry level, then mu), then each bisection's runs in its own schedule
    order, then the persistence and fill runs: fixed by the campaign, not by the order
    results arrived in."""

    prescan: frozenset  # the requests the prescan asked for
    checks: frozenset  # the persistence and fill runs' requests
    grid: frozenset  # the prescan's values of mu and the mu its refinement between motions ran
    bisections: tuple  # the jump's searches (their schedule_key)

    def role(self, request: RunRequest) -> str:
        """`prescan` (the prescan's runs, and the grid values below the headline it skipped),
        `search` (bisections and persistence runs) or `certification` (stricter numerics)."""
        if request in self.prescan:
            return "prescan"
        if request in self.checks:
            return "prescan" if request.mu in self.grid else "search"
        return run_role(request)

    def key(self, run: RunRecord) -> tuple:
        request = run.request
        if request in self.prescan:
            return (0, request.level, request.mu)
        for index, bisection in enumerate(self.bisections):
            key = bisection.schedule_key(request)
            if key is not None:
                return (1, index, *key)
        return (2, request.level, request.mu)


@dataclasses.dataclass(frozen=True)
class Window:
    """A sticking interval closed on both sides: a rising jump and the falling jump above it."""

    lo: float  # the rising jump's mu*
    hi: float  # the falling jump's mu*
    narrow: bool  # narrower than the persistence width: never a headline

    @property
    def width(self) -> float:
        return self.hi - self.lo


@dataclasses.dataclass(frozen=True)
class GridBelow:
    """The prescan grid below the headline: how much of it has a decided verdict (prescan
    or fill runs; a not-stick verdict always with the evidence of its own section, and a
    value that sticks always inside a bisected window), and the largest gap between
    decided values there, below which a window could still hide."""

    decided: int  # grid values below the headline with a decided verdict
    total: int  # grid values below the headline
    resolution: float  # largest gap between decided values below the headline [1]
    # runs between neighbours that name different motions (prescan.MotionRefinement), and
    # the intervals between them still wider than the persistence width (its budget ran
    # out; beside an undetermined value, wider than half that)
    motion_runs: int = 0
    unrefined: int = 0
    # values undetermined after every retry between such neighbours
    unrefined_at: tuple[float, ...] = ()

    @property
    def share(self) -> float:
        return self.decided / self.total if self.total else 1.0


@dataclasses.dataclass(frozen=True)
class JumpSearchState:
    """A finished JumpSearch as its answer is composed from it (JumpSearch.snapshot)."""

    mus: tuple[float, ...]  # the prescan grid
    tol: float
    persist: float  # [tol] a headline sticks this far above its bracket
    certified: bool  # certification enabled
    found: tuple[BisectionResult, ...]  # every bisection's result, in the order started
    last_scan: dict[float, RunRecord]  # mu -> its last prescan run
    checks: dict[float, RunRecord]  # mu -> its settled persistence or fill run
    never_ran: tuple[int, ...]  # grid indices the prescan wanted and never ran
    failure: str | None  # why it ended early (aborted), None
    headline: BisectionResult | None
    headline_judged: bool  # its persistence run was decided and showed it persists
    persists_nowhere: bool  # rising jumps, none persists
    never_sticks: bool  # every prescan value decided not stick, no fill run sticks
    runs: tuple[RunRecord, ...]  # every run, in the search's schedule order
    prescan_runs: tuple[RunRecord, ...]  # every prescan run, retries included, in order
    roles: dict[RunRequest, str]  # the role of every run
    between: Between = NOT_STICK_STICK  # the boundary's sides ("stick" reads side B)
    motion_runs: int = 0  # runs between neighbours naming different motions


@dataclasses.dataclass(frozen=True)
class JumpSearchResult:
    """All jumps of one point. The attributes of `BisectionResult` describe the *primary*
    jump (the headline: the lowest rising jump that persists; else the lowest jump), so
    code written for one jump keeps working; `jumps` holds every one, in increasing mu."""

    status: str  # "converged", NO_JUMP or "failed" (see NO_JUMP)
    reason: str
    jumps: tuple[BisectionResult, ...]
    scan: tuple[RunRecord, ...]  # the prescan runs, one per mu (its last retry level)
    runs: tuple[RunRecord, ...]  # every run made: prescan, bisections, checks
    primary: BisectionResult | None
    prescan_runs: tuple[RunRecord, ...] = ()  # every prescan run, retries included
    windows: tuple[Window, ...] = ()
    grid_below: GridBelow | None = None  # the whole grid for NO_JUMP; None: no headline
    checks: tuple[RunRecord, ...] = ()  # persistence and fill runs (settled)
    roles: dict[RunRequest, str] = dataclasses.field(default_factory=dict)
    grid_flag: str = "off"  # certification of the grid below the headline

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
        """`prescan` (with the grid values filled below the headline), `search` (bisections,
        persistence runs) or `certification` (stricter numerics)."""
        return self.roles.get(request) or run_role(request)

    @property
    def certification(self) -> str:
        """The weakest certification of the point's jumps and of the grid below its
        headline; of a point without a jump, that of its whole grid (`failed` if it has
        no answer)."""
        if self.status == NO_JUMP:
            return self.grid_flag
        if self.status != "converged":
            return "failed"
        flags = [j.certification for j in self.jumps if not above_headline(j, self.primary)]
        if self.grid_flag != "off":
            flags.append(self.grid_flag)
        return point_certification(flags)


def above_headline(jump: BisectionResult, head: BisectionResult | None) -> bool:
    """A jump that failed wholly above the headline's bracket: it cannot be a lower rising
    jump, so the headline stands without it (its failure is told, not hidden)."""
    return (
        head is not None
        and jump is not head
        and jump.status != "converged"
        and not math.isnan(jump.mu_lo)
        and jump.mu_lo >= head.mu_hi
    )


def _windows(jumps, persist_width: float) -> tuple[Window, ...]:
    """Every rising jump followed directly by a falling one: a closed sticking interval."""
    found = []
    for below, above in zip(jumps, jumps[1:], strict=False):
        if below.rising and not above.rising and below.status == above.status == "converged":
            found.append(
                Window(below.mu_star, above.mu_star, above.mu_lo - below.mu_hi < persist_width)
            )
    return tuple(found)


def _grid_below(state: JumpSearchState, top: float) -> GridBelow:
    """The grid below `top`: the headline's mu_lo, or math.inf for the whole grid (the
    answer "no jump")."""
    decided = {}
    for source in (state.last_scan, state.checks):
        for mu, run in source.items():
            if state.between.side(run.outcome) is not None:
                decided[mu] = run.outcome
    below = [mu for mu in state.mus if mu < top]
    end = top if math.isfinite(top) else state.mus[-1]
    seen = sorted(mu for mu in decided if mu < top) + [end]
    gaps = [b - a for a, b in zip([state.mus[0], *seen], seen, strict=False)]
    width = state.persist * state.tol
    runs = {**state.last_scan, **state.checks}
    undetermined = [mu for mu in runs if mu not in decided]
    pairs = motion_boundaries(decided, top, width, state.between, undetermined)
    boundaries = motion_boundaries(decided, top, 0.0, state.between)  # every such pair
    stuck = tuple(sorted({mu for mu in undetermined for a, b in boundaries if a < mu < b}))
    return GridBelow(
        sum(mu in decided for mu in below),
        len(below),
        max(gaps) if gaps else 0.0,
        state.motion_runs,
        len(pairs),
        stuck,
    )


def _distinct(jumps):
    """The jumps without those whose converged bracket overlaps another's of the same
    direction; of two such, the one found where the prescan put it (certified) stays."""
    kept: list = []
    for jump in jumps:
        same = [
            i
            for i, k in enumerate(kept)
            if k.status == jump.status == "converged"
            and k.rising == jump.rising
            and jump.mu_lo <= k.mu_hi
            and k.mu_lo <= jump.mu_hi
        ]
        if not same:
            kept.append(jump)
        elif jump.certification == "certified" and kept[same[0]].certification != "certified":
            kept[same[0]] = jump
    return tuple(kept)


def compose_result(state: JumpSearchState) -> JumpSearchResult:
    """The result of a finished `JumpSearch` (frictiondisk.tasks.jump_search.jumps) from its
    snapshot: the jumps that stand, the headline, the windows, the grid below it, and the
    status and reason that say so."""
    found = sorted(state.found, key=lambda j: (j.mu_lo, j.mu_hi))
    # a jump that stricter numerics showed to be an artefact of the short horizon is dropped
    jumps = tuple(j for j in found if j.certification != "vanished")
    # a jump that stricter numerics moved onto another one (its re-search left its prescan
    # cell, certify.CertifiedBisection.outer) is that jump: it vanished from where it was
    jumps = _distinct(jumps)
    vanished = len(found) - len(jumps)
    scan = tuple(state.last_scan[mu] for mu in state.mus if mu in state.last_scan)
    head = state.headline
    primary = head or ([j for j in jumps if j.rising] or list(jumps) or [None])[0]
    windows = _windows(jumps, state.persist * state.tol)
    grid = None if head is None else _grid_below(state, head.mu_lo)
    unresolved = [j for j in jumps if j.status != "converged" and above_headline(j, head)]
    problems, undecided_note = problems_of(state, jumps, scan, vanished, unresolved)
    no_jump = not jumps and not problems and state.never_sticks
    high, low = state.between.high, state.between.low.replace("_", " ")
    if not jumps and not problems and not no_jump:
        problems.append(
            f"no jump: every prescan value from mu = {state.mus[0]:.6g} to "
            f"{state.mus[-1]:.6g} gave {high} (the jump lies below the prescan)"
        )
    if no_jump:
        # an answer, not a failure: mu* lies above the grid, as far as the grid can tell
        grid = _grid_below(state, math.inf)
        status = NO_JUMP
        sticks = "sticks" if state.between.is_default else f"gives {high}"
        reason = (
            f"no jump: no value from mu = {state.mus[0]:.6g} to {state.mus[-1]:.6g} "
            f"{sticks}; {grid.decided} of {grid.total} grid values decided {low} "
            f"(resolution {grid.resolution:.3g})"
        ) + motion_note(state, grid)
    elif problems:
        status, reason = "failed", "; ".join(problems)
    else:
        status = "converged"
        reason = converged_reason(state, jumps, unresolved, windows, grid, scan, vanished)
        reason += f"; {undecided_note}" if undecided_note else ""
        reason += tail_notes(state, scan, vanished)
    return JumpSearchResult(
        status,
        reason,
        jumps,
        scan,
        state.runs,
        primary,
        state.prescan_runs,
        windows,
        grid,
        tuple(run for _, run in sorted(state.checks.items())),
        state.roles,
        _grid_flag(state, grid, no_jump),
    )


def _grid_flag(state, grid, no_jump: bool) -> str:
    """Certification of the grid below the headline (of the whole grid without a jump)."""
    if state.certified and grid is not None:
        whole = (
            grid.decided == grid.total and not grid.unrefined and (no_jump or state.headline_judged)
        )
        return "certified" if whole else "uncertain"
    return "uncertain" if state.persists_nowhere else "off"
