"""Every search ends: a bisection (and a certified one) driven by ask/tell with tol down to
1e-300 and random outcome patterns ends within a cap on runs and time, `converged` or
`failed` with a reason, and its replay from a journal of its answers (a resume) ends the
same way. No kernel: the outcomes come from a seeded pattern."""

from __future__ import annotations

import contextlib
import hashlib
import math
import signal

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from frictiondisk.model.search_settings import Certify
from frictiondisk.tasks.jump_search.bisection import Bisection
from frictiondisk.tasks.jump_search.bisection_settings import BisectionSettings
from frictiondisk.tasks.jump_search.certify import CertifiedBisection
from frictiondisk.tasks.jump_search.expanding import PLAIN, PREDICTED, Expanding
from frictiondisk.tasks.jump_search.jumps import JumpSearch

MAX_RUNS = 1500  # far above any search's bound (module docstring of bisection.py)
COLD = Expanding(defer=True)  # a cold find_jump point's search (find_jump/planner.py)
MAX_SECONDS = 20.0  # per search: a loop inside one call fails the test instead of hanging


class Stuck(Exception):
    pass


@contextlib.contextmanager
def no_longer_than(seconds: float):
    """Raise Stuck in this (main) thread after `seconds`: a loop that never returns fails."""

    def expire(signum, frame):
        raise Stuck(f"no answer within {seconds} s")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


def pattern(
    mu_star: float, band: float, p_undecided: float, p_flip: float, seed: int, slow: float = 0.0
):
    """A seeded outcome pattern: a jump at mu_star; within `band` of it a run is
    undetermined with probability p_undecided and flipped with p_flip (the numerics resolve
    nothing finer); within `slow` above it undetermined below the last retry level (the
    jump's slow approach); a reserve mu - mu_star (biased), or none. Deterministic per
    request."""

    def answer(request) -> dict:
        key = repr((request.mu, request.level, request.strict, seed)).encode()
        draw = int.from_bytes(hashlib.sha256(key).digest()[:8], "big") / 2.0**64
        sticks = request.mu >= mu_star
        near = abs(request.mu - mu_star) <= band
        if sticks and request.mu - mu_star <= slow and request.level < 2:
            outcome = "undetermined"
        elif near and draw < p_undecided:
            outcome = "undetermined"
        elif near and draw > 1.0 - p_flip:
            outcome = "stick_slip" if sticks else "stick"
        else:
            outcome = "stick" if sticks else "stick_slip"
        result = {"outcome": outcome, "reason": f"pattern at {request.mu!r}"}
        if seed % 3:
            result["reserve"] = request.mu - mu_star + (seed % 5 - 2) * band
        return result

    return answer


def drive(search, answer) -> tuple[list, object]:
    """Ask / tell until done; every request asked for is answered. Fails (never hangs)
    past MAX_RUNS runs, with nothing pending while not done, or past MAX_SECONDS."""
    asked = []
    with no_longer_than(MAX_SECONDS):
        while not search.done:
            requests = search.pending()
            assert requests or search.done, "not done, yet nothing to run"
            for request in requests:
                if search.done:
                    break
                search.feed(request, answer(request))
                asked.append(request)
                assert len(asked) <= MAX_RUNS, f"no end after {MAX_RUNS} runs"
        return asked, search.result()


def replay(make, journal: dict):
    """A resume: a fresh search answered from the journal of the first (nothing runs)."""
    return drive(make(), lambda request: journal[request])


def ends_and_resumes_alike(make, answer) -> tuple[list, object]:
    """Drive a fresh search to its end, then resume it from the journal of its runs: the
    resume asks for the same runs and ends the same way. Returns (asked, found)."""
    asked, found = drive(make(), answer)
    journal = {request: answer(request) for request in asked}
    again, refound = replay(make, journal)
    assert again == asked
    assert (refound.status, refound.reason) == (found.status, found.reason)
    return asked, found


tols = st.sampled_from([1e-300, 1e-200, 1e-30, 1e-17, 1e-16, 1e-15, 1e-14, 1e-12, 1e-9])
mus = st.floats(0.045, 0.29)
bands = st.sampled_from([0.0, 1e-17, 1e-15, 1e-13, 1e-10, 1e-6])
chances = st.sampled_from([0.0, 0.3, 0.7, 1.0])


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    tol=tols,
    mu_star=mus,
    band=bands,
    p_undecided=chances,
    p_flip=st.sampled_from([0.0, 0.2, 0.5]),
    seed=st.integers(0, 10**6),
    split=st.sampled_from([2, 2, 3]),
    root_finder=st.sampled_from(["itp", "bisect"]),
    expanding=st.sampled_from([PLAIN, PREDICTED]),
    max_retries=st.integers(0, 2),
)
def test_every_bisection_ends_and_its_resume_ends_alike(
    tol, mu_star, band, p_undecided, p_flip, seed, split, root_finder, expanding, max_retries
):
    answer = pattern(mu_star, band, p_undecided, p_flip, seed)
    rules = BisectionSettings(
        tol, (1e-6, 10.0), max_retries, split=split, root_finder=root_finder, expanding=expanding
    )
    _, found = ends_and_resumes_alike(lambda: Bisection((0.04, 0.3), rules), answer)
    assert found.status in ("converged", "failed") and found.reason
    if found.status == "converged":
        assert found.width <= tol * (1 + 1e-9) or "undetermined after every retry" in found.reason


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    tol=tols,
    mu_star=mus,
    band=bands,
    p_undecided=chances,
    p_flip=st.sampled_from([0.0, 0.2, 0.5]),
    seed=st.integers(0, 10**6),
    slow=st.sampled_from([0.0, 1e-11, 1e-9, 1e-7]),
    guided=st.booleans(),
    expanding=st.sampled_from([PLAIN, COLD, PREDICTED]),
)
def test_every_certified_search_ends_and_its_resume_ends_alike(
    tol, mu_star, band, p_undecided, p_flip, seed, slow, guided, expanding
):
    """The campaign's own search (find_jump: a cold, guided, certified bisection whose
    undetermined probes are deferred), also across a slow approach far wider than tol."""
    answer = pattern(mu_star, band, p_undecided, p_flip, seed, slow)

    def make():
        return CertifiedBisection(
            (0.04, 0.3),
            BisectionSettings(tol, (1e-6, 10.0), 2, expanding=expanding),
            certify=Certify(),
            guided=guided,
        )

    _, found = ends_and_resumes_alike(make, answer)
    assert found.status in ("converged", "failed") and found.reason


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    tol=tols,
    mu_star=mus,
    band=bands,
    p_undecided=chances,
    p_flip=st.sampled_from([0.0, 0.2, 0.5]),
    seed=st.integers(0, 10**6),
    stride=st.sampled_from([1, 4]),
)
def test_every_jump_search_ends_and_its_resume_ends_alike(
    tol, mu_star, band, p_undecided, p_flip, seed, stride
):
    """A prescan over a grid, then a certified bisection of every change."""
    answer = pattern(mu_star, band, p_undecided, p_flip, seed)
    grid = tuple(0.04 + 0.01 * k for k in range(26))

    def make():
        return JumpSearch(grid, tol, 2, certify=Certify(), stride=stride)

    _, found = ends_and_resumes_alike(make, answer)
    assert found.status in ("converged", "failed", "no_jump") and found.reason


@pytest.mark.parametrize("tol", [1e-300, 1e-17])
def test_a_tol_below_what_mu_resolves_fails_at_the_floor_with_the_reason(tol):
    """A clean jump (every run decided, an exact reserve) bisected past the floating-point
    resolution of mu: the bracket ends a few ulps wide, `failed`, naming why."""
    mu_star = 0.1234567890123
    asked, found = drive(
        Bisection((0.04, 0.3), BisectionSettings(tol, (1e-6, 10.0), 2)),
        pattern(mu_star, 0, 0, 0, 1),
    )
    assert found.status == "failed"
    assert "cannot be split finer than mu resolves" in found.reason
    assert f"tol {tol:.3g} cannot be reached" in found.reason
    assert found.mu_lo < mu_star <= found.mu_hi  # the bracket it reached still holds the jump
    assert found.width <= 8 * math.ulp(mu_star) * 2
    assert len(asked) < 80  # ~ log2(0.26 / ulp) halvings at worst, fewer with the reserve


def test_the_numerics_resolution_ends_a_search_before_tol():
    """`resolution`: a bracket narrower than the numerics resolve is not split again."""
    rules = BisectionSettings(1e-14, (1e-6, 10.0), 2, resolution=1e-9)
    asked, found = drive(Bisection((0.04, 0.3), rules), pattern(0.1234567890123, 0, 0, 0, 0))
    assert found.status == "failed"
    assert "the numerics' resolution 1e-09" in found.reason
    assert 1e-9 / 2 < found.width <= 1e-9


def test_an_undecided_mu_is_never_run_again_at_its_last_level():
    """The straddle around an undecided mu, at a tol far below an ulp: its probes would
    land on the undecided mu itself (re-run for ever, as a resume from a journal did);
    the search fails instead."""
    asked, found = drive(
        Bisection((0.04, 0.3), BisectionSettings(1e-300, (1e-6, 10.0), 1)),
        pattern(0.12, 1e-6, 1.0, 0.0, 0),
    )
    assert found.status == "failed"
    assert len(asked) == len(set(asked))  # no request is asked twice
