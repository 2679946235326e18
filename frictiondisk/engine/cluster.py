"""The Dask side of a campaign: start a client (of --scheduler or a local cluster), size
its tasks from the measured round trip of an empty task, name its dashboard."""

from __future__ import annotations

import time

from frictiondisk.engine.worker import noop
from frictiondisk.tasks.jobs import Sizing

SCHEDULER_TIMEOUT = 10.0  # [s] for the client to connect to --scheduler
WORKER_WAIT = 60.0  # [s] default wait for a live worker (--worker-wait)
TASK_OVERHEAD_SHARE = 0.05  # a task should last long enough that its scheduling costs <= 5 %
# [s] ... and at least this long: the driver's own work per task (submit, collect, a
# journal pack) is ~2-5 ms more, serial in one thread, beside 2 workers' kernels
MIN_TASK_S = 0.2
MAX_TASK_S = 1.0  # [s] ... but no longer: an interrupt waits for (or loses) the tasks in flight
TASKS_PER_WORKER = 2  # tasks in flight per worker thread: one running, one queued behind it
OVERHEAD_PROBES = 5  # round trips of an empty task timed (median): 8 cost 30 ms more, same value


class SchedulerFailed(Exception):
    """--scheduler cannot be used: unreachable, or no worker alive for too long."""


def start_client(workers: int, scheduler: str | None, processes: bool, dashboard: bool):
    """(client, cluster): a client of `scheduler` (cluster None; SchedulerFailed if it
    cannot connect), else of a new local cluster of `workers` single-thread workers, which
    serves the Dask dashboard if `dashboard`. The caller closes both."""
    import dask
    from distributed import Client, LocalCluster

    if scheduler:
        try:
            return Client(scheduler, timeout=SCHEDULER_TIMEOUT), None
        except (OSError, TimeoutError, ValueError) as err:
            raise SchedulerFailed(
                f"--scheduler {scheduler}: cannot connect within {SCHEDULER_TIMEOUT:g} s "
                f"({type(err).__name__}: {err})"
            ) from None
    # Dask's statistical profiler samples every worker thread every 10 ms: 3-4 % of
    # the CPU that two workers on two cores need for themselves (a dashboard tab).
    with dask.config.set({"distributed.worker.profile.enabled": False}):
        cluster = LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=processes,
            # None: no dashboard; the scheduler's own HTTP routes (health, metrics) still
            # bind, to a free port on loopback only, so that two campaigns at once never
            # warn of port 8787 and nothing is served to the network unasked
            dashboard_address=":0" if dashboard else None,
            scheduler_kwargs={"dashboard_address": ":0" if dashboard else "127.0.0.1:0"},
        )
    client = Client(cluster)
    if not processes:
        _send_without_batching_delay(client, cluster)
    return client, cluster


def task_sizing(
    overhead_s: float, mean_run_s: float | None, worker_threads: int, in_flight: int
) -> Sizing:
    """Cut work into tasks that last task_s = overhead / 5 %, within MIN_TASK_S and
    MAX_TASK_S: a batch holds task_s / mean_run_s independent runs (1 while no run time is
    known yet), a chain runs for task_s; TASKS_PER_WORKER tasks per worker thread are in
    flight."""
    scheduled_s = overhead_s * (1 - TASK_OVERHEAD_SHARE) / TASK_OVERHEAD_SHARE
    task_s = min(MAX_TASK_S, max(MIN_TASK_S, scheduled_s))
    batch = max(1, int(task_s / mean_run_s)) if mean_run_s else 1
    return Sizing(
        batch_runs=batch,
        chain_s=task_s,
        max_jobs=max(0, TASKS_PER_WORKER * worker_threads - in_flight),
        workers=worker_threads,
    )


def measure_task_overhead(client, probes: int = OVERHEAD_PROBES) -> float:
    """Median round trip [s] of an empty task through this client's scheduler: the cost
    per task that a batch must amortize (the first, cold, round trip is not counted)."""
    client.submit(noop, pure=False).result()
    times = []
    for _ in range(probes):
        t0 = time.perf_counter()
        client.submit(noop, pure=False).result()
        times.append(time.perf_counter() - t0)
    return sorted(times)[len(times) // 2]


def has_dashboard() -> bool:
    """Whether the Dask dashboard can be served here (it needs bokeh)."""
    import importlib.util

    return importlib.util.find_spec("bokeh") is not None


def dashboard_link(client) -> str:
    """The scheduler's dashboard address, or why there is none."""
    try:
        link = client.dashboard_link  # a scheduler without a dashboard lists no such service
    except (KeyError, AttributeError, TypeError):
        link = None
    if link and (client.cluster is None or has_dashboard()):
        return link
    return "not available (the Dask dashboard needs bokeh: pip install 'bokeh>=3.1')"


def _send_without_batching_delay(client, cluster) -> None:
    """Dask batches messages for 2-10 ms per hop (hard-coded BatchedSend intervals), which
    made a job's round trip 10.7 ms here; in our own in-process cluster every hop is
    reachable, and sending at once brings it to 3.0 ms. A pure latency setting: if a Dask
    release renames these attributes, the campaign runs the same, only slower."""
    comms = [getattr(client, "scheduler_comm", None)]
    comms += list(getattr(cluster.scheduler, "stream_comms", {}).values())
    comms += list(getattr(cluster.scheduler, "client_comms", {}).values())
    comms += [getattr(w, "batched_stream", None) for w in cluster.workers.values()]
    for comm in comms:
        if comm is not None and hasattr(comm, "interval"):
            comm.interval = 0
