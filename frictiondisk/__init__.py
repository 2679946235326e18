"""frictiondisk: bifurcation tracking for the radial dynamics of friction disks.

The public API (every name imports its machinery only when called, so `import frictiondisk`
stays cheap)::

    from frictiondisk import load_scene, simulate, load_campaign, run_campaign, open_results

    scene = load_scene("campaigns/demo_pin.yaml", ["params.mu=0.13"])
    result = simulate(scene)                 # result.outcome, result.reason, result.summary()
    campaign = load_campaign("campaigns/demo_line.yaml")   # or a dict: the parsed YAML
    run_campaign(campaign, "out/demo_line")  # resumes if the directory holds a journal
    run_campaigns(["campaigns/fig07_pin_xms.yaml", "campaigns/fig08_pin_x0.yaml"], "out/figs")
    results = open_results("out/demo_line")  # results.nc as an xarray.Dataset
    fig = plot_results("out/demo_line")      # what `frictiondisk plot DIR` draws
    fig = plot_orbit(simulate(scene, record=True, dt_out=0.05), scene)

Everything else lives in the packages below, in layer order (docs/architecture.md):
model, kernel, verdict, simulation, store, figures, tasks (one package per task, found
through tasks/registry.py), engine, studies, cli. docs/model.md describes the model.
"""

from __future__ import annotations

from os import PathLike
from pathlib import Path
from typing import TYPE_CHECKING, Any

from frictiondisk.version import __version__

if TYPE_CHECKING:
    import xarray as xr

    from frictiondisk.engine.campaign_run import RunSummary
    from frictiondisk.model.scene import SceneConfig
    from frictiondisk.simulation.result import SimulationResult
    from frictiondisk.tasks.campaign import Campaign

__all__ = [
    "__version__",
    "load_campaign",
    "load_scene",
    "open_results",
    "plot_orbit",
    "plot_results",
    "run_campaign",
    "run_campaigns",
    "simulate",
]


def load_scene(
    path: str | PathLike[str], overrides: list[str] | tuple[str, ...] = ()
) -> SceneConfig:
    """Load and validate a scene YAML file (every key not given takes its default, SI units).

    overrides: a list of "KEY=VALUE" strings like the CLI's --set, e.g. ["params.mu=0.13"]
    (one string alone is a TypeError, not a list of its characters). A bad file or value
    raises `frictiondisk.model.yamlio.ConfigError` naming the key and its allowed range.
    """
    from frictiondisk.model.scene import load_scene as _load_scene

    return _load_scene(path, overrides if isinstance(overrides, str) else tuple(overrides))


def simulate(scene: SceneConfig, record: bool = False, dt_out: float = 0.0) -> SimulationResult:
    """Run one scene and classify its long-term motion (stick, stick_slip, slide, ...).

    record: keep the trajectory (`result.trajectory`), sampled every dt_out [s] plus every
    switching instant (dt_out = 0: every step). The first call in a process compiles the
    numba kernel (or loads it from its cache).
    """
    from frictiondisk.simulation.simulate import simulate as _simulate

    return _simulate(scene, record=record, dt_out=dt_out)


def load_campaign(source: str | PathLike[str] | dict[str, Any]) -> Campaign:
    """Load and validate a campaign: a YAML file's path, or its parsed content as a dict
    (any task of frictiondisk.tasks.registry)."""
    if isinstance(source, dict):
        from frictiondisk.tasks.campaign import campaign_from_dict

        return campaign_from_dict(source, source="<dict>")
    from frictiondisk.tasks.campaign import load_campaign as _load_campaign

    return _load_campaign(source)


def run_campaign(
    campaign: Campaign | str | PathLike[str] | None,
    out_dir: str | PathLike[str],
    workers: int = 2,
    progress: bool = False,
) -> RunSummary:
    """Run a campaign (a `Campaign` or the path of its YAML file) into out_dir, resuming
    whatever out_dir's journal already holds; campaign=None resumes out_dir's own campaign.
    Writes out_dir/results.nc and runs.nc (trajectory.nc for a trajectory task).

    workers: local Dask workers (threads); progress: a progress bar on stderr. Returns the
    run's summary (points, runs computed and read from the journal, wall time)."""
    from frictiondisk.engine.runner import run_campaign as _run_campaign

    if campaign is not None and not hasattr(campaign, "task"):
        campaign = load_campaign(campaign)
    return _run_campaign(campaign, Path(out_dir), workers=workers, progress=progress)


def run_campaigns(
    campaigns: list[Campaign | str | PathLike[str]] | None,
    out_dir: str | PathLike[str],
    workers: int = 2,
    progress: bool = False,
) -> list[RunSummary]:
    """Run several campaigns (each a `Campaign` or the path of its YAML file) in this
    process, each into out_dir/<its name>/, their runs scheduled together on one set of
    workers, resuming whatever their journals already hold; campaigns=None resumes every
    campaign of out_dir. Names must differ. Returns each campaign's summary, in order."""
    from frictiondisk.engine.runner import run_campaigns as _run_campaigns

    if campaigns is not None:
        campaigns = [c if hasattr(c, "task") else load_campaign(c) for c in campaigns]
    return _run_campaigns(campaigns, Path(out_dir), workers=workers, progress=progress)


def open_results(path: str | PathLike[str], name: str = "results") -> xr.Dataset:
    """A campaign's output as an xarray Dataset, read into memory (the file is closed).

    path: a campaign directory (then `name` picks results.nc, runs.nc or trajectory.nc)
    or a netCDF file.
    """
    import xarray as xr

    path = Path(path)
    if path.is_dir():
        path = path / f"{name}.nc"
    with xr.open_dataset(path) as ds:
        return ds.load()


def plot_results(path: str | PathLike[str], runs: bool = False):
    """The matplotlib Figure `frictiondisk plot DIR [--runs]` draws for the campaign in
    directory `path`, from its netCDF files alone, with axis units and a caption. runs:
    overlay every run of a find_jump campaign."""
    from frictiondisk.tasks.plot import figure_for_dir

    return figure_for_dir(Path(path), show_runs=runs)


def plot_orbit(result: SimulationResult, scene: SceneConfig):
    """The Figure of the orbit y(x) [m] recorded in `result` (simulate(..., record=True)):
    sticking segments dark, sliding light, the master axis and the spring rest marked."""
    from frictiondisk.figures.plotting import plot_orbit as _plot_orbit

    return _plot_orbit(result, scene)
