"""`frictiondisk plot DIR`: the figure of a finished campaign, from its netCDF files alone.

Reads DIR/results.nc (and DIR/runs.nc for --runs), never simulates, and draws the figure
its task draws (frictiondisk.tasks.plot.figure_for_dir). Exit codes: 0 written, 2 a
missing or damaged results.nc / runs.nc (the message names the file and suggests
`frictiondisk resume DIR`), a partial results.nc without a finished point (stopped
early: nothing to draw yet), a file that is not a campaign result, or a bad -o suffix.
"""

from __future__ import annotations

from pathlib import Path

import click

from frictiondisk.cli.options import check_figure_suffix, fail

DEFAULT_FIGURE = "figure.png"


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
    "in its outcome's colour and marker (how the jump was iterated, or the curves "
    "followed); a grid shows each cell's run count.",
)
@click.option(
    "--boundary",
    type=click.Path(file_okay=False, path_type=Path),
    metavar="CAMPAIGN_DIR",
    multiple=True,
    help="basin map: draw the contour mu* = the map's mu of the find_jump campaign in "
    "CAMPAIGN_DIR (a grid over the same two keys) on top. Motion map: draw the boundary of "
    "any campaign in CAMPAIGN_DIR with a mu_star on top: a trace's curves or a find_jump's "
    "line over the map's two keys (a stick jump or a `between` boundary), or the contour "
    "mu* = the map's mu of a find_jump grid over them; repeatable.",
)
def plot(out_dir: Path, output: Path | None, show_runs: bool, boundary: tuple[Path, ...]) -> None:
    """Draw the figure of the campaign in DIR from DIR/results.nc (never simulates).

    find_jump along one key: mu* (or the bisected key) against the key with its brackets,
    the two sides labelled ("pure sticking" and "outer limit cycle", or the two motions of
    `between`), failed points listed. find_jump over two keys: a map
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
    from frictiondisk.store.campaign_files import CampaignFileError
    from frictiondisk.tasks.plot import figure_for_dir

    try:
        fig = figure_for_dir(
            out_dir, show_runs, note=lambda text: click.echo(text, err=True), boundary=boundary
        )
    except CampaignFileError as exc:
        fail(exc.headline, exc.details)
    target = output if output is not None else out_dir / DEFAULT_FIGURE
    written = save_figure(fig, target)
    click.echo(f"figure: {written.resolve()}")
