"""The section of the exact Coulomb pin (frictiondisk/verdict/rim_approach.py): a creep onto
the rim of the sticking disc against a stick-slip cycle, on gap sequences of known limit."""

import numpy as np

from frictiondisk.verdict.params import VerdictParams
from frictiondisk.verdict.rim_approach import repeats, rim_limit

VP = VerdictParams()

CYCLE_TOL = 1e-6  # [m]


def tangent_map(d0, c, n, limit=0.0):
    """d' = d - c (d - limit)^2: a tangent fixed point at `limit` [m], reached as 1 / (c n)."""
    gaps = [d0]
    for _ in range(n - 1):
        gaps.append(gaps[-1] - c * (gaps[-1] - limit) ** 2)
    return np.array(gaps)


def geometric(d0, limit, ratio, n):
    return limit + (d0 - limit) * ratio ** np.arange(n)


def test_a_tangent_approach_to_the_rim_is_onto_the_rim_once_within_the_cycle_tolerance():
    gaps = tangent_map(1e-5, 2e4, 400)  # the study's pin 1/48: c = 2.4e4 1/m
    assert gaps[-1] < CYCLE_TOL
    onto, evidence = rim_limit(gaps, CYCLE_TOL, VP)
    assert onto, evidence
    assert not repeats(gaps, CYCLE_TOL, VP)[0]  # 1 - ratio shrinks with the gap: no cycle
    assert not rim_limit(gaps[:40], CYCLE_TOL, VP)[0]  # still microns off the rim: not yet


def test_a_tangent_approach_to_a_gap_off_the_rim_is_not_onto_the_rim():
    limit = 0.3 * CYCLE_TOL  # a cycle sticking 0.3 um outside the disc
    gaps = tangent_map(1e-5, 2e4, 3000, limit)
    assert gaps[-1] < CYCLE_TOL
    onto, evidence = rim_limit(gaps, CYCLE_TOL, VP)
    assert not onto, evidence


def test_a_geometric_approach_to_a_cycle_is_a_cycle_and_not_onto_the_rim():
    gaps = geometric(0.05, 0.09, 0.87, 120)  # the default pin at mu 0.11, moving outwards
    assert repeats(gaps, CYCLE_TOL, VP)[0]
    assert not rim_limit(gaps, CYCLE_TOL, VP)[0]
    falling = geometric(0.09, 0.05, 0.87, 120)
    assert repeats(falling, CYCLE_TOL, VP)[0]
    assert not rim_limit(falling, CYCLE_TOL, VP)[0]  # its limit is far off the rim
    assert not repeats(falling[:40], CYCLE_TOL, VP)[0]  # remainder still above the tolerance


def test_onsets_that_scatter_within_the_tolerance_off_the_rim_repeat():
    rng = np.random.default_rng(0)
    gaps = 0.02 + 1e-8 * rng.standard_normal(64)
    assert repeats(gaps, CYCLE_TOL, VP)[0]
    assert not repeats(1e-8 * np.abs(rng.standard_normal(64)), CYCLE_TOL, VP)[0]  # on the rim
    assert repeats(np.full(32, 0.02), CYCLE_TOL, VP)[0]  # repeated to the last bit
