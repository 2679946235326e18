"""Ctrl-C at random moments of `frictiondisk run`: every stop exits 130 with its notice, and
the command the notice names (`resume DIR`, or the same `run` where nothing was started)
ends with results identical to an uninterrupted run.

    python -m frictiondisk.studies.sigint_trials -o out/sigint --trials 30 --max-delay 5

Each trial starts `run CAMPAIGN -o OUT/trial_<k>`, sends one SIGINT after a delay drawn
uniformly from [min-delay, max-delay] s (default 0 to 5; seeded), waits for the exit, then runs the command the
notice names and compares its results.nc and runs.nc with those of an uninterrupted run
(OUT/reference; frictiondisk.studies.identical). It prints one line per trial and the
counts, writes them to OUT/summary.json, and exits 1 unless every stop exited 130 and
every continuation is identical. Exit -2 (Python's own death by SIGINT, which a shell
shows as 130) is counted apart: it means the signal came while the interpreter was still
starting, before any frictiondisk code ran.
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

from frictiondisk.studies.identical import compare

WAIT_S = 120.0  # the most a stopped run may take to leave (its drain is at most 30 s)
RESULT_FILES = ("results.nc", "runs.nc")


def _command(python: str, *args: str) -> list[str]:
    return [python, "-m", "frictiondisk.cli", *args]


def _default_sigint() -> None:
    """A child started from a script gets an ignored SIGINT where the script's was (a
    background job): give it the default, like a terminal's foreground job."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _run(command: list[str], log: Path) -> int:
    with open(log, "w") as out:
        return subprocess.call(command, stdout=out, stderr=subprocess.STDOUT)


def interrupted_run(command: list[str], delay: float, log: Path) -> tuple[int | None, str]:
    """(exit code, last stderr line) of `command` sent SIGINT after `delay` s; None: it
    did not leave within WAIT_S (killed)."""
    with open(log, "w") as out:
        process = subprocess.Popen(
            command, stdout=out, stderr=subprocess.PIPE, text=True, preexec_fn=_default_sigint
        )
        time.sleep(delay)
        if process.poll() is None:
            process.send_signal(signal.SIGINT)
        try:
            _, err = process.communicate(timeout=WAIT_S)
        except subprocess.TimeoutExpired:
            process.kill()
            _, err = process.communicate()
            return None, "did not leave"
        out.write(err)
    lines = [line for line in err.splitlines() if line.strip()]
    return process.returncode, lines[-1] if lines else ""


def trial(k: int, delay: float, campaign: Path, out: Path, reference: Path, python: str) -> dict:
    """One trial: the stop, the continuation its notice names, the comparison."""
    folder = out / f"trial_{k:02d}"
    shutil.rmtree(folder, ignore_errors=True)
    run = _command(python, "run", str(campaign), "-o", str(folder))
    code, notice = interrupted_run(run, delay, out / f"trial_{k:02d}.stop.log")
    again = _command(python, "resume", str(folder)) if "resume" in notice else run
    resumed = _run(again, out / f"trial_{k:02d}.continue.log")
    differences = compare(reference, folder, set()) if resumed == 0 else ["not resumed"]
    return {
        "trial": k,
        "delay_s": round(delay, 3),
        "exit": code,
        "notice": notice,
        "continued_with": again[3],
        "continue_exit": resumed,
        "identical": not differences,
        "differences": differences[:5],
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--out", type=Path, required=True)
    parser.add_argument("--campaign", type=Path, default=Path("campaigns/demo_disk_line.yaml"))
    parser.add_argument("--trials", type=int, default=30)
    parser.add_argument("--min-delay", type=float, default=0.0, help="[s]")
    parser.add_argument("--max-delay", type=float, default=5.0, help="[s]")
    parser.add_argument("--seed", type=int, default=66)
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    python = sys.executable
    reference = args.out / "reference"
    if not all((reference / name).exists() for name in RESULT_FILES):
        shutil.rmtree(reference, ignore_errors=True)
        run = _command(python, "run", str(args.campaign), "-o", str(reference))
        if _run(run, args.out / "reference.log") != 0:
            print(f"error: the uninterrupted run failed; see {args.out / 'reference.log'}")
            return 1
    rng = random.Random(args.seed)
    delays = [rng.uniform(args.min_delay, args.max_delay) for _ in range(args.trials)]
    rows = []
    for k, delay in enumerate(delays):
        row = trial(k, delay, args.campaign, args.out, reference, python)
        rows.append(row)
        print(
            f"{k:3d} {row['delay_s']:6.3f} s exit {row['exit']} -> {row['continued_with']} "
            f"exit {row['continue_exit']} {'identical' if row['identical'] else 'DIFFERS'}"
            f"  | {row['notice'][:90]}",
            flush=True,
        )
    exits = collections.Counter(row["exit"] for row in rows)
    identical = sum(row["identical"] for row in rows)
    summary = {
        "campaign": str(args.campaign),
        "trials": len(rows),
        "delay_s": [args.min_delay, args.max_delay],
        "seed": args.seed,
        "exit_codes": {str(code): n for code, n in sorted(exits.items(), key=str)},
        "identical": identical,
        "rows": rows,
    }
    (args.out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    print(f"exit codes: {dict(exits)}; identical after continuing: {identical} of {len(rows)}")
    return 0 if exits == {130: len(rows)} and identical == len(rows) else 1


if __name__ == "__main__":
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    raise SystemExit(main())
