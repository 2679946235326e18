"""Checks that run before a campaign directory is created.

A campaign that cannot write its directory, reach its scheduler, fit its size limits or
run its worker count fails here, in well under a second, with a message naming the path
or the option, instead of after DIR was created or the work began. So does a find_jump
whose numerics cannot reach its tol (a resumed one too, read from DIR), naming the
smallest tol they reach; `run --tol-floor` runs it at that floor instead (`at_tol_floor`).
"""

from __future__ import annotations

import socket
from pathlib import Path

from frictiondisk.engine.budget import check as check_size
from frictiondisk.engine.budget import estimate
from frictiondisk.model.limits import workers_problem
from frictiondisk.store.layout import CAMPAIGN_FILE
from frictiondisk.store.paths import check_output_dir, describe_os_error

__all__ = [
    "SCHEDULER_TIMEOUT",
    "at_tol_floor",
    "numerics_warning",
    "preflight",
    "scheduler_problem",
]

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
    """Why a find_jump's numerics cannot reach its tol (None: they can, or no tol;
    frictiondisk.model.auto_numerics). `run` refuses such a campaign unless --tol-floor."""
    choice = getattr(campaign, "numerics_choice", None)
    return choice.warning() if choice is not None else None


def at_tol_floor(campaign):
    """(the campaign, None), or where its numerics cannot reach its tol, (the same campaign
    at the smallest tol they reach, a line saying so): its file's text with the task's
    `tol` raised and a comment that says why, so that DIR/campaign.yaml and a resume hold
    the tol that runs."""
    import yaml

    from frictiondisk.model.yamlio import StrictDumper, load_yaml_text
    from frictiondisk.tasks.campaign import campaign_from_text

    choice = getattr(campaign, "numerics_choice", None)
    if choice is None or choice.reaches or choice.floor is None:
        return campaign, None
    data = load_yaml_text(campaign.text)
    data[campaign.kind]["tol"] = choice.floor
    said = (
        f"{campaign.kind}.tol {choice.tol:g} raised to {choice.floor:g}, the smallest tol "
        "its numerics reach (run --tol-floor)"
    )
    text = f"# {said}\n" + yaml.dump(
        data, Dumper=StrictDumper, sort_keys=False, default_flow_style=False
    )
    return campaign_from_text(text, source=f"{campaign.name} at its tol floor"), said


def _reach_problems(campaign, out_dir: Path) -> list[str]:
    """A find_jump whose numerics cannot reach its tol; for a resume (`campaign` None) the
    one stored in DIR (a campaign DIR that does not load is left to the resume)."""
    if campaign is not None:
        warning = numerics_warning(campaign)
        return [f"{warning}, or run --tol-floor to run at that floor"] if warning else []
    from frictiondisk.engine.directory import FolderDamaged, is_campaign_folder, read_manifest
    from frictiondisk.model.yamlio import ConfigError
    from frictiondisk.tasks.campaign import load_campaign

    try:
        folders = (
            [out_dir / n for n in read_manifest(out_dir)]
            if is_campaign_folder(out_dir)
            else [out_dir]
        )
    except FolderDamaged:
        return []
    problems = []
    for folder in folders:
        try:
            stored = load_campaign(folder / CAMPAIGN_FILE)
        except (ConfigError, OSError):
            continue
        warning = numerics_warning(stored)
        if warning:
            problems.append(
                f"{folder / CAMPAIGN_FILE}: {warning}; or start it again at "
                f"that floor: frictiondisk run {folder / CAMPAIGN_FILE} --tol-floor -o NEW_DIR"
            )
    return problems


def preflight(
    campaign,
    out_dir: Path,
    workers: int,
    scheduler: str | None,
    force: bool,
) -> list[str]:
    """Problems that forbid starting (empty: go). `campaign` is None for a resume (the
    campaign stored in out_dir is checked for its tol)."""
    problems = _reach_problems(campaign, out_dir)
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
