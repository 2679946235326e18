"""What a bisection asks for and answers with: one run's request, a run and its outcome,
and the located jump. Plain values, shared by the searches (bisection, certify, jumps,
trace) and the engine that runs them. Pure Python."""

from __future__ import annotations

import dataclasses
from typing import Any

from frictiondisk.verdict.outcomes import UNDETERMINED


@dataclasses.dataclass(frozen=True)
class RunRequest:
    """One simulation the bisection needs: friction coefficient, retry level and
    certification level.

    The horizon of the run is the base horizon times horizon_factor ** level; a
    certification level `strict` > 0 tightens the numerics further (certify.py). `reach`
    retry levels are covered by one run: its horizon budget reaches as far as the run at
    level + reach would, so that it need not be restarted from t = 0 to look further (a
    certification check, certify.py)."""

    mu: float
    level: int = 0
    mode: str | None = None  # numerics.mode of the run; None: the point's own
    strict: int = 0  # certification level of the numerics (0: the point's own)
    watch: float = 0.0  # watch (observe) until this time before extrapolating [s] (certify.py)
    reach: int = 0  # retry levels whose horizon budget this one run covers at once
    # a certification check with the point's own integrator instead of certify.method
    # (after certify.method's run of it failed: certify.py)
    own_method: bool = False


@dataclasses.dataclass(frozen=True)
class RunRecord:
    request: RunRequest
    result: dict[str, Any]  # SimulationResult.summary()

    @property
    def outcome(self) -> str:
        return self.result["outcome"]


@dataclasses.dataclass(frozen=True)
class BisectionResult:
    """The located jump: a bracket with its midpoint, never a bare number."""

    status: str  # "converged" or "failed"
    reason: str
    mu_lo: float  # NaN if the bracket was never established
    mu_hi: float
    runs: tuple[RunRecord, ...]
    contradictions: tuple[tuple[float, float], ...]  # run pairs against one jump (see below)
    rising: bool = True  # not stick at mu_lo, stick at mu_hi (False: the other way round)
    certification: str = "off"  # model.search_settings.CERTIFICATION_FLAGS
    strict: int = 0  # certification level of the numerics behind mu_lo and mu_hi

    @property
    def mu_star(self) -> float:
        return 0.5 * (self.mu_lo + self.mu_hi)

    @property
    def width(self) -> float:
        return self.mu_hi - self.mu_lo

    @property
    def monotone(self) -> bool:
        return not self.contradictions

    def end_result(self, which: str) -> dict[str, Any] | None:
        """The decisive run at mu_lo or mu_hi (its last retry level)."""
        mu = self.mu_lo if which == "lo" else self.mu_hi
        found = None
        for run in self.runs:
            if run.request.mu == mu and run.outcome != UNDETERMINED:
                found = run.result
        return found
