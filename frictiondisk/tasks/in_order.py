"""Results fed to a search in its own order (pure Python): whatever order a campaign's
runs come back in from its workers, a search (a Bisection, JumpSearch or Tracer) takes
them in the order of its own pending list, so that what it decides never depends on
timing or worker count. A result that makes a later run needless would otherwise be
counted on one worker count and not on another (it was, once, on 16 workers)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


def feed_in_order(
    search,
    arrived: dict[Any, dict[str, Any]],
    request: Any,
    result: dict[str, Any],
    after_feed: Callable[[], None] | None = None,
) -> None:
    """Keep `result` in `arrived`, then feed `search` the results it holds while the first
    pending request is among them (`after_feed` after each); drop the results the search
    no longer waits for. `search`: anything with `done`, `pending()` and `feed()`."""
    arrived[request] = result
    while not search.done and search.pending() and search.pending()[0] in arrived:
        first = search.pending()[0]
        search.feed(first, arrived.pop(first))
        if after_feed is not None:
            after_feed()
    waiting = set() if search.done else set(search.pending())
    for held in [held for held in arrived if held not in waiting]:
        del arrived[held]
