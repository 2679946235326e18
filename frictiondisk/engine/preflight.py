"""Checks that run before a campaign directory is created.

A campaign that cannot write its directory, reach its scheduler, fit its size limits or
run its worker count fails here, in well under a second, with a message naming the path
or the option, instead of after DIR was created or the work began. So does, under
`run --strict`, a find_jump whose numerics cannot reach its tol.
"""

from __future__ import annotations

import socket
from pathlib import Path

from frictiondisk.engine.budget import check as check_size
from frictiondisk.engine.budget import estimate
from frictiondisk.model.limits import workers_problem
from frictiondisk.store.paths import check_output_dir, describe_os_error

__all__ = ["SCHEDULER_TIMEOUT", "numerics_warning", "preflight", "scheduler_problem"]

SCHEDULER_TIMEOUT = 5.0  # [s] to open a TCP connection to --scheduler


def scheduler_problem(address: str, timeout: float = SCHEDULER_TIMEOUT) -> str | None:
    """A message naming --scheduler if `address` does not parse as a Dask address or, for
    tcp/tls, nothing accepts a connection there within `timeout` seconds; else None."""
    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        scheme, location = parse_address(address, strict=False)
        if scheme not in ("tcp", "tls"):
            return None  # other transports (inproc, ucx, ws) are checked by the client
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as err:
        return (
            f"--scheduler: {address!r} is not a scheduler address ({err}): expected "
            "e.g. tcp://host:8786"
        )
    try:
        with socket.create_connection((host or "127.0.0.1", port), timeout=timeout):
            pass
    except OSError as err:
        why = "timed out" if isinstance(err, TimeoutError) else (err.strerror or str(err))
        return (
            f"--scheduler: nothing answers at {address} within {timeout:g} s ({why}); "
            "start the scheduler or check the address"
        )
    return None


def numerics_warning(campaign) -> str | None:
    """The warning that a find_jump's numerics cannot reach its tol (None: they can, or
    no tol; frictiondisk.model.auto_numerics). `run --strict` refuses such a campaign."""
    choice = getattr(campaign, "numerics_choice", None)
    return choice.warning() if choice is not None else None


def preflight(
    campaign,
    out_dir: Path,
    workers: int,
    scheduler: str | None,
    force: bool,
    strict: bool = False,
) -> list[str]:
    """Problems that forbid starting (empty: go). `campaign` is None for a resume.
    `strict`: numerics that cannot reach the tol are a problem too, not a warning."""
    problems = []
    warning = numerics_warning(campaign)
    if strict and warning:
        problems.append(f"--strict: {warning}")
    try:
        check_output_dir(out_dir, "campaign directory")
    except OSError as err:
        problems.append(describe_os_error(err))
    if scheduler:
        problem = scheduler_problem(scheduler)
        if problem:
            problems.append(problem)
    else:
        problem = workers_problem(workers)
        if problem:
            problems.append(problem)
    if campaign is not None and not force:
        size = check_size(campaign)
        if size:
            problems += size
            problems.append(
                f"the campaign would have {estimate(campaign).describe()}; "
                "shrink it, or pass --force to run it anyway"
            )
    return problems
