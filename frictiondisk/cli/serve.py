"""`frictiondisk serve`: keep this environment warm for `run` and `resume`
(the server is cli/warm_server.py; --detach and --stop are cli/warm_control.py)."""

from __future__ import annotations

import click

from frictiondisk.cli.options import fail

READY_TIMEOUT_S = 900.0  # [s] for --detach: a first start may compile the kernel


@click.command()
@click.option(
    "--idle-timeout",
    type=click.FloatRange(min=1.0),
    default=900.0,
    show_default=True,
    help="Stop after this many seconds [s] without a command.",
)
@click.option("--detach", is_flag=True, help="Start in the background; return once it is ready.")
@click.option("--stop", "stop_it", is_flag=True, help="Stop the server of this environment.")
def serve(idle_timeout: float, detach: bool, stop_it: bool) -> None:
    """Keep this environment warm: `run` and `resume` start in about 0.3 s, not 1.3 s.

    The server imports Dask, xarray and netCDF4 and loads the compiled kernel once. It
    runs each later `run` or `resume` of yours in a forked copy of itself, with your
    directory, environment, terminal and umask; the command you typed passes its signals
    on (Ctrl-C and SIGTERM stop a campaign as usual, Ctrl-Z suspends it) and exits with
    its code. The results are the same as without it. It serves one exact environment
    (these sources, this Python and its packages, NUMBA_*, DASK_* and PYTHON* variables,
    Dask's configuration, CPU affinity, nice, limits and cgroup); a command from any
    other runs on its own, as does any command with FRICTIONDISK_NO_SERVER=1. Its socket
    lives in $XDG_RUNTIME_DIR/frictiondisk (or $FRICTIONDISK_SERVER_DIR). Commands still
    running when it stops finish first.
    """
    from frictiondisk.cli.warm_control import ServerError
    from frictiondisk.cli.warm_control import detach as start_detached
    from frictiondisk.cli.warm_protocol import UnsafeServerDir, private_dir, socket_path
    from frictiondisk.cli.warm_server import serve as serve_here

    try:
        if stop_it:
            _stop(socket_path(private_dir(create=False)))
        elif detach:
            pid, path, log = start_detached(idle_timeout, READY_TIMEOUT_S)
            click.echo(f"frictiondisk serve: ready at {path} (pid {pid}); log: {log}")
        else:
            # the commands it runs are those of this command's own group (cli/main.py)
            serve_here(idle_timeout, click.get_current_context().find_root().command)
    except (ServerError, UnsafeServerDir) as exc:
        fail(f"serve: {exc}", [])
    except FileNotFoundError:
        click.echo("no server serves this environment")


def _stop(path) -> None:
    from frictiondisk.cli.warm_control import request_stop

    running = request_stop(path)
    if running is None:
        click.echo("no server serves this environment")
    else:
        ending = f" once its {running} running command(s) end" if running else ""
        click.echo(f"stopping the server{ending}")
