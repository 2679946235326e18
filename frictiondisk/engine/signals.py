"""How a campaign is stopped: Ctrl-C, SIGTERM or SIGHUP, noted by the signal handler and raised
by the campaign loop (Terminated, request_stop), the exception that reports it, and a
wait that lets a stop interrupt a run in a numba kernel (wait_interruptibly)."""

from __future__ import annotations

import contextlib
import os
import signal
import threading
from collections.abc import Callable
from typing import Any, TypeVar

T = TypeVar("T")


class CampaignInterrupted(Exception):
    """Stopped by Ctrl-C or SIGTERM; the journal holds every finished run and results.nc
    the finished points (marked partial). `exit_code`: 130 (Ctrl-C), 143 (SIGTERM) or
    129 (SIGHUP)."""

    def __init__(self, message: str, exit_code: int = 130):
        super().__init__(message)
        self.exit_code = exit_code


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so that it stops a campaign like Ctrl-C."""

    what = "terminated (SIGTERM)"
    exit_code = 143


class HungUp(Terminated):
    """SIGHUP (the terminal closed): stops a campaign like SIGTERM."""

    what = "hung up (SIGHUP: the terminal closed)"
    exit_code = 129


def describe_stop(stop: KeyboardInterrupt) -> tuple[str, int]:
    """(what stopped us, the exit code): Ctrl-C 130, SIGTERM 143, SIGHUP 129."""
    if isinstance(stop, Terminated):
        return stop.what, stop.exit_code
    return "interrupted", 130


def stop_notice(stop: KeyboardInterrupt, where: str = "") -> str:
    """What a stop outside the campaign loop says (before it started, while the command
    set up, or while it printed its answer): the same words and advice as a stop inside it
    (engine/runner.py), so that Ctrl-C reads alike at any moment. `where`: e.g. "while
    setting up"."""
    what, _ = describe_stop(stop)
    return (
        f"{what}{' ' + where if where else ''}; no finished run is lost. Run the same "
        "command again to continue"
    )


def drop_hint(stop: KeyboardInterrupt) -> str:
    """How to drop the runs in flight while a stop drains them: the same signal again
    (any second stop does it), a SIGTERM after a SIGHUP (the terminal is gone)."""
    if isinstance(stop, HungUp):
        return f"SIGTERM, kill {os.getpid()}, to drop them"
    if isinstance(stop, Terminated):
        return f"SIGTERM again, kill {os.getpid()}, to drop them"
    return "Ctrl-C again to drop them"


_stop_requested: list[type[KeyboardInterrupt]] = []


def request_stop(stop: type[KeyboardInterrupt]) -> None:
    """Note a stop (KeyboardInterrupt or Terminated) asked for by a signal. The handler
    raises it too, but an exception raised while the main thread runs a finalizer (Dask's
    Future.__del__) is printed and lost; the campaign loop then raises it from this note."""
    _stop_requested.append(stop)


def noted_stop() -> type[KeyboardInterrupt] | None:
    """The last stop noted by request_stop (None: none since the last clear)."""
    return _stop_requested[-1] if _stop_requested else None


def raise_if_stop_requested() -> None:
    """Raise the last stop noted by request_stop (the loop checks this between rounds)."""
    if _stop_requested:
        raise _stop_requested[-1]()


def clear_stop_requests() -> None:
    """Forget every noted stop (a new run starts, or a stop was handled)."""
    _stop_requested.clear()


def wait_interruptibly(function: Callable[..., T], *args: Any, **kwargs: Any) -> T:
    """`function(*args, **kwargs)` in a daemon thread while this (the main) thread waits in
    10 ms slices, so that a Ctrl-C or SIGTERM handler runs at once and its exception leaves
    from here. A numba kernel releases the GIL but never returns to the interpreter, and
    the main thread only runs signal handlers between bytecodes: a kernel called directly
    would delay a stop until its run ends. On a stop the thread is left running; it dies
    with the process."""
    outcome: dict[str, Any] = {}

    def target() -> None:
        try:
            outcome["value"] = function(*args, **kwargs)
        except BaseException as exc:  # handed to the waiting thread
            outcome["error"] = exc

    worker = threading.Thread(target=target, name="frictiondisk-run", daemon=True)
    worker.start()
    while worker.is_alive():
        worker.join(0.01)
    if "error" in outcome:
        raise outcome["error"]
    return outcome["value"]


def stop_signals() -> dict[int, type[KeyboardInterrupt]]:
    """The signals that stop a campaign, each with the stop it raises: Ctrl-C, SIGTERM and
    (where the platform has it) SIGHUP."""
    stops = {signal.SIGINT: KeyboardInterrupt, signal.SIGTERM: Terminated}
    if hasattr(signal, "SIGHUP"):
        stops[signal.SIGHUP] = HungUp
    return stops


@contextlib.contextmanager
def stops_noted_only():
    """While it holds, Ctrl-C, SIGTERM and SIGHUP are noted (request_stop), not raised: for a
    teardown (the Dask client and cluster closing) that an exception raised inside it can
    leave hung. The noted stop decides the command's exit afterwards (cli/run_and_exit.py).
    Only the main thread's handlers that are Python functions are replaced, and restored."""
    previous = {}
    if threading.current_thread() is threading.main_thread():
        for signum, stop in stop_signals().items():
            if callable(signal.getsignal(signum)):

                def note(signum, frame, stop=stop):
                    request_stop(stop)

                previous[signum] = signal.signal(signum, note)
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
