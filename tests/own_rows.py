"""Recorded rows of the motion's own section (tests/data/own_section_<name>.npz: the fields
of kernel/records.py OWN_STEP that the evidence reads), replayed by the motion tests."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from frictiondisk.kernel.records import OWN_STEP

DATA = Path(__file__).resolve().parent / "data"


def recorded_rows(name: str) -> np.ndarray:
    """The own-section rows recorded as own_section_<name>.npz, as OWN_STEP records."""
    with np.load(DATA / f"own_section_{name}.npz") as data:
        rows = np.zeros(data["t"].shape[0], dtype=OWN_STEP)
        for field in data.files:
            rows[field] = data[field]
    return rows
