"""Strong scaling of campaigns: workers 1, 2, 4, ... up to the machine's cores.

For each campaign: the wall time on 1, 2, ... workers, the speed-up, the parallel
efficiency and the speed-up as a fraction of the machine's own limit, measured just before
and just after the campaign's timings (N independent loops of kernel runs on N threads,
no orchestration: speed-up = N x one loop's time / N loops' time; on a shared machine it
drifts, so each table has its own):

  (a) the 10-point disk-from-rest prescan line (campaigns/disk_xms_at_rest.yaml);
  (b) the Fig 11 campaign (campaigns/fig11_betab_mu.yaml);
  (c) one point searched to tol 1e-8: a Fig 11 point, the braked disk from rest at
      beta_b = 0.005 (runs of about 0.2 s near its jump), multisection split 3, with the
      runs and wall time of plain bisection for comparison;
  (d) one prescanned disk point (the disk from rest at x_ms = 0.1).

`--quick` (the default of `make bench`) uses reduced copies of (a) (tol 1e-3) and (b)
(prescan step 0.02, tol 1e-3) so the whole bench takes minutes on 2 cores;
`--full` runs the campaign files as they are. Ratios are measured in this process
after JIT warm-up; on a shared machine the numbers are noisy: repeat with --repeats.

Targets (issue 10) on 2 cores: (a), (b) 2-worker speed-up >= 90 % of the machine's limit;
(c), (d) 2 workers >= 1.6x faster than 1.
"""

from __future__ import annotations

import argparse
import collections
import heapq
import os
import shutil
import statistics
import tempfile
import threading
import time
import types
from pathlib import Path

import xarray as xr
from harness import Record

from frictiondisk.engine.cluster import task_sizing
from frictiondisk.engine.runner import run_campaign
from frictiondisk.engine.worker import warm_up
from frictiondisk.simulation.simulate import simulate
from frictiondisk.store.journal import Journal
from frictiondisk.store.journal_entry import run_key
from frictiondisk.tasks.campaign import campaign_from_text, load_campaign
from frictiondisk.tasks.jobs import RunScenes
from frictiondisk.tasks.jump_search.requests import run_config

ROOT = Path(__file__).resolve().parents[1]


def _edit(text: str, old: str, new: str) -> str:
    """text with `old` replaced by `new`; `old` must occur (a campaign file that changed
    must not silently give a different benchmark)."""
    if old not in text:
        raise ValueError(f"bench: {old!r} not found in the campaign file")
    return text.replace(old, new)


def campaign_text(name: str, quick: bool) -> tuple[str, str]:
    """(YAML text, what it is) of bench campaign `name`; (c) and (d) have SPLIT in place of
    find_jump.split."""
    if name == "a":
        text = (ROOT / "campaigns/disk_xms_at_rest.yaml").read_text()
        if quick:
            text = _edit(text, "tol: 1.0e-4", "tol: 1.0e-3")
            return text, "disk_xms_at_rest.yaml, quick: tol 1e-3"
        return text, "campaigns/disk_xms_at_rest.yaml as is"
    if name == "b":
        text = (ROOT / "campaigns/fig11_betab_mu.yaml").read_text()
        if quick:
            text = _edit(text, "stop: 1.00, num: 90}", "stop: 0.99, num: 45}")
            text = _edit(text, "tol: 1.0e-4", "tol: 1.0e-3")
            return text, "fig11_betab_mu.yaml, quick: prescan of 45 mu (step 0.02), tol 1e-3"
        return text, "campaigns/fig11_betab_mu.yaml as is"
    if name == "c":
        text = """name: bench_one_point_fine
scene: disk
params: {x_ms: 0.1, phidot0: 0.0, beta_b: 0.005}
numerics: {mode: decide, t_decide: 30.0}
find_jump:
  bracket: [0.2, 0.25]
  tol: 1.0e-8
  split: SPLIT
  along:
    params.beta_b: [0.005]
"""
        what = "braked disk from rest, beta_b 0.005, bracket [0.2, 0.25], tol 1e-8, split SPLIT"
        return text, what
    if name == "d":
        text = (ROOT / "campaigns/disk_xms_at_rest.yaml").read_text()
        text = _edit(text, "params.x_ms: {start: 0.02, stop: 0.2, num: 10}", "params.x_ms: [0.1]")
        text = _edit(text, "  tol: 1.0e-4\n", "  tol: 1.0e-4\n  split: SPLIT\n")
        return text, "disk from rest at x_ms 0.1, prescan of 58 mu, tol 1e-4, split SPLIT"
    raise ValueError(name)


class KernelLoops:
    """The machine's own limit: N independent loops of kernel runs on N threads, no
    orchestration. One loop is calibrated once to last about `loop_s` seconds, so walls
    measured at different times are comparable."""

    def __init__(self, loop_s: float):
        from frictiondisk.tasks.jump_search.bisection import RunRequest

        campaign = load_campaign(ROOT / "campaigns/disk_xms_at_rest.yaml")
        point = campaign.points()[4].config
        configs = [run_config(point, RunRequest(mu, 0, "decide"), 2.0) for mu in (0.1, 0.2, 0.3)]
        t0 = time.perf_counter()
        n_loop = 0
        while time.perf_counter() - t0 < loop_s:
            simulate(configs[n_loop % len(configs)])
            n_loop += 1
        self.todo = [configs[k % len(configs)] for k in range(n_loop)]

    def _loop(self) -> None:
        for config in self.todo:
            simulate(config)

    def wall(self, n: int) -> float:
        """Wall time [s] of n loops on n threads."""
        threads = [threading.Thread(target=self._loop) for _ in range(n)]
        t0 = time.perf_counter()
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        return time.perf_counter() - t0


def _result_of(journal: Journal, canonical: dict) -> dict:
    return journal.get(run_key(types.SimpleNamespace(canonical=lambda: canonical)))


def _emulate(job, journal: Journal):
    """(value, busy seconds) a worker would return for this job (frictiondisk.tasks.jobs),
    from the journal of a measured run: every run takes the wall time it took there."""
    if isinstance(job, RunScenes):
        results = [_result_of(journal, c) for c in job.scenes]
        return results, sum(r["wall_s"] for r in results)
    bis, budget = job.search, job.budget_s
    made, busy = [], 0.0
    while not bis.done:
        if budget is not None and busy >= budget:
            break
        for request in bis.pending():
            result = _result_of(journal, job.scene_of(request).canonical())
            busy += result["wall_s"]
            made.append((request, result))
            bis.feed(request, result)
    return (bis, made), busy


def modelled_walls(
    text: str,
    journal_dir: Path,
    workers: list[int],
    overhead_s: float,
    driver_task_s: float,
    driver_run_s: float,
) -> dict[int, float]:
    """Wall time [s] of the campaign on N ideal cores: the driver's own planner and task
    sizing, replayed with each run's measured wall time, `overhead_s` per task on its
    worker, and serial driver time for each task that comes back: `driver_task_s` plus
    `driver_run_s` per run it made (keys, journal, planner)."""
    campaign = campaign_from_text(text, "<model>")
    journal = Journal(journal_dir)
    walls = {}
    for n in workers:
        planner = campaign.entry.planner(campaign)
        queue: collections.deque = collections.deque()
        running: list = []  # heap of (end time, sequence, job, value)
        t = driver_free = run_s = 0.0
        computed = sequence = 0
        while not planner.done:
            mean_run = run_s / computed if computed else None
            sizing = task_sizing(overhead_s, mean_run, n, len(queue) + len(running))
            queue.extend(planner.jobs(sizing))
            while len(running) < n and queue:
                job, work = queue.popleft()
                value, busy = _emulate(work, journal)
                heapq.heappush(running, (t + overhead_s + busy, sequence, job, value))
                sequence += 1
            end, _, job, value = heapq.heappop(running)
            made = planner.complete(job, value)
            t = driver_free = max(end, driver_free) + driver_task_s + driver_run_s * len(made)
            for _, _, result in made:
                computed += 1
                run_s += result["wall_s"]
        walls[n] = t
    return walls


def time_campaign(
    text: str, workers: int, repeats: int, keep: Path | None = None, processes: bool = False
):
    """Best wall time [s] of a fresh run on `workers` local workers, runs used, the
    results (results.nc, loaded), the measured cost per task [s] and the driver thread's
    CPU time [s]; with `keep`, the journal is copied there and the CPU time is counted
    without the fixed part (lock, replay, netCDF writes: a rerun on the full journal).
    processes: the workers are processes (`run --processes`), not threads of the driver's
    process."""
    best = None
    for _ in range(repeats):
        with tempfile.TemporaryDirectory() as tmp:
            campaign = campaign_from_text(text, "<bench>")
            t0, cpu0 = time.perf_counter(), time.thread_time()
            summary = run_campaign(
                campaign, Path(tmp), workers=workers, processes=processes, progress=False
            )
            wall, cpu = time.perf_counter() - t0, time.thread_time() - cpu0
            with xr.open_dataset(Path(tmp) / "results.nc") as ds:
                found = ds.load()
            if keep is not None:
                shutil.copytree(Path(tmp) / "journal", keep / "journal", dirs_exist_ok=True)
                # the fixed part of the driver's CPU: the same campaign on its full journal
                cpu0 = time.thread_time()
                run_campaign(campaign, Path(tmp), workers=workers, progress=False)
                cpu -= time.thread_time() - cpu0
        if best is None or wall < best[0]:
            best = (wall, summary.runs_total, found, summary.task_overhead_s, cpu)
    return best


def scaling_table(
    text,
    workers,
    repeats,
    model_to: int,
    loops: KernelLoops,
    driver_task_s: float,
    processes: bool = False,
):
    """Time the campaign on each worker count and the machine's limit in `repeats` rounds.

    The machine is shared and its speed drifts by tens of per cent within a minute, so
    ratios are taken within a round, never across rounds: in each round the kernel loops
    and the campaign run on every worker count back to back (in reverse order every other
    round, so a steady drift cancels), giving that round's limit and speed-up; the table
    shows the median over rounds. Returns ({workers: median speed-up}, {workers: median
    limit})."""
    timed: dict[int, tuple] = {}  # the fastest run on each worker count (its results)
    speedups: dict[int, list[float]] = {n: [] for n in workers}
    limits: dict[int, list[float]] = {n: [] for n in workers}
    of_limit: dict[int, list[float]] = {n: [] for n in workers}
    walls: dict[int, list[float]] = {n: [] for n in workers}
    with tempfile.TemporaryDirectory() as keep:
        for repeat in range(repeats):
            order = workers if repeat % 2 == 0 else workers[::-1]
            loop_wall, wall = {}, {}
            for n in order:
                loop_wall[n] = loops.wall(n)
                keep_here = Path(keep) if n == workers[0] and repeat == 0 else None
                candidate = time_campaign(text, n, 1, keep_here, processes)
                if keep_here is not None:
                    driver_cpu = candidate[4]  # without the fixed part (see time_campaign)
                wall[n] = candidate[0]
                walls[n].append(wall[n])
                if n not in timed or candidate[0] < timed[n][0]:
                    timed[n] = candidate
            for n in workers:
                # above n only when the one loop was slowed by a neighbour: capped
                limit_now = min(n, n * loop_wall[workers[0]] / loop_wall[n])
                speedup_now = wall[workers[0]] / wall[n]
                limits[n].append(limit_now)
                speedups[n].append(speedup_now)
                of_limit[n].append(speedup_now / limit_now)
        limit = {n: statistics.median(limits[n]) for n in workers}
        rows = {n: statistics.median(speedups[n]) for n in workers}
        print(
            f"  machine limit (independent kernel loops on N threads), median of {repeats} "
            "rounds: "
            + ", ".join(
                f"{n}: {limit[n]:.2f}x ({min(limits[n]):.2f}-{max(limits[n]):.2f})"
                for n in workers
                if n > workers[0]
            )
        )
        print(
            f"  {'workers':>7} {'wall [s]':>9} {'speed-up':>9} {'efficiency':>10} "
            f"{'of limit':>9}   (medians over rounds; speed-up range)"
        )
        found_1 = timed[workers[0]][2]
        for n in workers:
            found = timed[n][2]
            same = "" if found.identical(found_1) else "  RESULTS DIFFER"
            print(
                f"  {n:7d} {statistics.median(walls[n]):9.2f} {rows[n]:8.2f}x "
                f"{rows[n] / n:10.0%} {statistics.median(of_limit[n]):9.0%}   "
                f"({min(speedups[n]):.2f}-{max(speedups[n]):.2f}){same}"
            )
        wall, runs, found, overhead, _ = timed[workers[0]]
        print(f"  runs used: {runs}; cost per task measured by the driver: {overhead * 1e3:.1f} ms")
        # the model: measured run times, task cost and driver CPU; cores assumed ideal
        counts = sorted({1, 2, 4, 8, 16, model_to} | set(workers))
        tasks_1 = _tasks_on_one(text, Path(keep), overhead)
        runs_1 = len(Journal(Path(keep)))
        driver_run_s = max(0.0, driver_cpu - driver_task_s * tasks_1) / max(1, runs_1)
        model = modelled_walls(
            text, Path(keep), [*counts, 4096], overhead, driver_task_s, driver_run_s
        )
        print(
            f"  model (ideal cores; measured: run times, {overhead * 1e3:.1f} ms per task on "
            f"its worker, driver CPU {driver_task_s * 1e3:.2f} ms per task + "
            f"{driver_run_s * 1e3:.2f} ms per run; {tasks_1} tasks on 1 worker):"
        )
        print("  " + "  ".join(f"{n}: {model[1] / model[n]:.2f}x" for n in counts))
        print(
            f"  model on 4096 workers (the longest chain of dependent runs, plus task costs): "
            f"{model[1] / model[4096]:.1f}x"
        )
    return rows, limit, {n: statistics.median(of_limit[n]) for n in workers}


def driver_cpu_per_task(tasks: int = 300) -> float:
    """CPU time [s] of the driver's thread per task, for empty tasks submitted and collected
    the way the runner does (in-process cluster, sealed tasks, our keys, as_completed)."""
    from distributed import Client, LocalCluster, as_completed

    from frictiondisk.engine.cluster import _send_without_batching_delay
    from frictiondisk.engine.worker import Sealed, noop, run_sealed

    with (
        LocalCluster(
            n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None
        ) as cluster,
        Client(cluster) as client,
    ):
        _send_without_batching_delay(client, cluster)
        client.submit(noop, pure=False).result()
        done = as_completed(with_results=True, raise_errors=False)
        cpu0 = time.thread_time()
        for k in range(tasks):
            done.add(client.submit(run_sealed, Sealed(noop, ()), key=f"noop-bench-{k}"))
            for _ in done.next_batch(block=True):
                pass
        return (time.thread_time() - cpu0) / tasks


def _tasks_on_one(text: str, journal_dir: Path, overhead_s: float) -> int:
    """How many tasks the driver hands out on 1 worker (the model, counting)."""
    campaign = campaign_from_text(text, "<model>")
    journal = Journal(journal_dir)
    planner = campaign.entry.planner(campaign)
    tasks = computed = 0
    run_s = 0.0
    while not planner.done:
        mean_run = run_s / computed if computed else None
        jobs = planner.jobs(task_sizing(overhead_s, mean_run, 1, 0))
        for job, work in jobs:
            value, _ = _emulate(work, journal)
            tasks += 1
            for _, _, result in planner.complete(job, value):
                computed += 1
                run_s += result["wall_s"]
    return tasks


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="the campaign files as they are")
    parser.add_argument("--quick", action="store_true", help="reduced copies (default)")
    parser.add_argument("--repeats", type=int, default=3, help="rounds (medians are shown)")
    parser.add_argument("--workers", help="comma-separated worker counts (default 1, 2, 4, ...)")
    parser.add_argument("--only", default="abcd", help="which of a, b, c, d (default all)")
    parser.add_argument(
        "--split", type=int, default=3, help="(c), (d): parts per round (default 3)"
    )
    parser.add_argument(
        "--processes",
        action="store_true",
        help="workers as processes (run --processes): the driver keeps its GIL to itself",
    )
    args = parser.parse_args()
    quick = not args.full
    cores = os.cpu_count() or 1
    if args.workers:
        workers = sorted({int(w) for w in args.workers.split(",")} | {1})
    else:
        workers = sorted({1, cores} | {2**k for k in range(1, 8) if 2**k < cores})

    warm_up()
    import dask.array  # noqa: F401  (xarray imports it when writing results.nc: once per process)
    import distributed  # noqa: F401  (import time is not campaign time)

    record = Record("scaling")
    loops = KernelLoops(loop_s=2.0)
    driver_task_s = driver_cpu_per_task()
    print(
        f"driver CPU per task (empty tasks through an in-process cluster): "
        f"{driver_task_s * 1e3:.2f} ms"
    )
    record.number("driver CPU per task", driver_task_s * 1e3, "ms")
    for name in args.only:
        text, what = campaign_text(name, quick)
        text = text.replace("SPLIT", str(args.split))
        what = what.replace("SPLIT", str(args.split))
        title = {
            "a": "(a) 10-point disk-from-rest prescan line",
            "b": "(b) Fig 11 campaign",
            "c": "(c) one point searched to tol 1e-8",
            "d": "(d) one prescanned disk point",
        }[name]
        kind = "worker processes" if args.processes else "worker threads"
        print(f"== {title} [{what}; {kind}] ==")
        rows, limit, of_limit = scaling_table(
            text, workers, args.repeats, cores, loops, driver_task_s, args.processes
        )
        if 2 in rows:
            speedup = rows[2]
            if name in "ab":  # the paired ratio: speed-up / limit of the same round
                verdict = of_limit[2] >= 0.9
                target = f"2 workers >= 90 % of the machine's limit: {of_limit[2]:.0%}"
            else:
                verdict = speedup >= 1.6
                target = (
                    f"2 workers >= 1.6x faster than 1: {speedup:.2f}x "
                    f"(the machine's limit {limit[2]:.2f}x)"
                )
            print(f"  target, {target}: {'met' if verdict else 'NOT MET'}")
            for n, value in sorted(rows.items()):
                record.number(f"{title}: speed-up on {n} workers over 1", value, "1")
            record.number(f"{title}: 2 workers, share of the machine's limit", of_limit[2], "1")
        if name in "cd" and args.split != 2:
            plain = text.replace(f"split: {args.split}", "split: 2")
            wall, runs, *_ = time_campaign(plain, 1, args.repeats, processes=args.processes)
            print(
                f"  plain bisection (split 2) on 1 worker: {wall:.2f} s (best of "
                f"{args.repeats}), {runs} runs"
            )

    record.write()


if __name__ == "__main__":
    main()
