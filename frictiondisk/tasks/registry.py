"""The registry of tasks: name -> entry (tasks/entry.py), in the order a campaign file's
schema, its messages and docs/reference.md list them. The one place that names a task:
adding a task is adding its package and one line here."""

from __future__ import annotations

from frictiondisk.tasks.basin.entry import BasinEntry
from frictiondisk.tasks.entry import TaskEntry
from frictiondisk.tasks.find_jump.entry import FindJumpEntry
from frictiondisk.tasks.map.entry import MapEntry
from frictiondisk.tasks.scan.entry import ScanEntry
from frictiondisk.tasks.trace.entry import TraceEntry
from frictiondisk.tasks.trajectory.entry import TrajectoryEntry

TASKS: dict[str, TaskEntry] = {
    entry.name: entry
    for entry in (
        FindJumpEntry(),
        ScanEntry(),
        TrajectoryEntry(),
        BasinEntry(),
        TraceEntry(),
        MapEntry(),
    )
}


def entry_for(name: str) -> TaskEntry:
    """The entry of the task `name`; KeyError naming the known tasks if there is none."""
    try:
        return TASKS[name]
    except KeyError:
        raise KeyError(f"no task {name!r}; the tasks are {', '.join(TASKS)}") from None
