"""Progress on stderr: a tqdm bar on a terminal, plain log lines everywhere else.

A bar redraws itself with carriage returns, which a log file or a batch scheduler's
output keeps as one unreadable line. Off a terminal `progress_bar` returns `LogLines`,
which takes the same calls and prints one line every `every` seconds (and at the end):

    demo_line: 3/5 point (60%), 12.4 s, in_flight=2, runs=17
"""

from __future__ import annotations

import sys
import time
from typing import Any, TextIO

LOG_EVERY = 10.0  # seconds between two progress lines off a terminal


def progress_bar(
    total: int,
    desc: str,
    unit: str,
    initial: int = 0,
    stream: TextIO | None = None,
    disable: bool = False,
):
    """A tqdm bar if `stream` (stderr) is a terminal, else LogLines; None if disabled."""
    if disable:
        return None
    stream = stream or sys.stderr
    if _is_terminal(stream):
        from tqdm import tqdm

        return tqdm(
            total=total, initial=initial, unit=unit, desc=desc, file=stream, dynamic_ncols=True
        )
    return LogLines(total, desc, unit, initial, stream)


def _is_terminal(stream: TextIO) -> bool:
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


class LogLines:
    """The subset of tqdm's interface the campaign runner and the accuracy study use."""

    def __init__(
        self,
        total: int,
        desc: str,
        unit: str,
        initial: int = 0,
        stream: TextIO | None = None,
        every: float = LOG_EVERY,
    ):
        self.total = total
        self.desc = desc
        self.unit = unit
        self.n = initial
        self.stream = stream or sys.stderr
        self.every = every
        self._postfix = ""
        self._t0 = time.perf_counter()
        self._last = -float("inf")
        self._last_n: int | None = None

    def set_postfix(self, refresh: bool = False, **values: Any) -> None:
        self._postfix = ", ".join(f"{k}={v}" for k, v in sorted(values.items()))

    def set_postfix_str(self, text: str, refresh: bool = False) -> None:
        self._postfix = text

    def update(self, n: int = 1) -> None:
        self.n += n
        self.refresh()

    def refresh(self) -> None:
        now = time.perf_counter()
        if now - self._last >= self.every:
            self._emit(now)

    def close(self) -> None:
        if self._last_n != self.n:
            self._emit(time.perf_counter())

    def _emit(self, now: float) -> None:
        self._last, self._last_n = now, self.n
        share = f" ({self.n / self.total:.0%})" if self.total else ""
        line = f"{self.desc}: {self.n}/{self.total} {self.unit}{share}, {now - self._t0:.1f} s"
        if self._postfix:
            line += f", {self._postfix}"
        print(line, file=self.stream, flush=True)
