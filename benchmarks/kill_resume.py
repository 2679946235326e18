"""The journal's promise under SIGKILL: kill a running scan at random moments, resume it
each time, and check what the kills cost and that the results are those of an
uninterrupted run.

One reference run of the scan (uninterrupted) first. Then `run` into a fresh folder, and
SIGKILL the process a random delay after it starts computing (status.json written); `resume`, SIGKILL again, ...; once a resume
finishes, its results.nc and runs.nc are compared with the reference
(frictiondisk.studies.identical, timings left out) and the next round starts in a new
folder, until `--trials` kills are done. Every fourth stop is a graceful one (SIGINT,
Ctrl-C), which must lose nothing. Each kill checks:

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

# The child: the CLI, with each finished job's run count appended to a side file.
CHILD = """
import os, runpy, sys
import frictiondisk.engine.worker as worker
side = os.open(sys.argv[1], os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
run_job = worker.run_job
def counted(job, campaign_dir):
    value = run_job(job, campaign_dir)
    os.write(side, f"{len(value) if isinstance(value, list) else 0}\\n".encode())
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


def computing(folder: Path, child: subprocess.Popen, since: float) -> None:
    """Wait until the child computes (its status.json rewritten after `since`) or ends."""
    status = folder / "status.json"
    while child.poll() is None:
        try:
            if status.stat().st_mtime >= since:
                return
        except FileNotFoundError:
            pass
        time.sleep(0.02)


def job_sizes(side: Path) -> list[int]:
    try:
        return [int(line) for line in side.read_text().split()]
    except FileNotFoundError:
        return []


def one_stop(folder: Path, campaign: Path, delay: float, graceful: bool) -> tuple[bool, str]:
    """Start (or resume) the scan in `folder`, stop it after `delay` s; (ended by itself,
    a line on what the stop cost; 'FAIL' in it if a check failed)."""
    side = Path(tempfile.mkstemp(prefix="kill-side-")[1])
    before = Journal.count(folder) if folder.exists() else 0
    if (folder / "campaign.yaml").exists():
        args = ["resume", str(folder)]
    else:  # a run killed before it wrote its folder starts again
        args = ["run", str(campaign), "-o", str(folder)]
    started = time.time()
    child = start(side, args)
    computing(folder, child, started)
    try:
        child.wait(timeout=delay)
        finished = True
    except subprocess.TimeoutExpired:
        child.send_signal(signal.SIGINT if graceful else signal.SIGKILL)
        child.wait()
        finished = False
    sizes = job_sizes(side)
    side.unlink()
    after = Journal.count(folder) if folder.exists() else 0
    lost = before + sum(sizes) - after  # finished on a worker, not journaled
    bound = 0 if graceful else sum(sizes[-TASKS_PER_WORKER * WORKERS :])
    ok = 0 <= lost <= bound and (not finished or child.returncode == 0)
    how = f"exit {child.returncode}" if finished else ("SIGINT" if graceful else "SIGKILL")
    line = (
        f"{how:8s} {delay:5.2f} s in: journal {before} -> {after}, {len(sizes)} jobs "
        f"({sum(sizes)} runs) ended on workers, {lost} of them not journaled "
        f"(bound {bound}){'' if ok else '  FAIL'}"
    )
    return finished, line


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
    parser.add_argument("--trials", type=int, default=20, help="stops in all")
    parser.add_argument(
        "--max-delay", type=float, default=6.0, help="[s] latest stop, after computing starts"
    )
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    rng = random.Random(args.seed)
    failures = 0
    with tempfile.TemporaryDirectory(prefix="kill-resume-") as tmp:
        root = Path(tmp)
        campaign = root / "kill_scan.yaml"
        campaign.write_text(SCAN.format(runs=args.runs))
        reference = root / "reference"
        t0 = time.perf_counter()
        subprocess.run(
            [
                sys.executable,
                "-m",
                "frictiondisk.cli",
                "run",
                str(campaign),
                "-o",
                str(reference),
            ],
            check=True,
            stdout=subprocess.DEVNULL,
        )
        print(f"reference: {args.runs} runs in {time.perf_counter() - t0:.1f} s", flush=True)
        stops, round_no = 0, 0
        folder = root / f"round-{round_no}"
        while stops < args.trials:
            graceful = stops % 4 == 3
            done, line = one_stop(folder, campaign, rng.uniform(0.0, args.max_delay), graceful)
            print(f"round {round_no} {line}", flush=True)
            failures += "FAIL" in line
            if not done:
                stops += 1
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
            done, line = one_stop(folder, campaign, 3600.0, False)
            problems = check_round(folder, reference, args.runs)
            print(
                f"round {round_no} {line}; complete: "
                + ("identical" if not problems else "; ".join(problems)),
                flush=True,
            )
            failures += bool(problems) + ("FAIL" in line)
            break
    print(f"{args.trials} stops, {failures} failed checks (load {os.getloadavg()[0]:.1f})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
