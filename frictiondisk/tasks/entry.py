"""The plug-in of a task (`TaskEntry`, after xarray's `BackendEntrypoint`): what the shared
machinery (the campaign loader, the engine, the stores' writers, `run`/`status`/`plot`)
asks of a task. One subclass per task package (its entry.py), listed once in registry.py;
nothing outside the registry names a task. Heavy parts (planners, datasets, figures) are
imported only when asked for, so that loading a campaign stays cheap."""

from __future__ import annotations

from typing import Any, ClassVar


class TaskEntry:
    """A task: its campaign-file section (`spec`) and the capabilities the shared machinery
    reads instead of the task's name. Subclasses set the class attributes and override the
    methods that apply to them."""

    spec: ClassVar[type]  # the section's schema (a tasks.spec.TaskSpec subclass)
    summary: ClassVar[str]  # one line: what the task does
    # docs/reference.md: further tables (title, intro, model) of values inside the section
    reference_tables: ClassVar[tuple[tuple[str, str, type], ...]] = ()
    # a journal of its runs (a task without one keeps its files as its record, and is
    # asked `files_current` before it runs)
    journaled: ClassVar[bool] = True
    # run alone (not beside other campaigns), it runs in this process without Dask
    # (`run_alone`)
    runs_alone: ClassVar[bool] = False

    # `plot --runs` overlays its runs (runs.nc) on its figure
    shows_runs: ClassVar[bool] = False
    # `plot --boundary DIR` draws the campaign in DIR on its figure, if it is one of these
    # tasks (a basin map: a find_jump's mu* contour; a motion map: trace curves)
    boundary_tasks: ClassVar[tuple[str, ...]] = ()
    # its results.nc holds a bisected mu* at every point of its grid (a boundary for a basin
    # map; a campaign the accuracy study can bisect)
    mu_star_grid: ClassVar[bool] = False
    # the files of DIR its figure reads besides results.nc (and runs.nc for --runs)
    figure_files: ClassVar[tuple[str, ...]] = ()
    # few runs in flight for long (a trace): run beside other campaigns it goes first, so
    # that their runs fill round it (cli/gallery.py)
    starts_first: ClassVar[bool] = False

    def planner(self, campaign: Any) -> Any:
        """The campaign's planner (a frictiondisk.tasks.protocol.Planner)."""
        raise NotImplementedError

    def files_current(self, out_dir: Any) -> bool:
        """A task without a journal: whether its files in out_dir are complete (then its
        planner is told `already_written`)."""
        return False

    def run_alone(self, campaign: Any, out_dir: Any) -> tuple[int, Any]:
        """A task that `runs_alone`: run the campaign here, write its files; returns the
        runs computed and the path of the file that holds its runs."""
        raise NotImplementedError

    def figure(
        self,
        results: Any,
        runs: Any = None,
        *,
        show_runs: bool = False,
        boundary: tuple[Any, ...] = (),
        files: dict[str, Any] | None = None,
    ) -> Any:
        """The figure of the campaign (a matplotlib Figure) from its results.nc; `runs`:
        runs.nc (with `shows_runs`), `boundary`: the results.nc of campaigns of its
        `boundary_tasks` to draw on it, `files`: the Datasets of `figure_files` by name. ValueError
        saying what is wrong ("runs ..." or "boundary ..." for those inputs)."""
        raise NotImplementedError

    def run_lines(self, results: Any) -> list[str]:
        """What `run` and `resume` print under a finished campaign: its answer, read from
        its results.nc."""
        return []

    def status_lines(self, results: Any, complete: bool) -> list[str]:
        """What `status` prints under the results.nc line, of a complete campaign or of
        its partial results."""
        return []

    def size(self, task: Any) -> tuple[int, str]:
        """(runs per point without retries, the fields that set the campaign's size) of the
        section `task`: what engine/budget.py counts before a campaign starts."""
        return 1, self.name

    @property
    def name(self) -> str:
        """The task's name: its key in a campaign file (`spec.kind`)."""
        return self.spec.kind

    def __repr__(self) -> str:
        return f"<task {self.name}>"
