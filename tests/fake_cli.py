"""`python tests/fake_cli.py ARGS...`: the frictiondisk command line with the fake simulate
of tests/fake_simulate.py, each run sleeping FAKE_SIMULATE_DELAY_S seconds (default 0.003).
A campaign that a test stops with a real signal takes seconds, not the kernel's minutes;
the signal handlers, the driver, the journal and the files are the real ones."""

from __future__ import annotations

import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from fake_simulate import install  # noqa: E402


class _Setter:
    @staticmethod
    def setattr(target, name, value):
        setattr(target, name, value)


if __name__ == "__main__":
    install(_Setter, delay=float(os.environ.get("FAKE_SIMULATE_DELAY_S", "0.003")))
    from frictiondisk.cli.entry import run

    run()
