"""The study's report: the claims over all rows, then every disagreement and failure."""

from __future__ import annotations

import math
from collections import Counter

import numpy as np

from frictiondisk.studies.wellposed.judge import (
    disagrees,
    end_claims,
    end_contradicted,
    missed_jump,
    silent,
    verdict,
)
from frictiondisk.studies.wellposed.scenes import describe
from frictiondisk.studies.wellposed.settings import PERSIST_STEPS, SETTINGS, TOL
from frictiondisk.tasks.jump_search.jump_result import NO_JUMP
from frictiondisk.verdict.outcomes import STICK


def report(rows: list[dict], wall_s: float) -> list[str]:
    """The report's lines (wall_s: this invocation's wall time [s])."""
    settings = [s for s in SETTINGS if all(s in r for r in rows)]
    differ = [
        r for r in rows if "reference" in settings and disagrees(r["default"], r["reference"])
    ]
    lines = [f"well-posedness study: {len(rows)} scenes, tol {TOL:g}, {wall_s:.0f} s"]
    lines += settled_lines(rows, differ)
    lines += answer_lines(rows, settings)
    lines += cost_lines(rows, settings)
    lines += row_lines(rows, differ)
    return lines


def settled_lines(rows: list[dict], differ: list[dict]) -> list[str]:
    """Disagreements by who was right, silent errors (bracket ends contradicted by their
    watches among them), missed jumps."""
    counts = Counter(verdict(r) for r in differ)
    missed = [r for r in differ if missed_jump(r)]
    watched = [r for r in rows if r.get("ends")]
    contradicted = [r for r in watched if end_contradicted(r)]
    return [
        f"  default against the dense reference: {len(differ)} disagree; settled run by run: "
        + ", ".join(
            f"{k} right {v}" if k in ("default", "reference", "both") else f"{k} {v}"
            for k, v in sorted(counts.items())
        ),
        f"  silent errors (settled against a certified default, or a certified bracket end "
        f"contradicted by its watch): {sum(map(silent, rows))}",
        f"  missed jumps (sticking at the reference's lower mu_hi and at mu_hi + "
        f"{', '.join(map(str, PERSIST_STEPS))} tol): {len(missed)}, "
        f"{sum(1 for r in missed if r['default'].certified)} of them certified by the default",
        f"  certified brackets whose ends were watched: {len(watched)}; an end contradicted "
        f"by its watch: {len(contradicted)}",
        end_watch_line(watched),
    ]


def end_watch_line(watched: list[dict]) -> str:
    """What the watches of certified bracket ends showed: the end's claim confirmed,
    contradicted, or left open (undetermined, or the watches in conflict); how many
    contradicted ends were watched again at rtol / 100 and what that showed; how many the
    exact Coulomb integrator watched, and to what horizon at most."""
    shown, again = Counter(), Counter()
    exact = []
    for row in watched:
        claims = end_claims(row["default"])
        for run in row["ends"]:
            verdict = _end_verdict(run["sticks"], claims[run["mu"]])
            shown[verdict] += 1
            if "stricter" in run:
                again[verdict] += 1
            if "coulomb" in run:
                exact.append(run["coulomb"])
    text = (
        f"  bracket ends watched: {sum(shown.values())}: confirmed {shown['confirmed']}, "
        f"contradicted {shown['contradicted']}, open {shown['open']}"
    )
    if again:
        decided = sum(1 for row in watched for run in row["ends"] if "first" in run)
        text += (
            f"; ends watched again at rtol / 100: {sum(again.values())} (decided there "
            f"{decided}), then confirmed {again['confirmed']}, contradicted "
            f"{again['contradicted']}, open {again['open']}"
        )
    if exact:
        stuck = sum(1 for w in exact if w["outcome"] == STICK)
        longest = max(w["t_end"] for w in exact)
        text += (
            f"; exact Coulomb watches {len(exact)} (stick {stuck}, the longest to {longest:.0f} s)"
        )
    return text


def _end_verdict(sticks: bool | None, claim: bool) -> str:
    if sticks is None:
        return "open"
    return "confirmed" if sticks == claim else "contradicted"


def answer_lines(rows: list[dict], settings: list[str]) -> list[str]:
    """Failed points, points without a jump, certification, the grid below mu*, windows."""
    n = len(rows)
    default = [r["default"] for r in rows]
    failed = sum(1 for f in default if f.status == "failed")
    without = [r for r in rows if r["default"].status == NO_JUMP]
    # a scene in which no value of the whole grid sticks has no mu*: an answer (NO_JUMP),
    # not a failure; it is compared with the reference like any other
    agree = [r for r in without if "reference" in r and math.isnan(r["reference"].mu_star)]
    flags = Counter(f.certification for f in default)
    shares = [f.grid_share for f in default if math.isfinite(f.grid_share)]
    whole = sum(1 for s in shares if s >= 1.0)
    windowed = {s: sum(1 for r in rows if r[s].windows) for s in settings if s != "uncertified"}
    return [
        f"  failed points (honest, with a reason): {failed} of {n} "
        f"({100 * failed / max(1, n):.1f} %); no jump on the whole grid: {len(without)} "
        f"({len(agree)} as in the reference)",
        "  certification of the default: "
        + ", ".join(f"{k} {v}" for k, v in sorted(flags.items())),
        f"  grid below mu* decided: {whole} of {len(shares)} headlines on their whole grid "
        f"(mean share {np.mean(shares) if shares else math.nan:.3f}); resolution "
        f"{np.nanmax([f.resolution for f in default] or [math.nan]):.3g} at most",
        "  scenes with sticking windows: " + ", ".join(f"{s} {k}" for s, k in windowed.items()),
    ]


def cost_lines(rows: list[dict], settings: list[str]) -> list[str]:
    """Runs and kernel time per setting; certification's cost over the uncertified default."""
    walls = {s: sum(r[s].wall_s for r in rows) for s in settings}
    runs = {s: sum(r[s].runs for r in rows) for s in settings}
    uncertified = walls.get("uncertified", 0.0)
    extra = walls["default"] / uncertified - 1.0 if uncertified > 0 else math.nan
    return [
        "  runs: "
        + ", ".join(f"{s} {runs[s]}" for s in settings)
        + "; kernel wall time [s]: "
        + ", ".join(f"{s} {walls[s]:.1f}" for s in settings),
        f"  certification costs {100 * extra:+.0f} % kernel wall time over uncertified",
    ]


def row_lines(rows: list[dict], differ: list[dict]) -> list[str]:
    """Every disagreement with its watches, and every failed point with its reason."""
    lines = []
    if differ:
        lines.append("  disagreements (seed/scene: default mu* [cert], reference mu*, settled):")
    for r in differ:
        d, ref = r["default"], r["reference"]
        runs_text = "; ".join(
            f"{s['mu']:.5f} {s['outcome']} at {s['t_end']:.0f} s"
            for s in [*r["settled"], *r.get("persisted", [])]
        )
        lines.append(
            f"    {r['seed']}/{r['index']}: {d.mu_star:.5f} [{d.certification}] vs "
            f"{ref.mu_star:.5f} -> {verdict(r)} right; "
            f"{describe(r['scene'])}; runs: {runs_text}"
        )
    for r in rows:
        if "reference" in r and end_contradicted(r):
            d = r["default"]
            runs_text = "; ".join(
                f"{s['mu']:.7g} {s['outcome']} at {s['t_end']:.0f} s" for s in r["ends"]
            )
            lines.append(
                f"    end contradicted {r['seed']}/{r['index']}: [{d.mu_lo:.7g}, {d.mu_hi:.7g}] "
                f"[{d.certification}]; watches: {runs_text}; {describe(r['scene'])}"
            )
        if r["default"].status == "failed":
            lines.append(
                f"    failed {r['seed']}/{r['index']}: {r['default'].reason}; "
                f"{describe(r['scene'])}"
            )
    return lines
