"""How a campaign is stopped: Ctrl-C or SIGTERM, noted by the signal handler and raised
by the campaign loop (Terminated, request_stop), and the exception that reports it."""

from __future__ import annotations


class CampaignInterrupted(Exception):
    """Stopped by Ctrl-C or SIGTERM; the journal holds every finished run and results.nc
    the finished points (marked partial). `exit_code`: 130 (Ctrl-C) or 143 (SIGTERM)."""

    def __init__(self, message: str, exit_code: int = 130):
        super().__init__(message)
        self.exit_code = exit_code


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so that it stops a campaign like Ctrl-C."""


_stop_requested: list[type[KeyboardInterrupt]] = []


def request_stop(stop: type[KeyboardInterrupt]) -> None:
    """Note a stop (KeyboardInterrupt or Terminated) asked for by a signal. The handler
    raises it too, but an exception raised while the main thread runs a finalizer (Dask's
    Future.__del__) is printed and lost; the campaign loop then raises it from this note."""
    _stop_requested.append(stop)


def _raise_if_stop_requested() -> None:
    if _stop_requested:
        raise _stop_requested[-1]()
