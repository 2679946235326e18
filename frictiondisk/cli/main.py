"""Command line interface: thin click commands over config, simulate, trajectory and plotting.

Exit codes: 0 on a completed run (whatever its outcome), 2 on a bad command line, a bad
scene file (the message names the field; no traceback) or an output path that cannot be
written (named, with the cause), 130 on Ctrl-C, 1 on any other failure.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import sys
from pathlib import Path
from typing import Any

import click

from frictiondisk.cli.options import TaskName, check_figure_suffix, fail
from frictiondisk.verdict import outcomes
from frictiondisk.version import __version__


class _Main(click.Group):
    """The command group; an OSError no command caught is still reported as the path and
    its cause (no space left, read-only, not a directory) with exit code 2, never as a
    traceback."""

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except OSError as exc:
            from frictiondisk.store.paths import describe_os_error

            fail(describe_os_error(exc), [])


MAIN_HELP = f"""frictiondisk: stick-slip and permanent sticking of rigid friction disks.

    Simulates a pin or a slave disk on a driven master disk with elasto-visco-plastic
    friction contacts, and classifies each run as {outcomes.names_text()}.
    """


@click.group(cls=_Main, context_settings={"help_option_names": ["-h", "--help"]}, help=MAIN_HELP)
@click.version_option(__version__, "--version", prog_name="frictiondisk")
def main() -> None:
    """The `frictiondisk` command group (its help: MAIN_HELP, which lists the outcomes)."""


def _check_dt_out(ctx: click.Context, param: click.Parameter, value: float) -> float:
    if not (math.isfinite(value) and value > 0.0):
        raise click.BadParameter(f"must be a finite number > 0 (seconds), got {value!r}")
    return value


def _json_default(value: Any) -> Any:
    """Serialise numpy scalars (and anything with .item()) in the JSON summary."""
    item = getattr(value, "item", None)
    if item is None:
        raise TypeError(f"not JSON serialisable: {type(value).__name__}")
    value = item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _fmt(value: float | None, unit: str = "", spec: str = ".6g") -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    return f"{value:{spec}}{' ' + unit if unit else ''}"


SIMULATE_HELP = f"""Simulate one SCENE (a YAML file) and report its outcome.

    The outcome is one of {outcomes.names_text()} (always with a reason):
    stick_slip wherever the slave sticks as a whole for part of the final window, slide only
    where it never does and its motion is not yet shown (cycle_converged says whether a
    motion has settled); reported with the first sticking radius R1, the cycle size and a, the number of
    stick/slide transitions and the stick fraction of the final window.
    """


@main.command(help=SIMULATE_HELP)
@click.argument("scene", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "--set",
    "overrides",
    multiple=True,
    metavar="KEY=VALUE",
    help="Override one scene value, e.g. --set params.mu=0.2 (repeatable).",
)
@click.option(
    "--json",
    "as_json",
    is_flag=True,
    help="Print exactly one JSON object with the outcome and measures on stdout.",
)
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False, path_type=Path),
    metavar="PATH",
    help="Write the trajectory (netCDF4, with units and the full configuration) to PATH.",
)
@click.option(
    "--plot",
    "plot_path",
    type=click.Path(dir_okay=False, path_type=Path),
    metavar="PATH",
    callback=check_figure_suffix,
    help="Draw the orbit (sticking dark, sliding light) to PATH (.png, .pdf or .svg).",
)
@click.option(
    "--dt-out",
    type=float,
    metavar="SECONDS",
    default=0.01,
    show_default=True,
    callback=_check_dt_out,
    help="Recording interval for -o/--plot [s].",
)
def simulate(
    scene: Path,
    overrides: tuple[str, ...],
    as_json: bool,
    output: Path | None,
    plot_path: Path | None,
    dt_out: float,
) -> None:
    """`frictiondisk simulate` (its help: SIMULATE_HELP, which lists the outcomes)."""
    record = output is not None or plot_path is not None
    config = _checked_scene(scene, overrides, (output, plot_path), dt_out if record else None)

    # Imported here so that `--help` and `--version` stay fast (the kernel compiles with numba).
    from frictiondisk.simulation.compile_notice import announce_compile
    from frictiondisk.simulation.simulate import simulate as run_simulation

    announce_compile()

    # With --json, stdout carries the JSON object and nothing else.
    redirect = contextlib.redirect_stdout(sys.stderr) if as_json else contextlib.nullcontext()
    with redirect, _os_errors_reported():
        result = _interruptible(run_simulation, config, record=record, dt_out=dt_out)
        if record and result.trajectory is None:
            raise click.ClickException("the simulation returned no trajectory to write or plot")
        if record and result.trajectory.truncated:
            click.echo(
                f"warning: the trajectory buffer filled up; samples after "
                f"t = {result.trajectory.t[-1]:.6g} s were not recorded (raise --dt-out)",
                err=True,
            )
        outputs = _write_outputs(result, config, output, plot_path)

    from frictiondisk.model.headline import scene_headline

    head = scene_headline(config)
    summary = result.summary()
    if as_json:
        payload = dict(summary)
        payload.update(
            scene=head["scene"],
            mu=head["mu"],
            config_hash=str(config.content_hash()),
            outputs=outputs,
        )
        click.echo(json.dumps(payload, default=_json_default, allow_nan=False))
        return
    click.echo("\n".join(_report_lines(scene, head, summary, outputs)))


def _checked_scene(scene: Path, overrides: tuple[str, ...], paths, dt_out: float | None):
    """The scene file with its overrides, validated, and the output `paths` checked
    writable (a recording every `dt_out` [s] checked too); else exit 2 naming every
    problem."""
    from frictiondisk.model.limits import recording_problem
    from frictiondisk.model.scene import ConfigError, load_scene
    from frictiondisk.store.paths import check_output_file, describe_os_error

    if not scene.is_file():
        fail(str(scene), [f"scene file not found: {scene}"])
    try:
        config = load_scene(scene, list(overrides))
    except ConfigError as exc:
        fail(str(scene), list(exc.problems))
    except OSError as exc:
        fail(str(scene), [f"cannot read the scene file: {exc.strerror or exc}"])
    problems = [recording_problem(config, dt_out, "--dt-out")] if dt_out is not None else []
    for path in paths:
        try:
            if path is not None:
                check_output_file(path)
        except OSError as exc:
            problems.append(describe_os_error(exc))
    if any(problems):
        fail(str(scene), [problem for problem in problems if problem])
    return config


def _write_outputs(result, config, output: Path | None, plot_path: Path | None) -> dict:
    """Write the trajectory and the orbit figure asked for; their resolved paths."""
    outputs: dict[str, str | None] = {"trajectory": None, "plot": None}
    if output is not None:
        from frictiondisk.store.trajectory import write_trajectory

        outputs["trajectory"] = str(write_trajectory(output, result, config).resolve())
    if plot_path is not None:
        import matplotlib

        matplotlib.use("Agg")
        from frictiondisk.figures.plotting import plot_orbit, save_figure

        fig = plot_orbit(result, config)
        outputs["plot"] = str(save_figure(fig, plot_path).resolve())
    return outputs


def _report_lines(scene: Path, head: dict, summary: dict, outputs: dict) -> list[str]:
    """The report of one run, a line per measure."""
    lines = [
        f"scene:        {scene} ({head['scene']}, mu = {head['mu']:g}, x_ms = {head['x_ms']:g} m)",
        f"outcome:      {summary['outcome']} ({summary['reason']})",
        f"R1:           {_fmt(summary['R1'], 'm')} at t = {_fmt(summary['t_R1'], 's')}",
        f"size:         {_fmt(summary['size'], 'm')}    a: {_fmt(summary['a'], 'm')}",
        f"transitions:  {summary['n_transitions']}"
        f"    stick fraction: {_fmt(summary['stick_fraction'], spec='.3f')}",
        f"steps:        {summary['n_steps']} accepted, {summary['n_rejected']} rejected"
        f" ({summary['method']}), t_end = {_fmt(summary['t_end'], 's')}",
        f"wall time:    {_fmt(summary['wall_s'], 's', '.3g')}",
    ]
    if summary.get("n_revolutions"):
        lines.insert(
            -2,
            f"per rev:      slip {_fmt(summary['slip_per_rev'], 'm', '.3g')}, centre drift "
            f"{_fmt(summary['drift_per_rev'], 'm', '.3g')}, spin drift "
            f"{_fmt(summary['spin_drift_per_rev'], 'rad', '.3g')} "
            f"(last of {summary['n_revolutions']} revolutions)",
        )
    if outputs["trajectory"]:
        lines.append(f"trajectory:   {outputs['trajectory']}")
    if outputs["plot"]:
        lines.append(f"plot:         {outputs['plot']}")
    return lines


@contextlib.contextmanager
def _os_errors_reported():
    """An OSError while writing outputs: exit 2 naming the path and the cause."""
    from frictiondisk.store.paths import describe_os_error

    try:
        yield
    except OSError as exc:
        fail(describe_os_error(exc), [])


def _interruptible(function, *args, **kwargs):
    """`function(*args, **kwargs)`, stopped at once by Ctrl-C (exit 130) even while its run
    sits in the numba kernel (frictiondisk.engine.signals.wait_interruptibly)."""
    from frictiondisk.engine.signals import wait_interruptibly

    try:
        return wait_interruptibly(function, *args, **kwargs)
    except KeyboardInterrupt:
        click.echo("error: interrupted (Ctrl-C); nothing was written", err=True)
        sys.stdout.flush()
        sys.stderr.flush()
        # No interpreter shutdown: it takes seconds (numba, llvmlite) and nothing is left
        # to save, since outputs are written after the run.
        os._exit(130)


@main.command("show-defaults")
@click.option(
    "--scene",
    "scene",
    type=click.Choice(["pin", "disk"]),
    default="pin",
    show_default=True,
    help="Which scene's defaults to print: the keys that scene uses (a pin has no spin "
    "and no contact layout keys; it refuses them).",
)
@click.option(
    "--task",
    type=TaskName(),
    default=None,
    help="Print the keys of this campaign task instead of the scene.",
)
def show_defaults(scene: str, task: str | None) -> None:
    """Print the resolved default scene as YAML, every key with its description and unit
    (SI; [1] = dimensionless) in a comment; docs/reference.md has the same as tables.

    The output is a valid scene file: save it, edit a value, and `simulate` it. With
    --task, print a campaign task's keys and defaults instead.
    """
    from frictiondisk.model.reference import annotated_scene
    from frictiondisk.tasks.reference import annotated_task

    click.echo(annotated_task(task) if task else annotated_scene(scene))


# Campaign commands live in frictiondisk/cli/campaign.py, `plot` in cli/plot.py,
# `accuracy` in cli/accuracy.py.
def _add_campaign_commands() -> None:
    from frictiondisk.cli.accuracy import accuracy
    from frictiondisk.cli.campaign import resume, run, status
    from frictiondisk.cli.plot import plot

    for command in (run, resume, status, plot, accuracy):
        main.add_command(command)


_add_campaign_commands()


if __name__ == "__main__":  # python -m frictiondisk.cli
    main()
