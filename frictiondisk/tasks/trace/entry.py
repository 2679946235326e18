"""The `trace` task's plug-in (registry.py lists it)."""

from __future__ import annotations

from typing import Any

from frictiondisk.tasks.entry import TaskEntry
from frictiondisk.tasks.trace.spec import Trace


class TraceEntry(TaskEntry):
    spec = Trace
    summary = "follow every jump curve through a (key, mu) plane"
    shows_runs = True
    starts_first = True  # one correction per curve end in flight

    def size(self, task: Trace) -> tuple[int, str]:
        """The first look alone; the curves' runs depend on what it finds."""
        return (
            task.first_look.keys * task.first_look.mu,
            "trace.first_look.keys, trace.first_look.mu",
        )

    def planner(self, campaign: Any) -> Any:
        from frictiondisk.tasks.trace.planner import TracePlanner

        return TracePlanner(campaign)

    def figure(self, results, runs=None, *, show_runs=False, boundary=(), files=None):
        from frictiondisk.tasks.trace.figure import plot_trace

        return plot_trace(results, runs, show_runs=show_runs)

    def run_lines(self, results) -> list[str]:
        """The uncertain points and what failed (the curves: `status`)."""
        from frictiondisk.tasks.trace.table import trace_closing

        return trace_closing(results)

    def status_lines(self, results, complete: bool) -> list[str]:
        from frictiondisk.tasks.trace.table import trace_closing, trace_lines

        return trace_lines(results) + trace_closing(results)
