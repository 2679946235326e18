"""`frictiondisk accuracy`: the accuracy study of a find_jump campaign (thin; the study is
frictiondisk/studies/accuracy/, run here by frictiondisk.engine.local).

Exit codes: 0 done (failed bisections are rows with their reason), 2 bad command line or
campaign file (the message names the field), 1 any other failure.
"""

from __future__ import annotations

from pathlib import Path

import click

from frictiondisk.cli.options import fail

DEFAULT_TOL = 1.0e-9  # the study's bisection tol: below the numerics errors it measures


def _knob_list(ctx: click.Context, param: click.Parameter, value: str | None) -> tuple[str, ...]:
    if value is None:
        return ()
    return tuple(name.strip() for name in value.split(",") if name.strip())


@click.command()
@click.argument("campaign_file", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "-o",
    "--out",
    "out_dir",
    type=click.Path(file_okay=False, path_type=Path),
    required=True,
    help="Output directory (accuracy.nc, work_precision.png and .pdf).",
)
@click.option(
    "--point",
    type=int,
    default=0,
    show_default=True,
    help="Campaign point to study: its index in C order over `along` (0 = the first).",
)
@click.option(
    "--tol",
    type=float,
    default=DEFAULT_TOL,
    show_default=True,
    help="Bisection tolerance of every setting (errors below it are not resolved).",
)
@click.option(
    "--knobs",
    callback=_knob_list,
    metavar="NAME,...",
    help="Knobs to study (default: all that apply): rtol, method, preset, t_decide, "
    "stiffness, damping, eps, points (disk only).",
)
@click.option(
    "--quick",
    is_flag=True,
    help="Short ladders, no scipy-radau or coulomb rows (the references stay).",
)
@click.option(
    "--workers",
    type=click.IntRange(1, 64),
    default=1,
    show_default=True,
    help="Bisections run at once on threads (wall times are cleanest with 1).",
)
def accuracy(
    campaign_file: Path,
    out_dir: Path,
    point: int,
    tol: float,
    knobs: tuple[str, ...],
    quick: bool,
    workers: int,
) -> None:
    """Accuracy study of the jump search of CAMPAIGN_FILE (a find_jump campaign) at one point.

    Bisects mu* under a ladder of settings per knob (integrator and rtol, presets, the
    decision horizon, contact stiffness, damping, eps and, for the disk, the number of
    contact points) and reports each bracket, its error against the knob's reference and
    its cost. Writes DIR/accuracy.nc and the work-precision figure DIR/work_precision.png
    (and .pdf). Progress goes to stderr.
    """
    from frictiondisk.model.scene import ConfigError
    from frictiondisk.studies.accuracy.entry import AccuracyEntry
    from frictiondisk.tasks.campaign import load_campaign

    study = AccuracyEntry()

    source = str(campaign_file)
    if not campaign_file.is_file():
        fail(source, [f"campaign file not found: {campaign_file}"])
    try:
        campaign = load_campaign(campaign_file)
    except ConfigError as exc:
        fail(source, list(exc.problems))
    except OSError as exc:
        fail(source, [f"cannot read the campaign file: {exc.strerror or exc}"])
    problems = study.applies_to(campaign) or study.option_problems(campaign, point, tol, knobs)
    if problems:
        fail(source, problems)

    import matplotlib

    matplotlib.use("Agg")
    from frictiondisk.engine.local import run_study
    from frictiondisk.figures.plotting import save_figure
    from frictiondisk.store.files import atomic_write_netcdf

    ds = run_study(study.study(campaign, point, knobs, tol, quick), workers)
    nc = atomic_write_netcdf(ds, out_dir / "accuracy.nc")
    fig = study.figure(ds)
    png = save_figure(fig, out_dir / "work_precision.png")
    pdf = save_figure(fig, out_dir / "work_precision.pdf")
    click.echo(study.table(ds))
    click.echo(f"dataset: {nc}")
    click.echo(f"figure:  {png} (and {pdf.name})")
