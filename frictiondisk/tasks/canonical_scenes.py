"""A run's canonical scene, made once between the driver and its planner. Pure Python.

The driver makes a run's canonical scene for its journal key and hands it to the planner
(`remember`); the planner sends it to a worker with the run's job (`for_job`). Where the
job is made first, the scene made for it is kept until the driver keys the run
(`for_key`). Either way a run's scene is made once; a scene dropped (`forget`) is only
made again if asked for.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable


class CanonicalScenes:
    """The canonical scenes of a planner's runs, by run (module docstring)."""

    def __init__(self) -> None:
        self._keyed: dict[Hashable, dict] = {}  # made for a key, until the run's job
        self._sent: dict[Hashable, dict] = {}  # made for a job, until the run is keyed

    def remember(self, run: Hashable, canonical: dict) -> None:
        """The scene the driver made for run's key, for its job."""
        self._keyed[run] = canonical

    def for_job(self, run: Hashable, make: Callable[[], dict]) -> dict:
        """The run's scene for its job: the driver's, or made now and kept for its key."""
        canonical = self._keyed.pop(run, None)
        if canonical is None:
            canonical = self._sent[run] = make()
        return canonical

    def for_key(self, run: Hashable, make: Callable[[], dict]) -> dict:
        """The run's scene for its key: the one its job was sent with, or made now."""
        canonical = self._sent.pop(run, None)
        return make() if canonical is None else canonical

    def forget(self, run: Hashable) -> None:
        """Drop the run's scene (its result is known, or it will not be keyed)."""
        self._keyed.pop(run, None)
        self._sent.pop(run, None)
