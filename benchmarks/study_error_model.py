"""The error model behind `numerics.rtol: auto`: mu* error per scene kind against rtol,
atol and the decision horizon, written to frictiondisk/model/numerics_error.csv.

For every kind of frictiondisk.model.auto_numerics (KIND_SCENES below: the default slave
at five axes offsets x_ms = 0.06 ... 0.14 m, x0 = 0) the jump is bisected (engine/local.py
bisect_setting: a bracket around it, the default limits and retries, no certification,
no journal) to a study tol far below any campaign's, under two ladders:

* `rtol`: rodas4 at rtol 1e-4 ... 1e-9 with atol = 1e-3 rtol and atol = 1e-6 rtol,
  t_decide 30 s; reference rtol 1e-10, atol 1e-16;
* `t_decide`: 10, 30, 120 s at rtol 1e-8, atol 1e-14; reference 480 s.

A row's error is |mu* - mu*_ref| plus both bracket half widths (an upper bound of the
error the bisection can see), the largest over the kind's points; its cost, accepted
steps per simulated second, the largest too. A setting whose bisection failed at any
point (undetermined runs near mu*) is kept with that status and never chosen. The
table's header records this command, the versions and the date.

    python benchmarks/study_error_model.py --processes 2 --cache out/error_model.jsonl --write
    python benchmarks/study_error_model.py --kinds pin          # print only
"""

from __future__ import annotations

import argparse
import concurrent.futures
import csv
import datetime
import io
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TABLE = ROOT / "frictiondisk" / "model" / "numerics_error.csv"

RTOLS = (1.0e-4, 1.0e-5, 1.0e-6, 1.0e-7, 1.0e-8, 1.0e-9)
ATOL_RATIOS = (1.0e-3, 1.0e-6)  # atol / rtol
RTOL_REFERENCE = (1.0e-10, 1.0e-16)
T_DECIDES = (10.0, 30.0, 120.0)  # [s]
T_REFERENCE = 480.0
T_NUMERICS = (1.0e-8, 1.0e-14)  # rtol, atol of the horizon ladder
DEFAULT_T = 30.0

# kind -> (base scene, {x_ms: bracket}, study tol). The brackets of a disk not started
# co-rotating hold its jump and leave out mu = c_s x_ms / F_n, where a disk from rest
# self-centres ever more slowly (docs/model.md); they come from a bisection to 1e-4.
_LINE = (0.06, 0.08, 0.1, 0.12, 0.14)  # axes offsets x_ms [m] of every kind
KIND_SCENES = {
    "pin": ({"scene": "pin", "params": {"x0": 0.0}}, dict.fromkeys(_LINE, [0.05, 0.3]), 1e-11),
    "disk_corotating": (
        {"scene": "disk", "params": {"x0": 0.0, "phidot0": 1.1}},
        dict.fromkeys(_LINE, [0.05, 0.3]),
        1.0e-11,
    ),
    "disk_from_rest": (
        {"scene": "disk", "params": {"x0": 0.0, "phidot0": 0.0}},
        {
            0.06: [0.061, 0.075],
            0.08: [0.081, 0.1],
            0.1: [0.105, 0.14],
            0.12: [0.121, 0.16],
            0.14: [0.145, 0.185],
        },
        1.0e-10,
    ),
    "disk_braked": (
        {"scene": "disk", "params": {"x0": 0.0, "phidot0": 0.0, "beta_b": 0.005}},
        {
            0.06: [0.16, 0.19],
            0.08: [0.18, 0.21],
            0.1: [0.19, 0.24],
            0.12: [0.225, 0.255],
            0.14: [0.245, 0.28],
        },
        1.0e-10,
    ),
    "stribeck": (
        {"scene": "pin", "params": {"x0": 0.0}, "contact": {"stribeck": {"r": 0.8, "v_s": 0.01}}},
        dict.fromkeys(_LINE, [0.05, 0.5]),
        1.0e-11,
    ),
}
COLUMNS = (
    "kind",
    "knob",
    "rtol",
    "atol",
    "t_decide",
    "is_reference",
    "status",
    "points",
    "error",
    "n_steps",
    "t_simulated",
)


def settings() -> list[tuple[str, float, float, float, bool]]:
    """(knob, rtol, atol, t_decide, is_reference) of both ladders, references last."""
    rows = [
        ("rtol", rtol, float(f"{ratio * rtol:.12g}"), DEFAULT_T, False)
        for rtol in RTOLS
        for ratio in ATOL_RATIOS
    ]
    rows.append(("rtol", *RTOL_REFERENCE, DEFAULT_T, True))
    rows += [("t_decide", *T_NUMERICS, t, False) for t in T_DECIDES]
    rows.append(("t_decide", *T_NUMERICS, T_REFERENCE, True))
    return rows


def campaign_of(kind: str, x_ms: float):
    from frictiondisk.tasks.campaign import campaign_from_dict

    scene, brackets, _ = KIND_SCENES[kind]
    task = {"bracket": brackets[x_ms], "along": {"params.x_ms": [x_ms]}}
    return campaign_from_dict({"name": f"error_model_{kind}", **scene, "find_jump": task})


def measure(kind: str, x_ms: float, rtol: float, atol: float, t_decide: float) -> dict:
    """One bisection of `kind` at x_ms with these numerics (in a worker process)."""
    from frictiondisk.engine.local import bisect_setting
    from frictiondisk.model.auto_numerics import scene_kinds

    campaign = campaign_of(kind, x_ms)
    base = campaign.points()[0].config
    assert kind in scene_kinds(base), (kind, scene_kinds(base))
    config = base.with_overrides(
        {"numerics.rtol": rtol, "numerics.atol": atol, "numerics.t_decide": t_decide}
    )
    out = bisect_setting(config, campaign.task, KIND_SCENES[kind][2])
    return {
        "status": out.status,
        "mu_star": out.mu_star,
        "half_width": out.half_width,
        "n_runs": out.n_runs,
        "n_undetermined": out.n_undetermined,
        "n_steps": out.n_steps,
        "t_simulated": out.t_simulated,
    }


def table_rows(kind: str, measured: dict) -> list[dict]:
    """The CSV rows of one kind: each setting against its knob's reference at each point;
    the largest error, the worst status and the largest cost over the points."""
    rows = []
    points = sorted(KIND_SCENES[kind][1])
    for knob, rtol, atol, t, is_ref in settings():
        ref = next((r, a, tt) for k, r, a, tt, ref in settings() if ref and k == knob)
        errors, costs, status = [], [], "converged"
        for x_ms in points:
            out, at_ref = measured[(x_ms, rtol, atol, t)], measured[(x_ms, *ref)]
            if out["status"] != "converged" or at_ref["status"] != "converged":
                status = out["status"] if out["status"] != "converged" else "reference failed"
                continue
            gap = abs(out["mu_star"] - at_ref["mu_star"])
            errors.append(gap + out["half_width"] + at_ref["half_width"])
            costs.append((out["n_steps"], out["t_simulated"]))
        steps, t_simulated = max(costs, key=lambda c: c[0] / c[1], default=(0, 1.0))
        rows.append(
            {
                "kind": kind,
                "knob": knob,
                "rtol": f"{rtol:g}",
                "atol": f"{atol:g}",
                "t_decide": f"{t:g}",
                "is_reference": int(is_ref),
                "status": status,
                "points": len(points),
                "error": f"{max(errors, default=float('nan')):.3g}",
                "n_steps": steps,
                "t_simulated": f"{t_simulated:.6g}",
            }
        )
    return rows


class Cache:
    """Finished bisections, one JSON line each, keyed by the setting and the kernel
    version (an interrupted study goes on where it stopped; a kernel change recomputes)."""

    def __init__(self, path: Path | None):
        from frictiondisk.store.journal_entry import kernel_version

        self.path, self.version, self.done = path, kernel_version(), {}
        if path is not None and path.is_file():
            for line in path.read_text().splitlines():
                item = json.loads(line)
                if item["kernel"] == self.version:
                    self.done[tuple(item["job"])] = item["out"]

    def put(self, job: tuple, out: dict) -> None:
        self.done[job] = out
        if self.path is not None:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            with self.path.open("a") as file:
                file.write(json.dumps({"kernel": self.version, "job": job, "out": out}) + "\n")


def header(argv: list[str]) -> str:
    from frictiondisk.store.journal_entry import kernel_version
    from frictiondisk.version import __version__

    command = " ".join(["python benchmarks/study_error_model.py", *argv])
    lines = [
        "The mu* error of the numerics per scene kind: the data of numerics auto",
        "(frictiondisk/model/auto_numerics.py; docs/accuracy.md, 'Numerics from the tol').",
        f"measured by: {command}",
        f"frictiondisk {__version__}, {kernel_version()}, {datetime.date.today()}",
        "error: the largest over the kind's points of |mu* - mu*_ref| + both bracket half "
        "widths; knob rtol: rodas4, t_decide 30 s,",
        f"reference rtol {RTOL_REFERENCE[0]:g}, atol {RTOL_REFERENCE[1]:g}; knob t_decide: "
        f"rtol {T_NUMERICS[0]:g}, atol {T_NUMERICS[1]:g}, reference {T_REFERENCE:g} s;",
        "cost: n_steps / t_simulated of the costliest point (accepted steps per simulated s).",
    ]
    for kind, (scene, brackets, tol) in KIND_SCENES.items():
        keys = json.dumps({k: v for k, v in scene.items() if k != "scene"})
        points = ", ".join(f"x_ms {x:g} bracket {b}" for x, b in brackets.items())
        lines.append(f"{kind}: {scene['scene']} {keys}; {points}; study tol {tol:g}")
    return "".join(f"# {line}\n" for line in lines)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kinds", default=",".join(KIND_SCENES), help="comma-separated kinds")
    parser.add_argument("--processes", type=int, default=1)
    parser.add_argument("--cache", type=Path, help="keep finished bisections here (JSON lines)")
    parser.add_argument("--write", action="store_true", help=f"write {TABLE.relative_to(ROOT)}")
    args = parser.parse_args(argv)
    kinds = args.kinds.split(",")
    unknown = sorted(set(kinds) - set(KIND_SCENES))
    if unknown:
        parser.error(f"--kinds: unknown kind {unknown[0]!r}; allowed: {', '.join(KIND_SCENES)}")
    if args.write and set(kinds) != set(KIND_SCENES):
        parser.error("--write needs every kind (the table is written whole)")
    cache = Cache(args.cache)
    # a scene on both ladders (rtol 1e-8, atol 1e-14, 30 s) is bisected once
    jobs = sorted(
        {
            (kind, x_ms, r, a, t)
            for kind in kinds
            for x_ms in KIND_SCENES[kind][1]
            for _, r, a, t, _ in settings()
        }
    )
    with concurrent.futures.ProcessPoolExecutor(args.processes) as pool:
        futures = {pool.submit(measure, *job): job for job in jobs if job not in cache.done}
        for future in concurrent.futures.as_completed(futures):
            job = futures[future]
            out = future.result()
            cache.put(job, out)
            kind, x_ms, r, a, t = job
            print(
                f"{kind:16s} x_ms {x_ms:4g} rtol {r:7.0e} atol {a:7.0e} t {t:4g} s: "
                f"{out['status']:9s} mu* {out['mu_star']:.12f} runs {out['n_runs']} "
                f"steps {out['n_steps']}",
                file=sys.stderr,
                flush=True,
            )
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, COLUMNS, lineterminator="\n")
    writer.writeheader()
    for kind in kinds:
        measured = {job[1:]: out for job, out in cache.done.items() if job[0] == kind}
        writer.writerows(table_rows(kind, measured))
    text = header(argv) + buffer.getvalue()
    print(text, end="")
    if args.write:
        TABLE.write_text(text, encoding="utf-8")
        print(f"written: {TABLE.relative_to(ROOT)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
