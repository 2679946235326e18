"""Which cells of a motion map to run: a coarse lattice first, refined where neighbours differ.

The map's grid (1 or 2 keys) is the finest it can show. `CellRefinement` runs every
`stride`-th value of each axis (and the last), which cuts the grid into blocks whose
corners are run. Once nothing is waiting (`refine`), every block whose run cells (corners,
and any cell on its edges or inside that a neighbouring block had run) all show one and
the same decided motion is *uniform*: its other cells are not run but inferred from it,
and flagged so in results.nc. Every other block (two motions, or an `undetermined` cell)
is split at the middle of each axis it spans by 2 or more, and the new corners run. The
refinement ends when every block is uniform or one grid step wide: a boundary between
two motions is then resolved to the grid step, as a dense map would show it.

A cell's *motion* here is what the planner says it is (its run's outcome, or the leading
motion of its sampled start), so this module knows nothing of runs. The cells asked for
depend on the motions only, never on the order they arrive in. Pure Python.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

from frictiondisk.verdict.outcomes import UNDETERMINED

Cell = tuple[int, ...]
Block = tuple[tuple[int, int], ...]  # per axis (first index, last index), both run


def coarse_indices(n: int, stride: int) -> list[int]:
    """Every stride-th index of an axis of n values, and the last."""
    return sorted(set(range(0, n, stride)) | {n - 1})


class CellRefinement:
    """The cells to run, grown block by block as their motions come back (`settle`)."""

    def __init__(self, shape: Sequence[int], strides: Sequence[int]):
        if len(shape) != len(strides) or not shape or min(shape) < 1 or min(strides) < 1:
            raise ValueError(f"bad map shape {tuple(shape)} or strides {tuple(strides)}")
        self.shape = tuple(shape)
        axes = [coarse_indices(n, s) for n, s in zip(shape, strides, strict=True)]
        self.blocks: list[Block] = [
            tuple(zip(a, a[1:], strict=False)) if len(a) > 1 else ((a[0], a[0]),) for a in axes
        ]
        self.blocks = [tuple(parts) for parts in itertools.product(*self.blocks)]
        self.wanted: set[Cell] = {corner for b in self.blocks for corner in corners(b)}
        self.motions: dict[Cell, str] = {}  # cell -> the motion of its settled run(s)

    def settle(self, cell: Cell, motion: str) -> None:
        """Record the motion of a wanted cell."""
        if cell not in self.wanted:
            raise ValueError(f"cell {cell} was not asked for")
        self.motions[cell] = motion

    @property
    def waiting(self) -> set[Cell]:
        """Wanted cells without a motion yet."""
        return self.wanted - self.motions.keys()

    def refine(self) -> set[Cell]:
        """Once nothing is waiting: split every block that is neither uniform nor one step
        wide, and return the new cells to run (added to `wanted`); empty when done."""
        if self.waiting:
            return set()
        new_blocks: list[Block] = []
        for block in self.blocks:
            if self.uniform_motion(block) is not None or not splittable(block):
                new_blocks.append(block)
            else:
                new_blocks += split(block)
        self.blocks = new_blocks
        new = {c for b in new_blocks for c in corners(b)} - self.wanted
        self.wanted |= new
        return new

    def uniform_motion(self, block: Block) -> str | None:
        """The one decided motion of every run cell in the closed block, else None."""
        seen = {m for cell, m in self.motions.items() if inside(cell, block)}
        if len(seen) == 1 and UNDETERMINED not in seen:
            return seen.pop()
        return None

    def inferred(self) -> dict[Cell, str]:
        """Every cell not run that lies in a uniform block -> that block's motion (a cell
        on the edge of two uniform blocks: both share a run corner, so they agree)."""
        found: dict[Cell, str] = {}
        for block in self.blocks:
            motion = self.uniform_motion(block)
            if motion is None:
                continue
            ranges = [range(lo, hi + 1) for lo, hi in block]
            for cell in itertools.product(*ranges):
                if cell not in self.motions:
                    found.setdefault(cell, motion)
        return found


def corners(block: Block) -> set[Cell]:
    return set(itertools.product(*block))


def inside(cell: Cell, block: Block) -> bool:
    return all(lo <= i <= hi for i, (lo, hi) in zip(cell, block, strict=True))


def splittable(block: Block) -> bool:
    """A block that spans 2 or more grid steps along some axis."""
    return any(hi - lo >= 2 for lo, hi in block)


def split(block: Block) -> list[Block]:
    """The block cut at the middle of every axis it spans by 2 or more steps."""
    parts = []
    for lo, hi in block:
        if hi - lo >= 2:
            mid = (lo + hi) // 2
            parts.append(((lo, mid), (mid, hi)))
        else:
            parts.append(((lo, hi),))
    return [tuple(p) for p in itertools.product(*parts)]
