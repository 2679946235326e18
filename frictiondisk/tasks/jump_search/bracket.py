"""What a bisection knows so far: its bracket, every run and its verdict. Pure Python.

`BracketState` is the mutable half of a bisection (bisection.py): the bracket
[lo, hi], the phase (`check` its ends, `bisect`, `converged`), the round (bumped whenever
the bracket or the phase changes), every run in the order it came back, the side of each
decided mu, the retry level to ask for next, the schedule key of every request (the order
runs are reported in, fixed by the schedule, never by the order results arrive in), the
friction reserve of each decided run, and the failure that ended the search. The probe
strategies (itp.py, straddle.py, deferral.py) read it; the bisection moves it.
"""

from __future__ import annotations

from frictiondisk.tasks.jump_search.runs import RunRecord, RunRequest
from frictiondisk.verdict.outcomes import STICK

ScheduleKey = tuple[int, int, float]  # (round, level, mu) when a request was first asked for


class BracketState:
    """The bracket of one bisection and every verdict behind it (module docstring)."""

    def __init__(self, lo: float, hi: float):
        self.lo = lo
        self.hi = hi
        self.phase = "check"
        self.round = 0  # bumped whenever the bracket or the phase changes
        self.runs: list[RunRecord] = []
        self.known: dict[float, str] = {}  # mu -> stick / not-stick (determined runs only)
        self.level: dict[float, int] = {}  # mu -> retry level to ask for next
        self.issued: dict[RunRequest, ScheduleKey] = {}
        self.signal: dict[float, float] = {}  # mu -> friction reserve (decided runs, finite)
        # (schedule key, mu) of the decided runs: "the last two" never depend on timing
        self.decided: list[tuple[ScheduleKey, float]] = []
        self.failure: str | None = None

    @property
    def done(self) -> bool:
        return self.failure is not None or self.phase == "converged"

    def issue(self, request: RunRequest) -> None:
        """Note a request's schedule key the first time it is asked for."""
        self.issued.setdefault(request, (self.round, request.level, request.mu))

    def learn(self, request: RunRequest, side: str, signal: float | None) -> None:
        """A decided run: its side, its place among the decided runs, its reserve."""
        self.known[request.mu] = side
        self.decided.append((self.issued[request], request.mu))
        if signal is not None:
            self.signal[request.mu] = signal

    def move(self, lo: float | None = None, hi: float | None = None, phase=None) -> None:
        """A new round: the bracket [lo, hi] and the phase where given."""
        if lo is not None:
            self.lo, self.hi = lo, hi
        if phase is not None:
            self.phase = phase
        self.round += 1

    def fail(self, reason: str) -> None:
        self.failure = reason

    def sticks(self, mu: float) -> bool:
        """A decided mu lies on the boundary's high (stick) side."""
        return self.known[mu] == STICK

    def agrees(self, mu: float) -> bool:
        """mu carries a reserve whose sign agrees with its verdict (> 0: stick)."""
        return mu in self.signal and (self.signal[mu] > 0) == self.sticks(mu)

    def holds(self, end: float, rising: bool) -> bool:
        """A decided bracket end gave the verdict its side of the jump should give."""
        return self.sticks(end) == ((end == self.hi) if rising else (end == self.lo))

    def outcome_at(self, mu: float) -> str:
        """The outcome of the last run at mu ("nothing" where none ran)."""
        for run in reversed(self.runs):
            if run.request.mu == mu:
                return run.outcome
        return "nothing"

    def ordered_runs(self) -> tuple[RunRecord, ...]:
        """Every run in the order requested, not the order results arrived: independent
        of timing."""
        return tuple(sorted(self.runs, key=lambda run: self.issued[run.request]))

    def contradictions(self, rising: bool) -> tuple[tuple[float, float], ...]:
        """Pairs of runs that contradict a single jump of this direction: (stick mu, larger
        not-stick mu) for a rising jump, the reverse for a falling one."""
        sticks = sorted(mu for mu, side in self.known.items() if side == STICK)
        nots = sorted(mu for mu, side in self.known.items() if side != STICK)
        if rising:
            return tuple((s, n) for s in sticks for n in nots if s < n)
        return tuple((n, s) for s in sticks for n in nots if n < s)
