"""Which initial state sample j of a point gets.

Sample j of a point is fixed by the campaign's `seed`, the point's varied values and j
alone: the draws of each sampled key come in blocks of `BLOCK` from numpy's
`SeedSequence(seed, spawn_key=(point words, key words, block))`, so a sample does not change
with the batch size, the sample count, the other sampled keys or the other points.

`task` is any spec with `seed` and `sample` (dotted initial-state key -> Distribution).
"""

from __future__ import annotations

import hashlib
import json

import numpy as np

BLOCK = 1024  # draws per SeedSequence block


def _words(text: str) -> tuple[int, ...]:
    """Four 32-bit words of the sha256 of `text` (a SeedSequence spawn key part)."""
    digest = hashlib.sha256(text.encode()).digest()[:16]
    return tuple(int.from_bytes(digest[i : i + 4], "little") for i in range(0, 16, 4))


def point_words(coords: dict[str, float]) -> tuple[int, ...]:
    """Spawn-key words of a point: a hash of its varied keys and values (not its index, so a
    point keeps its samples when other points are added to the campaign)."""
    return _words(json.dumps({k: repr(float(v)) for k, v in sorted(coords.items())}))


def draw_block(task, coords: dict[str, float], key: str, block: int) -> np.ndarray:
    """Draws BLOCK * block ... BLOCK * (block + 1) - 1 of sampled `key` at a point."""
    dist = task.sample[key]
    seq = np.random.SeedSequence(task.seed, spawn_key=(*point_words(coords), *_words(key), block))
    rng = np.random.default_rng(seq)
    if dist.kind == "uniform":
        return rng.uniform(dist.a, dist.b, BLOCK)
    return rng.normal(dist.a, dist.b, BLOCK)


def sample_values(
    task, coords: dict[str, float], j: int, blocks: dict[tuple[str, int], np.ndarray] | None = None
) -> dict[str, float]:
    """The sampled initial-state values of sample j at the point of `coords`; `blocks`
    keeps the draw blocks of this point between calls ((key, block) -> draws)."""
    blocks = {} if blocks is None else blocks
    out = {}
    for key in task.sample:
        block = (key, j // BLOCK)
        if block not in blocks:
            blocks[block] = draw_block(task, coords, key, block[1])
        out[key] = float(blocks[block][j % BLOCK])
    return out
