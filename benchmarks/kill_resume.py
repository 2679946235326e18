"""The journal's promise under SIGKILL: kill a running scan at random moments, resume it
each time, and check what the kills cost and that the results are those of an
uninterrupted run.

One reference run of the scan (uninterrupted) first; it measures how long the workers
compute (from the first job's end to the last's). Then `run` into a fresh folder, and
SIGKILL the process a random delay after its first job ended, drawn within the computing
left (the share of points not yet journaled times the reference's), so that kills land
while jobs are in flight (the side file below counts them); `resume`, SIGKILL again, ...;
once a resume finishes, its results.nc and runs.nc are compared with the reference
(frictiondisk.studies.identical, timings left out) and the next round starts in a new
folder, until `--trials` SIGKILLs are done. After every third kill comes a graceful stop
(SIGINT, Ctrl-C), which must lose nothing. Each kill checks:

* runs finished on a worker but not journaled (computed again by the resume) are at most
  the runs of the last TASKS_PER_WORKER x workers jobs the workers finished: the batches
  in flight (a worker counts each job's runs into a side file as the job ends);
* after a graceful stop, none;
* at the end of a round, every run's key is in computed.log exactly once: no journaled run
  was ever computed again, and the journal holds every point.

    python benchmarks/kill_resume.py                 # the 4 000-run scan, 20 kills
    python benchmarks/kill_resume.py --runs 400 --trials 5

Exit code 1 if any check fails.
"""

from __future__ import annotations

import argparse
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from frictiondisk.engine.cluster import TASKS_PER_WORKER
from frictiondisk.store.journal import Journal
from frictiondisk.studies.identical import compare

SCAN = """\
name: kill_scan
scene: pin
params: {{x_ms: 0.1}}
scan:
  mu: {{start: 0.13, stop: 0.30, num: {runs}}}
  mode: decide
"""

# The child: the CLI, with a line in a side file as each job starts on a worker ("-1 t")
# and as it ends (its run count and time, "n t").
CHILD = """
import os, runpy, sys, time
import frictiondisk.engine.worker as worker
side = os.open(sys.argv[1], os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
run_job = worker.run_job
def counted(job, campaign_dir):
    os.write(side, f"-1 {time.time()}\\n".encode())
    value = run_job(job, campaign_dir)
    os.write(side, f"{len(value) if isinstance(value, list) else 0} {time.time()}\\n".encode())
    return value
worker.run_job = counted
sys.argv = ["frictiondisk", *sys.argv[2:]]
runpy.run_module("frictiondisk.cli", run_name="__main__")
"""
WORKERS = 2


def start(side: Path, args: list[str]) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-c", CHILD, str(side), *args],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )


def computing(side: Path, child: subprocess.Popen) -> None:
    """Wait until the child's workers compute (a first job ended) or the child ends."""
    while child.poll() is None:
        if job_ends(side):
            return
        time.sleep(0.005)


def side_lines(side: Path) -> list[tuple[int, float]]:
    """(runs, time) of each line: runs -1 for a job's start, else the runs it ended with."""
    try:
        rows = [line.split() for line in side.read_text().splitlines()]
    except FileNotFoundError:
        return []
    return [(int(runs), float(at)) for runs, at in rows]


def job_ends(side: Path) -> list[tuple[int, float]]:
    return [(runs, at) for runs, at in side_lines(side) if runs >= 0]


def in_flight(side: Path) -> int:
    """Jobs started on a worker and not ended."""
    lines = side_lines(side)
    return sum(runs < 0 for runs, _ in lines) - sum(runs >= 0 for runs, _ in lines)


def one_stop(folder: Path, campaign: Path, delay_of, graceful: bool) -> tuple[bool, str, int]:
    """Start (or resume) the scan in `folder`, stop it `delay_of(journaled runs)` s after
    its first job ended; (ended by itself, a line on what the stop cost ('FAIL' in it if
    a check failed), the jobs in flight when it was stopped)."""
    side = Path(tempfile.mkstemp(prefix="kill-side-")[1])
    before = Journal.count(folder) if folder.exists() else 0
    if (folder / "campaign.yaml").exists():
        args = ["resume", str(folder)]
    else:  # a run killed before it wrote its folder starts again
        args = ["run", str(campaign), "-o", str(folder)]
    child = start(side, args)
    computing(side, child)
    delay = delay_of(before)
    try:
        child.wait(timeout=delay)
        finished, flying = True, 0
    except subprocess.TimeoutExpired:
        flying = in_flight(side)
        child.send_signal(signal.SIGINT if graceful else signal.SIGKILL)
        child.wait()
        finished = False
    sizes = [runs for runs, _ in job_ends(side)]
    side.unlink()
    after = Journal.count(folder) if folder.exists() else 0
    lost = before + sum(sizes) - after  # finished on a worker, not journaled
    bound = 0 if graceful else sum(sizes[-TASKS_PER_WORKER * WORKERS :])
    ok = 0 <= lost <= bound and (not finished or child.returncode == 0)
    how = f"exit {child.returncode}" if finished else ("SIGINT" if graceful else "SIGKILL")
    flight = "" if finished else f", {flying} jobs in flight"
    line = (
        f"{how:8s} {delay:5.2f} s in{flight}: journal {before} -> {after}, {len(sizes)} jobs "
        f"({sum(sizes)} runs) ended on workers, {lost} of them not journaled "
        f"(bound {bound}){'' if ok else '  FAIL'}"
    )
    return finished, line, flying


def check_round(folder: Path, reference: Path, runs: int) -> list[str]:
    counts = Journal(folder).computed_counts()
    problems = [f"{key}: computed {n} times" for key, n in counts.items() if n > 1][:5]
    if len(counts) != runs:
        problems.append(f"{len(counts)} keys in computed.log, {runs} points")
    problems += compare(reference, folder, set())
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=4000, help="points of the scan")
    parser.add_argument("--trials", type=int, default=20, help="SIGKILLs in all")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    rng = random.Random(args.seed)
    failures = 0
    with tempfile.TemporaryDirectory(prefix="kill-resume-") as tmp:
        root = Path(tmp)
        campaign = root / "kill_scan.yaml"
        campaign.write_text(SCAN.format(runs=args.runs))
        reference = root / "reference"
        side = Path(tempfile.mkstemp(prefix="kill-side-")[1])
        t0 = time.perf_counter()
        child = start(side, ["run", str(campaign), "-o", str(reference)])
        if child.wait() != 0:
            raise SystemExit(f"the reference run failed (exit {child.returncode})")
        ends = [at for _, at in job_ends(side)]
        compute_s = max(ends) - min(ends)  # from the first job's end to the last's
        side.unlink()
        print(
            f"reference: {args.runs} runs in {time.perf_counter() - t0:.1f} s, "
            f"{compute_s:.1f} s from the first job's end to the last's",
            flush=True,
        )

        def delay_of(journaled: int) -> float:
            return rng.uniform(0.0, compute_s * (1.0 - journaled / args.runs))

        stops, round_no = 0, 0
        landed = {True: 0, False: 0}  # graceful or not: stops with jobs in flight
        folder = root / f"round-{round_no}"
        while stops - stops // 4 < args.trials:
            graceful = stops % 4 == 3
            done, line, flying = one_stop(folder, campaign, delay_of, graceful)
            print(f"round {round_no} {line}", flush=True)
            failures += "FAIL" in line
            if not done:
                stops += 1
                landed[graceful] += flying > 0
                continue
            problems = check_round(folder, reference, args.runs)
            print(
                f"round {round_no} complete: "
                + ("identical" if not problems else "; ".join(problems)),
                flush=True,
            )
            failures += bool(problems)
            round_no += 1
            folder = root / f"round-{round_no}"
        while folder.exists():  # finish the last round
            done, line, _ = one_stop(folder, campaign, lambda _: 3600.0, False)
            problems = check_round(folder, reference, args.runs)
            print(
                f"round {round_no} {line}; complete: "
                + ("identical" if not problems else "; ".join(problems)),
                flush=True,
            )
            failures += bool(problems) + ("FAIL" in line)
            break
    print(
        f"{args.trials} SIGKILLs ({landed[False]} with jobs in flight) and {stops // 4} SIGINTs "
        f"({landed[True]} with jobs in flight), {failures} failed checks "
        f"(load {os.getloadavg()[0]:.1f})"
    )
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
