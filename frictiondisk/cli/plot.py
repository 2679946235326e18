"""`frictiondisk plot DIR`: the figure of a finished campaign, from its netCDF files alone.

Reads DIR/results.nc (and DIR/runs.nc for --runs), never simulates, and draws the figure
that fits the campaign (see frictiondisk.figures.campaign). Exit codes: 0 written, 2 a
missing or damaged results.nc / runs.nc (the message names the file and suggests
`frictiondisk resume DIR`), a partial results.nc without a finished point (stopped
early: nothing to draw yet), a file that is not a campaign result, or a bad -o suffix.
"""

from __future__ import annotations

from pathlib import Path

import click

from frictiondisk.cli.options import check_figure_suffix, fail

DEFAULT_FIGURE = "figure.png"


class CampaignFileError(Exception):
    """A campaign file that is missing, damaged or cannot be drawn: `headline` names the
    file, `details` say what to do."""

    def __init__(self, headline: str, details: list[str]):
        super().__init__("\n  ".join([headline, *details]))
        self.headline = headline
        self.details = details


def _load(path: Path, out_dir: Path):
    """The Dataset in `path`, fully loaded and closed; CampaignFileError naming the file if
    it is missing or does not load completely (e.g. truncated)."""
    import xarray as xr

    from frictiondisk.engine.directory import CAMPAIGN_FILE

    remedy = f"rebuild it from the journal: frictiondisk resume {out_dir}"
    if not path.is_file():
        if not (out_dir / CAMPAIGN_FILE).is_file():
            raise CampaignFileError(
                f"{path}: not found",
                [
                    f"{out_dir} is not a campaign directory (no {CAMPAIGN_FILE}); "
                    f"make one with: frictiondisk run CAMPAIGN.yaml -o {out_dir}"
                ],
            )
        raise CampaignFileError(
            f"{path}: not found", [f"the campaign has not finished writing it; {remedy}"]
        )
    try:
        with xr.open_dataset(path, cache=False) as ds:
            return ds.load()
    except Exception as exc:  # any reader error: truncated, corrupted, not netCDF
        detail = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise CampaignFileError(f"{path}: damaged, cannot be read ({detail})", [remedy]) from None


@click.command()
@click.argument("out_dir", metavar="DIR", type=click.Path(file_okay=False, path_type=Path))
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False, path_type=Path),
    metavar="FILE",
    callback=check_figure_suffix,
    help=f"Figure file; the suffix (.png, .pdf or .svg) picks the format [default: DIR/{DEFAULT_FIGURE}].",
)
@click.option(
    "--runs",
    "show_runs",
    is_flag=True,
    help="find_jump and trace: overlay every run of runs.nc as a dot at (coordinate, mu), "
    "stick dark, not stick light (how the jump was iterated, or the curves followed); a "
    "grid shows each cell's run count.",
)
@click.option(
    "--boundary",
    type=click.Path(file_okay=False, path_type=Path),
    metavar="JUMP_DIR",
    default=None,
    help="basin map: draw the contour mu* = the map's mu of the find_jump campaign in "
    "JUMP_DIR (a grid over the same two keys) on top.",
)
def plot(out_dir: Path, output: Path | None, show_runs: bool, boundary: Path | None) -> None:
    """Draw the figure of the campaign in DIR from DIR/results.nc (never simulates).

    find_jump along one key: mu* against the key with its brackets, the regions "pure
    sticking" and "outer limit cycle", failed points listed. find_jump over two keys: a map
    of mu*. scan of mu: size against mu by outcome, and a against mu with its
    least-squares line. scan of mu and one more key: one size curve per value of that key.
    trajectory: the orbit, sticking dark and sliding light (whole, or the last cycle with
    the deviation a marked). trace: the jump curves of the (key, mu) plane, their sticking
    side shaded, the folds where two jumps meet starred. basin: the fractions of each outcome against the varied key
    with 95 % Wilson bands, or a basin map coloured by outcome.
    """
    import matplotlib

    matplotlib.use("Agg")
    from frictiondisk.figures.plotting import save_figure

    try:
        fig = figure_for_dir(
            out_dir, show_runs, note=lambda text: click.echo(text, err=True), boundary=boundary
        )
    except CampaignFileError as exc:
        fail(exc.headline, exc.details)
    target = output if output is not None else out_dir / DEFAULT_FIGURE
    written = save_figure(fig, target)
    click.echo(f"figure: {written.resolve()}")


def figure_for_dir(out_dir: Path, show_runs: bool = False, note=None, boundary=None):
    """The Figure of the campaign in `out_dir`, from its netCDF files alone.

    `show_runs` overlays the runs of a find_jump campaign (ignored for other tasks, with
    a message to `note`, a callable taking text, if given). Raises CampaignFileError
    naming the file if one is missing, damaged or cannot be drawn. `boundary`: a find_jump
    campaign directory whose mu* contour is drawn on a basin map."""
    from frictiondisk.engine.directory import RESULTS_FILE, RUNS_FILE
    from frictiondisk.engine.orbit import TRAJECTORY_FILE
    from frictiondisk.figures.campaign import plot_campaign
    from frictiondisk.figures.orbit import plot_trajectory

    out_dir = Path(out_dir)
    results = _load(out_dir / RESULTS_FILE, out_dir)
    if results.attrs.get("partial") and not results.attrs.get("points_done"):
        raise CampaignFileError(
            f"{out_dir / RESULTS_FILE}: nothing to draw, no point is finished yet "
            f"(partial: 0 of {results.attrs.get('points_total', '?')} points)",
            [f"the campaign was stopped early; continue with: frictiondisk resume {out_dir}"],
        )
    task = results.attrs.get("task")
    if task == "trajectory":
        trajectory = _load(out_dir / TRAJECTORY_FILE, out_dir)
        try:
            return plot_trajectory(results, trajectory)
        except ValueError as exc:
            raise CampaignFileError(
                f"{out_dir / TRAJECTORY_FILE}: cannot draw this file", [str(exc)]
            ) from None
    runs = None
    if show_runs and task in ("find_jump", "trace"):
        runs = _load(out_dir / RUNS_FILE, out_dir)
    elif show_runs:
        if note is not None:
            note(
                f"note: --runs applies to find_jump and trace campaigns; in a {task} every "
                "run is a point already"
            )
        show_runs = False
    if task == "basin":
        from frictiondisk.figures.basin import plot_basin

        jump = None if boundary is None else _load(Path(boundary) / RESULTS_FILE, Path(boundary))
        try:
            return plot_basin(results, jump)
        except ValueError as exc:
            bad = Path(boundary) if str(exc).startswith("boundary") else out_dir
            raise CampaignFileError(
                f"{bad / RESULTS_FILE}: cannot draw this file", [str(exc)]
            ) from None
    if boundary is not None and note is not None:
        note(f"note: --boundary applies to basin maps; {out_dir} holds a {task}")
    try:
        return plot_campaign(results, runs, show_runs=show_runs)
    except ValueError as exc:
        path = out_dir / (RUNS_FILE if str(exc).startswith("runs") else RESULTS_FILE)
        raise CampaignFileError(f"{path}: cannot draw this file", [str(exc)]) from None
