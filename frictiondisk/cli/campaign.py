"""Campaign commands: `run`, `resume`, `status` (thin; the work is in frictiondisk/engine/:
the runner, and what `status` reports, engine/status.py),
for one campaign in DIR or several in DIR/<name>/ (`run A.yaml B.yaml -o DIR`).

Exit codes: 0 done, 2 bad campaign file, a different or hand-edited campaign in DIR, a
path that cannot be written (named, with the cause), a symbolic link in DIR, an
unreachable scheduler, a campaign over its size limits, a find_jump whose numerics cannot
reach its tol (unless `run --tol-floor`), two campaigns of one name in one run, or one campaign into a folder of
several (or the reverse); 3 DIR is in use by another run,
130 interrupted (Ctrl-C), 143 terminated (SIGTERM), 129 hung up (SIGHUP: the terminal
closed). A stop journals the runs in flight that finish within 30 s and writes results.nc
with the finished points, marked partial; resume continues.
"""

from __future__ import annotations

import contextlib
import signal
from pathlib import Path

import click

from frictiondisk.cli.options import fail

EXIT_LOCKED = 3


@contextlib.contextmanager
def _signals_stop_the_campaign():
    """Ctrl-C (SIGINT), SIGTERM (a batch scheduler, `kill`) and SIGHUP (a closed
    terminal) stop a campaign alike: runs journaled, partial results. Each handler notes the stop before
    raising it, so that a raise lost in a finalizer still stops the campaign loop."""
    from frictiondisk.engine.signals import request_stop, stop_signals

    def stopper(stop):
        def handler(signum, frame):
            request_stop(stop)
            raise stop()

        return handler

    previous = {}
    try:
        for signum, stop in stop_signals().items():
            if signum != signal.SIGTERM and signal.getsignal(signum) is signal.SIG_IGN:
                continue  # ignored when we started (nohup, a background job): stays so
            previous[signum] = signal.signal(signum, stopper(stop))
    except ValueError:  # not the main thread (an embedding application): leave it alone
        pass
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


def _execute(
    campaigns: list | None,
    out_dir: Path,
    workers: int,
    scheduler: str | None,
    processes: bool,
    worker_wait: float,
    force: bool = False,
    dashboard: bool = False,
    several: bool = False,
):
    """Run (campaigns None: resume) one campaign into out_dir, or with `several`, each
    of `campaigns` into out_dir/<name>/ in this process (engine/runner.py); report the
    outcome, or fail with the documented exit code."""
    from frictiondisk.engine.cluster import SchedulerFailed
    from frictiondisk.engine.directory import CampaignChanged, FolderDamaged
    from frictiondisk.engine.preflight import preflight
    from frictiondisk.engine.runner import CampaignsClash, run_campaign, run_campaigns
    from frictiondisk.engine.signals import CampaignInterrupted, describe_stop, stop_notice
    from frictiondisk.model.scene import ConfigError
    from frictiondisk.store.lock import CampaignLocked
    from frictiondisk.store.paths import describe_os_error

    problems = []
    for k, campaign in enumerate(campaigns or [None]):
        where = out_dir / campaign.name if several and campaign is not None else out_dir
        # the scheduler is probed once: the campaigns share it
        problems += preflight(campaign, where, workers, scheduler if k == 0 else None, force)
    if problems:
        fail(f"{out_dir}: cannot start (nothing was created)", list(dict.fromkeys(problems)))
    for campaign in campaigns or []:
        _echo_numerics(campaign, f"{campaign.name}: " if several else "")
    options = dict(worker_wait=worker_wait, dashboard=dashboard)
    try:
        with _signals_stop_the_campaign():
            if several:
                summaries = run_campaigns(
                    campaigns, out_dir, workers, scheduler, processes, **options
                )
            else:
                campaign = campaigns[0] if campaigns else None
                summaries = [
                    run_campaign(campaign, out_dir, workers, scheduler, processes, **options)
                ]
    except CampaignChanged as exc:
        fail(
            f"{exc.out_dir}: the campaign differs from the one this directory holds",
            exc.differences,
        )
    except CampaignsClash as exc:
        fail(f"{out_dir}: refused (nothing was written)", exc.problems)
    except FolderDamaged as exc:
        fail(str(exc), [])
    except CampaignLocked as exc:
        fail(str(exc), [], EXIT_LOCKED)
    except CampaignInterrupted as exc:
        fail(str(exc), [], exc.exit_code)
    except KeyboardInterrupt as stop:  # outside the campaign loop: set-up, a trajectory run
        fail(stop_notice(stop, "outside the campaign loop"), [], describe_stop(stop)[1])
    except ConfigError as exc:
        fail(f"{out_dir}/campaign.yaml", list(exc.problems))
    except SchedulerFailed as exc:
        fail(str(exc), [f"continue with: frictiondisk resume {out_dir}"])
    except FileNotFoundError as exc:
        fail(str(exc) if exc.filename is None else describe_os_error(exc), [])
    except OSError as exc:
        fail(
            describe_os_error(exc, exc.filename or out_dir),
            [f"finished runs are in the journal; fix this, then: frictiondisk resume {out_dir}"],
        )
    for summary in summaries:
        if several:  # each campaign's lines under its name
            name = summary.results.parent.name
            click.echo(f"{name}:")
            _echo_summary(summary, out_dir / name, indent="  ")
        else:
            _echo_summary(summary, out_dir)
    if several:
        wall = max((summary.wall_s for summary in summaries), default=0.0)
        click.echo(f"all {len(summaries)} campaigns done, {wall:.1f} s")


def _echo_summary(summary, out_dir: Path, indent: str = "") -> None:
    """What a finished campaign prints: rejected journal entries, its counts, its files
    and its closing lines (on stdout, each line after `indent`)."""
    for line in summary.moved_aside:
        click.echo(f"journal: rejected and recomputed: {line}", err=True)
    if summary.moved_aside:
        click.echo(
            f"journal: {len(summary.moved_aside)} entries failed verification; they are kept "
            f"in {out_dir / 'journal' / 'corrupt'}",
            err=True,
        )
    click.echo(
        f"{indent}done: {summary.points} points ({summary.points_failed} failed), "
        f"{summary.runs_total} runs used, {summary.runs_computed} computed now, "
        f"{summary.runs_saved_by_warm_start} saved by warm starts, {summary.wall_s:.1f} s"
    )
    click.echo(f"{indent}results: {summary.results}")
    label = "trajectory:" if summary.runs.name == "trajectory.nc" else "runs:   "
    click.echo(f"{indent}{label} {summary.runs}")
    _echo_closing(summary.results, indent)


def _echo_numerics(campaign, label: str = "") -> None:
    """The preflight line of a find_jump: its numerics and why (chosen from the tol, or
    given; numerics that cannot reach the tol were refused at preflight) (stderr)."""
    choice = getattr(campaign, "numerics_choice", None)
    if choice is not None:
        click.echo(f"{label}numerics: {choice.describe()}", err=True)


def _echo_closing(results_path: Path, indent: str = "") -> None:
    """The answer of a finished campaign, in its task's words (engine/status.py): a
    find_jump's mu* table (uncertain points named: not an error, exit 0, the best bracket
    of each kept and flagged), a scan's outcome per point, a basin's fractions with their
    95 % intervals."""
    from frictiondisk.engine.status import answer_lines

    for line in answer_lines(results_path):
        click.echo(indent + line)


_workers = click.option(
    "--workers",
    type=click.IntRange(1, 256),
    default=2,
    show_default=True,
    help="Local Dask workers (ignored with --scheduler); at most 4 per CPU core.",
)
_scheduler = click.option(
    "--scheduler",
    metavar="ADDRESS",
    default=None,
    help="Use an existing Dask scheduler (e.g. tcp://host:8786) instead of a local cluster.",
)
_worker_wait = click.option(
    "--worker-wait",
    type=click.FloatRange(0, 86_400),
    default=60.0,
    show_default=True,
    metavar="SECONDS",
    help="With --scheduler: fail after this long without a live worker (warns at once).",
)
_dashboard = click.option(
    "--dashboard",
    is_flag=True,
    help="Serve the Dask dashboard (bokeh) of the local workers and print its address.",
)
_processes = click.option(
    "--processes/--threads",
    default=False,
    show_default=True,
    help="Local workers as processes or as threads (the kernel releases the GIL).",
)


@click.command()
@click.argument(
    "campaign_files",
    metavar="CAMPAIGN_FILE...",
    nargs=-1,
    required=True,
    type=click.Path(dir_okay=False, path_type=Path),
)
@click.option(
    "-o",
    "--out",
    "out_dir",
    type=click.Path(file_okay=False, path_type=Path),
    required=True,
    help="Campaign directory (journal, results.nc, runs.nc); with several files, the "
    "folder that holds one such directory per campaign, DIR/<name>/.",
)
@_workers
@_scheduler
@_worker_wait
@_processes
@_dashboard
@click.option(
    "--force",
    is_flag=True,
    help="Run a campaign over the size limits (points, runs, memory) anyway.",
)
@click.option(
    "--tol-floor",
    is_flag=True,
    help="Run a find_jump whose numerics cannot reach its tol at the smallest tol they "
    "reach (written into DIR/campaign.yaml), instead of refusing it.",
)
@click.option("--strict", is_flag=True, hidden=True, help="The default now: no effect.")
def run(
    campaign_files: tuple[Path, ...],
    out_dir: Path,
    workers: int,
    scheduler,
    worker_wait: float,
    processes: bool,
    dashboard: bool,
    force: bool,
    tol_floor: bool,
    strict: bool,
) -> None:
    """Run CAMPAIGN_FILE into DIR; running it again on the same DIR resumes it.

    At the end it prints the answer: the mu* table of a find_jump (failed points with
    their reasons), the outcome and size per point of a scan, a basin's fractions. A
    find_jump's numerics keys not given (rtol, atol, t_decide) are chosen from its tol; the
    line `numerics: ...` says what runs and why (docs/accuracy.md).

    With several files, each campaign runs into DIR/<its name>/ (names must differ), all
    in this one process on one set of workers: their runs are scheduled together, so one
    campaign's last points overlap the next one's first. Each keeps its own journal, lock
    and files; `resume DIR` and `status DIR` take the folder."""
    from frictiondisk.engine.preflight import at_tol_floor
    from frictiondisk.model.scene import ConfigError
    from frictiondisk.tasks.campaign import load_campaign

    campaigns = []
    for campaign_file in campaign_files:
        if not campaign_file.is_file():
            fail(str(campaign_file), [f"campaign file not found: {campaign_file}"])
        try:
            campaign = load_campaign(campaign_file)
        except ConfigError as exc:
            fail(str(campaign_file), list(exc.problems))
        if tol_floor:
            campaign, said = at_tol_floor(campaign)
            if said:
                click.echo(f"{campaign.name}: {said}", err=True)
        campaigns.append(campaign)
    several = len(campaigns) > 1
    _execute(
        campaigns,
        out_dir,
        workers,
        scheduler,
        processes,
        worker_wait,
        force,
        dashboard,
        several,
    )


@click.command()
@click.argument("out_dir", type=click.Path(file_okay=False, path_type=Path))
@_workers
@_scheduler
@_worker_wait
@_processes
@_dashboard
def resume(
    out_dir: Path, workers: int, scheduler, worker_wait: float, processes: bool, dashboard: bool
) -> None:
    """Continue the campaign in DIR from its journal (no finished run is computed again);
    in a folder of several campaigns (`run A.yaml B.yaml -o DIR`), every one of them."""
    from frictiondisk.engine.directory import is_campaign_folder

    if not out_dir.exists():
        fail(f"{out_dir} does not exist: nothing to resume", [])
    several = is_campaign_folder(out_dir)
    if not several and not (out_dir / "campaign.yaml").is_file():
        fail(f"{out_dir} is not a campaign directory (no campaign.yaml)", [])
    _execute(
        None,
        out_dir,
        workers,
        scheduler,
        processes,
        worker_wait,
        dashboard=dashboard,
        several=several,
    )


@click.command()
@click.argument("out_dir", type=click.Path(file_okay=False, path_type=Path))
def status(out_dir: Path) -> None:
    """Report progress of the campaign in DIR: points, runs, failures, time left, and the
    answer so far (the mu* table with the reason of each failed point, a scan's outcome
    and size per point); in a folder of several campaigns, of each of them."""
    from frictiondisk.engine.directory import FolderDamaged, is_campaign_folder, read_manifest

    if not is_campaign_folder(out_dir):
        _report_status(out_dir)
        return
    try:
        names = read_manifest(out_dir)
    except FolderDamaged as exc:
        fail(str(exc), [])
    click.echo(f"folder:    {out_dir}, {len(names)} campaigns: {', '.join(names)}")
    for name in names:
        click.echo("")
        _report_status(out_dir / name)


def _report_status(out_dir: Path) -> None:
    """Print the progress of the campaign in DIR (exit 2 if DIR holds none)."""
    from frictiondisk.engine.status import NotACampaign, status_lines
    from frictiondisk.store.paths import describe_os_error

    try:
        lines = status_lines(out_dir)
    except NotACampaign as exc:
        fail(str(exc), [])
    except OSError as exc:
        fail(describe_os_error(exc), [])
    click.echo("\n".join(lines))
