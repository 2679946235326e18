"""The benchmarks' one harness: each benchmark measures its baseline in the same run, prints
ratios, and writes every number it measured as JSON.

Every benchmark here times its own baseline beside what it measures (numba against scipy
Radau, 2 workers against 1, the search against plain bisection, ...) in the same process
and the same minutes, so a shared, noisy machine slows both alike and the ratio keeps its
meaning where a bare wall time would not. A benchmark keeps its numbers in a `Record`:

    record = Record("campaign")
    record.ratio("pin line: speed-up 2 workers over 1", wall_1, wall_2, target=">= 1.7")
    record.number("pin line: wall, 1 worker", wall_1, "s")
    record.write()      # out/bench/campaign.json (BENCH_OUT=DIR: DIR/campaign.json)

The JSON holds the date, the versions (frictiondisk, kernel), the machine (cores, load
average before and after) and each number with its unit and target, so that runs on
different days or machines can be compared by what they measured, not by what they printed.
"""

from __future__ import annotations

import datetime
import json
import os
import platform
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

OUT = Path(os.environ.get("BENCH_OUT", "out/bench"))


def best_of(run: Callable[[], Any], repeats: int) -> tuple[float, Any]:
    """The smallest wall time [s] of `repeats` calls of run(), and the last call's value."""
    walls, value = [], None
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        value = run()
        walls.append(time.perf_counter() - t0)
    return min(walls), value


class Record:
    """The numbers of one benchmark run (module docstring)."""

    def __init__(self, name: str):
        self.name = name
        self.numbers: dict[str, dict[str, Any]] = {}
        self.started = datetime.datetime.now(datetime.UTC)
        self.load_before = os.getloadavg()[0]

    def number(self, key: str, value: float, unit: str = "", target: str | None = None) -> float:
        """Keep a measured number (unit: 's', 'ms', '1', ...; target: e.g. '<= 0.6')."""
        self.numbers[key] = {"value": _plain(value), "unit": unit, "target": target}
        return value

    def ratio(
        self, key: str, numerator: float, denominator: float, target: str | None = None
    ) -> float:
        """Keep numerator / denominator, both measured in this run, and print it."""
        value = numerator / denominator if denominator else float("nan")
        self.numbers[key] = {
            "value": _plain(value),
            "unit": "1",
            "target": target,
            "of": [_plain(numerator), _plain(denominator)],
        }
        shown = f"   (target {target})" if target else ""
        print(f"  ratio {key}: {value:.3g}{shown}", flush=True)
        return value

    def write(self, path: Path | None = None) -> Path:
        """Write the record as JSON (default OUT/<name>.json) and say where."""
        path = Path(path) if path is not None else OUT / f"{self.name}.json"
        path.parent.mkdir(parents=True, exist_ok=True)
        data = {
            "benchmark": self.name,
            "argv": sys.argv[1:],
            "started": self.started.isoformat(timespec="seconds"),
            "versions": _versions(),
            "machine": {
                "cpus": os.cpu_count(),
                "platform": platform.platform(),
                "load_before": self.load_before,
                "load_after": os.getloadavg()[0],
            },
            "numbers": self.numbers,
        }
        path.write_text(json.dumps(data, indent=1) + "\n")
        print(f"numbers: {path}", flush=True)
        return path


def _versions() -> dict[str, str]:
    from frictiondisk.store.journal_entry import kernel_version
    from frictiondisk.version import __version__

    return {"frictiondisk": __version__, "kernel": kernel_version(), "python": sys.version}


def _plain(value: Any) -> Any:
    """A number as JSON takes it (numpy scalars included; NaN as null)."""
    if hasattr(value, "item"):
        value = value.item()
    if isinstance(value, float) and value != value:
        return None
    return value
