"""Contact layouts of the disk: body-frame points and their shares of the contact totals.

A layout is N points p_i [m] and positive shares s_i. Contact i carries the fraction
w_i = s_i / sum(s) of the total normal force, stiffness and damping (kernel/model.py).

* ring:    N points evenly on one circle, equal shares (the paper's layout).
* annulus: a facing inner_radius <= r <= outer_radius under uniform pressure. It is cut
  into M concentric bands of equal width, M ~ sqrt(N width / (2 pi mean radius)), so the
  cells are about as long as they are wide; band j gets n_j points in proportion to its
  area (largest remainder, at least one each), evenly spaced and shifted by half a cell on
  every other band. Each point's share is the area of its cell, so the contact pressure is
  uniform, and it sits at the friction radius of its band,
      rho_j = 2/3 (r_out^3 - r_in^3) / (r_out^2 - r_in^2),
  so that the torque of the band sliding as a whole is the continuous facing's exactly.
* points:  explicit positions and shares.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["annulus", "annulus_bands", "layout", "relative_weights", "ring"]


def ring(n: int, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """N points on a circle of `radius` [m] at angles 2 pi i / N; equal shares."""
    angles = 2.0 * np.pi * np.arange(n) / n
    positions = radius * np.column_stack((np.cos(angles), np.sin(angles)))
    return positions, np.ones(n)


def annulus_bands(n: int, inner: float, outer: float) -> list[int]:
    """Points per band (inner to outer) of an N-point annulus (module docstring)."""
    width = outer - inner
    mean = 0.5 * (inner + outer)
    bands = max(1, min(n, round(math.sqrt(n * width / (2.0 * math.pi * mean)))))
    edges = inner + width * np.arange(bands + 1) / bands
    areas = edges[1:] ** 2 - edges[:-1] ** 2
    ideal = n * areas / areas.sum()
    counts = np.maximum(1, np.floor(ideal).astype(int))
    # largest remainder, then take back from the bands most above their ideal count
    while counts.sum() < n:
        counts[int(np.argmax(ideal - counts))] += 1
    while counts.sum() > n:
        counts[int(np.argmax(np.where(counts > 1, counts - ideal, -np.inf)))] -= 1
    return [int(c) for c in counts]


def annulus(n: int, inner: float, outer: float) -> tuple[np.ndarray, np.ndarray]:
    """N points on the annulus inner <= r <= outer [m]; shares = cell areas [m^2]."""
    counts = annulus_bands(n, inner, outer)
    bands = len(counts)
    edges = inner + (outer - inner) * np.arange(bands + 1) / bands
    positions, shares = [], []
    for j, count in enumerate(counts):
        r0, r1 = edges[j], edges[j + 1]
        rho = 2.0 / 3.0 * (r1**3 - r0**3) / (r1**2 - r0**2)
        angles = 2.0 * np.pi * (np.arange(count) + 0.5 * (j % 2)) / count
        positions.append(rho * np.column_stack((np.cos(angles), np.sin(angles))))
        shares.append(np.full(count, math.pi * (r1**2 - r0**2) / count))
    return np.vstack(positions), np.concatenate(shares)


def layout(
    kind: str,
    n: int,
    ring_radius: float | None = None,
    inner_radius: float | None = None,
    outer_radius: float | None = None,
    positions=None,
    weights=None,
) -> tuple[np.ndarray, np.ndarray]:
    """(positions (N, 2) [m], shares) of a disk's `contact.layout` `kind` (ring, annulus or
    points) with its keys; explicit points without weights share equally."""
    if kind == "annulus":
        return annulus(n, inner_radius, outer_radius)
    if kind == "points":
        shares = np.ones(n) if weights is None else np.array(weights)
        return np.array(positions, dtype=float).reshape(-1, 2), shares
    return ring(n, ring_radius)


def relative_weights(shares: np.ndarray) -> np.ndarray:
    """Shares scaled to mean 1, i.e. N w_i. Equal shares give exactly 1.0 each, so a ring
    packs to the same bits as the per-contact totals c/N, beta/N, F_n/N."""
    shares = np.asarray(shares, dtype=float)
    return shares * (shares.shape[0] / shares.sum())
