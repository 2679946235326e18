"""Well-posedness study: is the certified headline mu* true, checked against a dense
reference and settled run by run?

Draws seeded random scenes (pin and disk; random x_ms, x0, m_s, omega_m, J_s, phidot0,
beta_b; a Stribeck curve on half of them) and locates every jump of each three times:

* `default`: the campaign defaults (prescan 0.02 ... 0.80 step 0.01, adaptive, the numerics
  a tol of 1e-4 chooses, certification on);
* `uncertified`: the same with certification off (what the extra wall time is against);
* `reference`: a dense prescan (step 0.01, every value run), horizon x 8, rtol and atol
  / 100.

A scene *disagrees* when the headline mu* (the lowest rising jump that persists) of the
default and the reference differ by more than tol, or one finds a headline and the other
none. Every disagreement is *settled run by run*: each verdict the two settings claim at
the disputed mu (their headline brackets' ends and every decided value between the two
headlines) is run again with a long horizon (SETTLE_HORIZON s, horizon_budget SETTLE_BUDGET,
rtol / 100) under `numerics.evidence: observe`, where only what the run shows counts (it
sticks, or its section repeats), never an extrapolation; a pin with Coulomb friction is
watched by the exact Coulomb integrator too (no regularization; it sticks, creeps onto
the rim of its sticking disc, or its stick onsets repeat), and two watches that show
different verdicts settle nothing. The table says which side was right: the default
(then the reference missed or misjudged something), the reference (then the default's
verdict was wrong: *silent* if the default called that point certified), both (a window
between their samples, narrower than the default's grid), or neither settled. A watch
that stays undetermined leaves a dispute open only where the two sides claim different
things there (`implied_claim`: below its headline bracket a side says "does not stick",
over its persistence width above it "sticks").

Where the reference's headline lies lower, a jump the default's grid stepped over is
checked too: where the settling run at the reference's mu_hi sticks and the slave sticks,
watched the same way, at mu_hi + 2, 5, 10 and 20 tol (PERSIST_STEPS), sticking persists
below the default's headline, so the lowest rising jump lies lower: the default is wrong
about its headline, whatever its verdicts at the values it ran (a *missed jump*; silent if
certified).

    python benchmarks/study_wellposed.py                       # seeds 1-10, 50 scenes each
    python benchmarks/study_wellposed.py --seeds 1 --scenes 4 --processes 1
    python benchmarks/study_wellposed.py --cache out/wellposed.jsonl   # resumable
    # a change to the default's rules against the references an earlier run computed:
    python benchmarks/study_wellposed.py --reference-from out/wellposed.jsonl --cache out/d.jsonl

Exit 1 if any default verdict is settled against a certified default.
"""

from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import math
import multiprocessing
import os
import sys
import time
from pathlib import Path

import numpy as np

from frictiondisk.tasks.jump_search.jump_result import NO_JUMP

TOL = 1.0e-4
# the default's prescan step: 0.01 (the issue's own campaign, 58 values over 0.03 ... 0.6,
# and the shipped campaigns) unless --default-step, which sets it here so that the spawned
# workers, which import this module afresh, see it too
DEFAULT_STEP = 0.01
DEFAULT_STEP_ENV = "FRICTIONDISK_STUDY_DEFAULT_STEP"


def default_grid(step: float) -> tuple[float, ...]:
    """The default's prescan: mu = 0.02 ... 0.80 in steps of `step`."""
    n_values = math.floor(0.78 / step + 1e-9) + 1  # the last value <= 0.80
    return tuple(round(0.02 + step * k, 5) for k in range(n_values))


PRESCAN = default_grid(float(os.environ.get(DEFAULT_STEP_ENV, repr(DEFAULT_STEP))))
REFERENCE_PRESCAN = default_grid(0.01)  # 0.02 ... 0.80, every value run
REFERENCE_HORIZON = 8.0
REFERENCE_RTOL = 0.01
SETTLE_HORIZON = 1500.0  # [s] t_decide of a settling run
SETTLE_BUDGET = 8.0  # its horizon_budget: up to 12 000 s
SETTLE_RTOL = 0.01  # rtol factor of a settling run
SETTLE_EPS = 0.01  # eps factor of a settling run: slip eps T a revolution counts as none,
# and a braked disk's answer moves with eps below its Melan bound (docs/model.md section 6)
COULOMB_MAX_STEPS = 50_000_000  # scipy Radau steps of an exact Coulomb watch
SETTLE_MAX = 6  # settling runs per disagreement at most (the nearest to the dispute)
SETTINGS = ("default", "uncertified", "reference")
PERSIST = 3.0  # [tol] a headline's persistence width (prescan.persist's default)
PERSIST_STEPS = (2, 5, 10, 20)  # [tol] above the reference's mu_hi, watched for a missed jump


def draw_scene(seed: int, index: int) -> dict:
    """The scene dict of scene `index` of the study seeded `seed`: a pin for even index, a
    disk for odd; a Stribeck curve on every other pin and every other disk."""
    rng = np.random.default_rng([seed, index])
    scene = "disk" if index % 2 else "pin"
    omega_m = float(rng.uniform(0.6, 1.6))
    params = {
        "x_ms": float(rng.uniform(0.05, 0.15)),
        "x0": float(rng.uniform(-0.03, 0.03)),
        "m_s": float(rng.uniform(0.5, 2.0)),
        "omega_m": omega_m,
    }
    if scene == "disk":
        params["J_s"] = float(rng.uniform(0.005, 0.2))
        params["phidot0"] = float(rng.choice([0.0, omega_m]))
        params["beta_b"] = float(rng.choice([0.0, rng.uniform(0.0, 0.01)]))
    contact: dict = {}
    stribeck = {"r": float(rng.uniform(0.6, 0.95)), "v_s": float(10.0 ** rng.uniform(-3, -1.5))}
    if (index // 2) % 2 == 1:
        contact["stribeck"] = stribeck
    return {"scene": scene, "params": params, "contact": contact}


@dataclasses.dataclass(frozen=True)
class Found:
    """What one setting found for one scene."""

    status: str
    reason: str
    mu_star: float  # headline (NaN: none)
    mu_lo: float
    mu_hi: float
    n_jumps: int
    windows: tuple[tuple[float, float], ...]
    certification: str
    grid_share: float  # share of the grid below mu* with a decided verdict (NaN: no headline)
    resolution: float  # largest gap between decided mu below mu* (NaN: no headline)
    claims: tuple[tuple[float, bool], ...]  # every decided (mu, sticks) of the search
    runs: int
    wall_s: float  # kernel wall time of every run [s]

    @property
    def certified(self) -> bool:
        return self.status in ("converged", NO_JUMP) and self.certification in (
            "certified",
            "recertified",
        )


def _config(scene: dict, setting: str):
    """The scene with the numerics a find_jump campaign at TOL gives it (numerics auto,
    frictiondisk/model/auto_numerics.py); the reference's horizon x 8, rtol and atol / 100."""
    from frictiondisk.model.auto_numerics import for_campaign
    from frictiondisk.model.scene import scene_from_dict

    config = scene_from_dict(scene)
    choice = for_campaign(config, {}, TOL, scene.get("numerics"))
    if choice.chosen:
        config = config.with_overrides(choice.overrides())
    if setting == "reference":
        num = config.numerics
        config = config.with_overrides(
            {
                "numerics.t_decide": num.t_decide * REFERENCE_HORIZON,
                "numerics.rtol": num.rtol * REFERENCE_RTOL,
                "numerics.atol": num.atol * REFERENCE_RTOL,
            }
        )
    return config


def _answer_claims(search) -> tuple[tuple[float, bool], ...]:
    """(mu, sticks) that the search's answer stands on: its decided values at the point's
    numerics, except where certification moved a jump (those are superseded), and the ends
    of every final bracket at the level that certified it."""
    claims = dict(search.known())
    for bisection in search.bisections:
        res = bisection.result()
        if res.status != "converged" or res.certification == "vanished":
            continue
        base = bisection.searches[0].result()
        if len(bisection.searches) > 1 and base.status == "converged":
            lo, hi = min(base.mu_lo, res.mu_lo), max(base.mu_hi, res.mu_hi)
            claims = {mu: stick for mu, stick in claims.items() if not lo <= mu <= hi}
        claims[res.mu_lo] = not res.rising
        claims[res.mu_hi] = res.rising
    return tuple((float(mu), bool(stick)) for mu, stick in sorted(claims.items()))


def locate(scene: dict, setting: str, observe: bool = False) -> Found:
    """Prescan and bisect every jump of `scene` under `setting` (module docstring)."""
    from frictiondisk.engine.worker import run_bisection
    from frictiondisk.model.search_settings import DEFAULT_MAX_RETRIES, OFF, Certify
    from frictiondisk.tasks.jump_search.jumps import JumpSearch
    from frictiondisk.tasks.jump_search.prescan import default_stride

    config = _config(scene, setting)
    grid = REFERENCE_PRESCAN if setting == "reference" else PRESCAN
    stride = 1 if setting == "reference" else default_stride(len(grid), "decide", "corotation")
    certify = Certify(observe=observe) if setting == "default" else OFF
    search = JumpSearch(grid, TOL, DEFAULT_MAX_RETRIES, "decide", 2, certify, stride=stride)
    search, _ = run_bisection(search, config.canonical(), 2.0, os.devnull)
    result = search.result()
    runs = [run.result for run in result.runs]
    head = search.headline()
    below = result.grid_below
    return Found(
        status=result.status,
        reason=result.reason,
        mu_star=head.mu_star if head is not None else math.nan,
        mu_lo=head.mu_lo if head is not None else math.nan,
        mu_hi=head.mu_hi if head is not None else math.nan,
        n_jumps=len(result.jumps),
        windows=tuple((float(w.lo), float(w.hi)) for w in result.windows),
        certification=result.certification,
        grid_share=below.share if below is not None else math.nan,
        resolution=below.resolution if below is not None else math.nan,
        claims=_answer_claims(search),
        runs=len(runs),
        wall_s=float(sum(run.get("wall_s", 0.0) for run in runs)),
    )


def disagrees(found: Found, reference: Found) -> bool:
    """Headline mu* more than TOL apart, or a headline on one side only."""
    a, b = found.mu_star, reference.mu_star
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) != math.isnan(b)
    return abs(a - b) > TOL * (1 + 1e-9)


def disputed(default: Found, reference: Found) -> list[float]:
    """The mu whose verdicts settle a disagreement: both headline brackets' ends and every
    value either setting decided between the two headlines (the SETTLE_MAX nearest)."""
    heads = [m for m in (default.mu_star, reference.mu_star) if math.isfinite(m)]
    ends = [m for f in (default, reference) for m in (f.mu_lo, f.mu_hi) if math.isfinite(m)]
    if not heads:
        return []
    lo, hi = min(heads) - TOL, max(heads) + TOL
    inside = {mu for f in (default, reference) for mu, _ in f.claims if lo <= mu <= hi}
    centre = 0.5 * (lo + hi)
    inside = sorted(inside - set(ends), key=lambda mu: abs(mu - centre))
    return sorted({*ends, *inside[: max(0, SETTLE_MAX - len(ends))]})


WATCH = ("outcome", "t_end", "reason")  # what a settling run keeps of each watch


def _watched(result) -> dict:
    return {k: getattr(result, k) for k in WATCH}


def coulomb_pin(scene: dict) -> bool:
    """A pin with Coulomb friction: the exact Coulomb integrator watches it too."""
    stribeck = scene.get("contact", {}).get("stribeck") or {}
    return scene["scene"] == "pin" and stribeck.get("r", 1.0) == 1.0


def settle(scene: dict, mu: float, longer: int = 1, regularized: dict | None = None) -> dict:
    """Long runs at mu that count only what they show (numerics.evidence: observe): the
    regularized model at rtol, atol and eps / 100 and, on a Coulomb pin, the exact Coulomb
    integrator (numerics.method coulomb, no regularization: its stick onsets repeat, or
    creep onto the rim of the sticking disc, frictiondisk/verdict/rim_approach.py) over
    the same horizon. The verdict is the one they show; where both show one and they
    differ, none. longer: a factor on the horizon budget and the step budget
    (benchmarks/settle_longer.py); regularized: that watch's outcome, t_end and reason from
    an earlier call with the same longer, taken instead of run again."""
    from frictiondisk.simulation.simulate import simulate

    config = _config(scene, "default")
    num = config.numerics
    config = config.with_overrides(
        {
            "params.mu": mu,
            "numerics.t_decide": SETTLE_HORIZON,
            "numerics.horizon_budget": SETTLE_BUDGET * longer,
            "numerics.max_steps": num.max_steps * longer,
            "numerics.rtol": num.rtol * SETTLE_RTOL,
            "numerics.atol": num.atol * SETTLE_RTOL,
            "contact.eps": config.contact.eps * SETTLE_EPS,
            "numerics.evidence": "observe",
        }
    )
    watches = [
        {k: regularized[k] for k in WATCH}
        if regularized is not None
        else _watched(simulate(config))
    ]
    if coulomb_pin(scene):
        exact = config.with_overrides(
            {
                "numerics.method": "coulomb",
                "numerics.t_decide": SETTLE_HORIZON * SETTLE_BUDGET * longer,
                "numerics.max_steps": COULOMB_MAX_STEPS * longer,
            }
        )
        watches.append(_watched(simulate(exact)))
    decided = [w for w in watches if w["outcome"] != "undetermined"]
    shown = {w["outcome"] == "stick" for w in decided}
    head = decided[0] if decided else watches[0]
    run = {
        "mu": mu,
        "outcome": head["outcome"] if len(shown) < 2 else "conflict",
        "sticks": next(iter(shown)) if len(shown) == 1 else None,
        "t_end": head["t_end"],
        "reason": "; ".join(w["reason"] for w in decided) if len(decided) > 1 else head["reason"],
    }
    if len(watches) > 1:
        run["regularized"], run["coulomb"] = watches
    return run


def claim_at(found: Found, mu: float) -> bool | None:
    for m, stick in found.claims:
        if m == mu:
            return stick
    return None


def lower_reference(row: dict) -> bool:
    """The reference's headline lies more than tol below the default's."""
    d, ref = row["default"].mu_star, row["reference"].mu_star
    return math.isfinite(d) and math.isfinite(ref) and ref < d - TOL * (1 + 1e-9)


def missed_jump(row: dict) -> bool:
    """Sticking that persists below the default's headline: the settling run at the
    reference's lower mu_hi sticks, and so does every watching run PERSIST_STEPS above it.
    The lowest rising jump then lies at or below that mu_hi (below it still where the
    reference's mu_lo sticks too), and the default did not report it. A default bracket that
    holds that mu_hi (one straddling undetermined mu, wider than tol) reported it."""
    if not lower_reference(row) or not row.get("persisted"):
        return False
    if row["reference"].mu_hi >= row["default"].mu_lo:
        return False
    seen = {run["mu"]: run["sticks"] for run in row["settled"]}
    sticks_above = seen.get(row["reference"].mu_hi) is True
    return sticks_above and all(run["sticks"] is True for run in row["persisted"])


def implied_claim(found: Found, mu: float) -> bool | None:
    """A side's claim at mu: the verdict it decided there; else, below its headline
    bracket, 'does not stick' (its headline is the lowest rising jump), and over the
    persistence width above it, 'sticks' (its headline persists)."""
    claim = claim_at(found, mu)
    if claim is not None or not math.isfinite(found.mu_star):
        return claim
    if mu < found.mu_lo:
        return False
    if found.mu_hi <= mu <= found.mu_hi + PERSIST * TOL:
        return True
    return None


def verdict(row: dict) -> str:
    """Which side the settling runs proved right: default (its claims stand; the
    reference's are refuted, or some stay open), reference, both (a window between their
    samples), neither, or unsettled (a claim of the default is open). A decided verdict
    refutes the side that claimed otherwise there; a missed jump (`missed_jump`) makes the
    default wrong. A watch that ends undetermined leaves open each side's claim there
    (`implied_claim`) where the two differ; where both say the same, as on a scene where
    they agree, the dispute is not there."""
    wrong = {"default": missed_jump(row), "reference": False}
    open_ = {"default": False, "reference": False}
    for run in row["settled"]:
        claims = {side: implied_claim(row[side], run["mu"]) for side in wrong}
        for side in wrong:
            if run["sticks"] is None:
                open_[side] |= claims[side] is not None and len(set(claims.values())) > 1
            elif claim_at(row[side], run["mu"]) not in (None, run["sticks"]):
                wrong[side] = True
    if wrong["default"] and wrong["reference"]:
        return "neither"
    if wrong["default"]:
        return "reference"
    if open_["default"]:
        return "unsettled"
    if wrong["reference"] or open_["reference"]:
        return "default"
    return "both"


def study_scene(args: tuple[int, int, bool, bool, dict | None, dict]) -> dict:
    """One row; `known_reference`: the reference of an earlier study of this scene (its
    JSON), taken instead of located again; `known_settled`: mu -> a settling run of an
    earlier study at this scene and mu, taken instead of run again (marked `reused`)."""
    seed, index, reference, observe, known_reference, known_settled = args
    scene = draw_scene(seed, index)
    row = {"seed": seed, "index": index, "scene": scene}
    for setting in SETTINGS if reference else SETTINGS[:2]:
        if setting == "reference" and known_reference is not None:
            row[setting] = _from_json({setting: known_reference})[setting]
        else:
            row[setting] = locate(scene, setting, observe)
    row["settled"] = []
    row["persisted"] = []

    def settled_at(mu: float) -> dict:
        known = known_settled.get(mu)
        if known is not None and coulomb_pin(scene) and "coulomb" not in known:
            # settled before the exact Coulomb watch: add it, reusing the regularized one
            return {**settle(scene, mu, regularized=known), "reused": True}
        if known is not None:
            return {**known, "reused": True}
        return settle(scene, mu)

    if reference and disagrees(row["default"], row["reference"]):
        row["settled"] = [settled_at(mu) for mu in disputed(row["default"], row["reference"])]
        if lower_reference(row):
            above = row["reference"].mu_hi
            row["persisted"] = [settled_at(above + k * TOL) for k in PERSIST_STEPS]
    return row


def _known_settled(paths: list[Path]) -> dict[tuple[int, int], dict[float, dict]]:
    """(seed, index) -> mu -> every settling run in the rows of `paths` (JSON lines). A
    settling run watches (numerics.evidence observe): it reads neither the default's rules
    nor the bound, so a change to those leaves it as it was. A change to the settling
    numerics (SETTLE_*) or to the kernel's integration makes these stale: then run afresh."""
    known: dict[tuple[int, int], dict[float, dict]] = {}
    for path in paths:
        for line in path.read_text().splitlines():
            entry = json.loads(line)
            runs = entry["row"].get("settled", []) + entry["row"].get("persisted", [])
            scene = known.setdefault((entry["seed"], entry["index"]), {})
            for run in runs:
                scene[float(run["mu"])] = {k: v for k, v in run.items() if k != "reused"}
    return known


CODE = ("kernel", "outcome", "simulation", "search", "model")  # what decides a row


def _code_hash() -> str:
    """A hash of this study and of the packages that decide its rows (not the engine, the
    store or the figures): a cached row is reused only with all of them unchanged."""
    root = Path(__file__).resolve().parents[1] / "frictiondisk"
    digest = hashlib.sha256(Path(__file__).read_bytes())
    for package in CODE:
        for source in sorted((root / package).rglob("*.py")):
            digest.update(source.read_bytes())
    return digest.hexdigest()[:16]


def _to_json(row: dict) -> dict:
    return {k: dataclasses.asdict(v) if isinstance(v, Found) else v for k, v in row.items()}


def _from_json(row: dict) -> dict:
    out = dict(row)
    for setting in [s for s in SETTINGS if s in row]:
        data = dict(row[setting])
        data["windows"] = tuple(tuple(w) for w in data["windows"])
        data["claims"] = tuple(tuple(c) for c in data["claims"])
        out[setting] = Found(**data)
    return out


def _warm_up() -> None:
    """Load (or compile) the kernel in a worker before it times any run: a process's first
    row otherwise counts the compile as kernel time of its first setting (the default)."""
    from frictiondisk.engine.worker import warm_up

    warm_up()


def _known_references(path: Path) -> tuple[dict[tuple[int, int], dict], str]:
    """(seed, index) -> the reference (JSON) of every row in `path`, and the code of those
    rows (one code only: a reference mixed from several codes would be no one reference)."""
    known, codes = {}, set()
    for line in path.read_text().splitlines():
        entry = json.loads(line)
        if "reference" in entry["row"]:
            known[(entry["seed"], entry["index"])] = entry["row"]["reference"]
            codes.add(entry["code"])
    if len(codes) != 1:
        raise SystemExit(f"{path}: references of {len(codes)} codes ({sorted(codes)}), need one")
    return known, codes.pop()


def run_study(
    seeds,
    scenes: int,
    processes: int,
    cache: Path | None = None,
    reference: bool = True,
    observe: bool = False,
    reference_from: Path | None = None,
    only: str = "all",
    settled_from: list[Path] | None = None,
) -> list[dict]:
    """Every scene of every seed; rows already in `cache` (same code) are not run again.
    reference False: the default and uncertified settings only (the cost of certification).
    observe: the default's certification watches (certify.observe). reference_from: take
    each scene's reference from the rows of an earlier study (JSON lines, any code) instead
    of locating it again (the reference dominates the study's cost); the disagreements are
    settled anew. only: "braked", the disks with a brake (beta_b > 0), the class that the
    co-rotation verdict decides; "unbraked", the other scenes; "all". settled_from: the
    rows of earlier studies whose settling runs are taken where the same scene and mu are
    disputed again (`_known_settled`)."""
    known, ref_code = _known_references(reference_from) if reference_from else ({}, "")
    settled = _known_settled(settled_from or [])
    jobs = [
        (seed, index, reference, observe, known.get((seed, index)), settled.get((seed, index), {}))
        for seed in seeds
        for index in range(scenes)
        if only == "all" or (only == "braked") == _braked(draw_scene(seed, index))
    ]
    code = _code_hash() + ("" if reference else "-cost") + ("-observe" if observe else "")
    code += f"-grid-{PRESCAN[0]}-{PRESCAN[1] - PRESCAN[0]:.4g}-{len(PRESCAN)}"
    code += f"-reference-of-{ref_code}" if ref_code else ""
    done: dict[tuple[int, int], dict] = {}
    if cache is not None and cache.is_file():
        for line in cache.read_text().splitlines():
            entry = json.loads(line)
            if entry.get("code") == code:
                done[(entry["seed"], entry["index"])] = _from_json(entry["row"])
    todo = [job for job in jobs if job[:2] not in done]

    def keep(row):
        done[(row["seed"], row["index"])] = row
        if cache is not None:
            with cache.open("a") as f:
                entry = {"code": code, "seed": row["seed"], "index": row["index"]}
                f.write(json.dumps({**entry, "row": _to_json(row)}) + "\n")

    if processes <= 1:
        _warm_up()
        for job in todo:
            keep(study_scene(job))
    else:
        with multiprocessing.get_context("spawn").Pool(processes, _warm_up) as pool:
            for row in pool.imap_unordered(study_scene, todo):
                keep(row)
    return [done[job[:2]] for job in jobs]


def _braked(scene: dict) -> bool:
    return scene["scene"] == "disk" and scene["params"].get("beta_b", 0.0) > 0.0


def describe(scene: dict) -> str:
    params = ", ".join(f"{k} {v:.4g}" for k, v in scene["params"].items())
    stribeck = " Stribeck" if scene["contact"].get("stribeck") else ""
    return f"{scene['scene']}{stribeck}: {params}"


def report(rows: list[dict], wall_s: float) -> list[str]:
    n = len(rows)
    default = [r["default"] for r in rows]
    failed = [r for r in rows if r["default"].status == "failed"]
    without = [r for r in rows if r["default"].status == NO_JUMP]
    lines = [f"well-posedness study: {n} scenes, tol {TOL:g}, {wall_s:.0f} s"]
    settings = [s for s in SETTINGS if all(s in r for r in rows)]
    differ = [
        r for r in rows if "reference" in settings and disagrees(r["default"], r["reference"])
    ]
    verdicts = {(r["seed"], r["index"]): verdict(r) for r in differ}
    silent = [
        r
        for r in differ
        if verdicts[(r["seed"], r["index"])] in ("reference", "neither") and r["default"].certified
    ]
    counts: dict[str, int] = {}
    for v in verdicts.values():
        counts[v] = counts.get(v, 0) + 1
    lines.append(
        f"  default against the dense reference: {len(differ)} disagree; settled run by run: "
        + ", ".join(
            f"{k} right {v}" if k in ("default", "reference", "both") else f"{k} {v}"
            for k, v in sorted(counts.items())
        )
    )
    lines.append(f"  silent errors (settled against a certified default): {len(silent)}")
    missed = [r for r in differ if missed_jump(r)]
    lines.append(
        f"  missed jumps (sticking at the reference's lower mu_hi and at mu_hi + "
        f"{', '.join(map(str, PERSIST_STEPS))} tol): {len(missed)}, "
        f"{sum(1 for r in missed if r['default'].certified)} of them certified by the default"
    )
    # a scene in which no value of the whole grid sticks has no mu*: an answer (NO_JUMP),
    # not a failure; it is compared with the reference like any other
    agree = [r for r in without if "reference" in r and math.isnan(r["reference"].mu_star)]
    lines.append(
        f"  failed points (honest, with a reason): {len(failed)} of {n} "
        f"({100 * len(failed) / max(1, n):.1f} %); no jump on the whole grid: {len(without)} "
        f"({len(agree)} as in the reference)"
    )
    flags: dict[str, int] = {}
    for f in default:
        flags[f.certification] = flags.get(f.certification, 0) + 1
    lines.append(
        "  certification of the default: " + ", ".join(f"{k} {v}" for k, v in sorted(flags.items()))
    )
    shares = [f.grid_share for f in default if math.isfinite(f.grid_share)]
    whole = sum(1 for s in shares if s >= 1.0)
    lines.append(
        f"  grid below mu* decided: {whole} of {len(shares)} headlines on their whole grid "
        f"(mean share {np.mean(shares) if shares else math.nan:.3f}); resolution "
        f"{np.nanmax([f.resolution for f in default] or [math.nan]):.3g} at most"
    )
    windowed = {s: sum(1 for r in rows if r[s].windows) for s in settings if s != "uncertified"}
    lines.append(
        "  scenes with sticking windows: " + ", ".join(f"{s} {k}" for s, k in windowed.items())
    )
    walls = {s: sum(r[s].wall_s for r in rows) for s in settings}
    runs = {s: sum(r[s].runs for r in rows) for s in settings}
    extra = walls["default"] / walls["uncertified"] - 1.0 if walls["uncertified"] > 0 else math.nan
    lines.append(
        "  runs: "
        + ", ".join(f"{s} {runs[s]}" for s in settings)
        + "; kernel wall time [s]: "
        + ", ".join(f"{s} {walls[s]:.1f}" for s in settings)
    )
    lines.append(f"  certification costs {100 * extra:+.0f} % kernel wall time over uncertified")
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
            f"{ref.mu_star:.5f} -> {verdicts[(r['seed'], r['index'])]} right; "
            f"{describe(r['scene'])}; runs: {runs_text}"
        )
    for r in failed:
        lines.append(
            f"    failed {r['seed']}/{r['index']}: {r['default'].reason}; {describe(r['scene'])}"
        )
    return lines


def silent_errors(rows: list[dict]) -> int:
    return sum(
        1
        for r in rows
        if "reference" in r
        and disagrees(r["default"], r["reference"])
        and verdict(r) in ("reference", "neither")
        and r["default"].certified
    )


def _seeds(text: str) -> list[int]:
    if "-" in text:
        a, b = text.split("-")
        return list(range(int(a), int(b) + 1))
    return [int(s) for s in text.split(",")]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="1-10", help="e.g. 1-10 or 1,3")
    parser.add_argument("--scenes", type=int, default=50, help="scenes per seed")
    parser.add_argument("--processes", type=int, default=2)
    parser.add_argument(
        "--default-step",
        type=float,
        default=None,
        help=f"prescan step of the default and uncertified settings (default {DEFAULT_STEP})",
    )
    parser.add_argument("--cache", type=Path, default=None, help="JSON lines of finished rows")
    parser.add_argument(
        "--cost-only", action="store_true", help="no reference: the cost of certification only"
    )
    parser.add_argument(
        "--observe", action="store_true", help="the default certifies watching (certify.observe)"
    )
    parser.add_argument(
        "--reference-from",
        type=Path,
        default=None,
        help="take each scene's reference from an earlier study's rows (a change to the "
        "default's rules, checked against the reference already computed)",
    )
    subset = parser.add_mutually_exclusive_group()
    subset.add_argument(
        "--braked-only",
        action="store_true",
        help="only the disks with a brake (beta_b > 0): a change to the co-rotation verdict",
    )
    subset.add_argument(
        "--unbraked-only",
        action="store_true",
        help="only the scenes without a brake (pins, unbraked disks)",
    )
    parser.add_argument(
        "--settled-from",
        type=Path,
        action="append",
        default=[],
        help="take settling runs at a disputed scene and mu from an earlier study's rows "
        "(JSON lines; repeatable): they watch, so a change to the rules leaves them as they were",
    )
    args = parser.parse_args(argv)
    if args.default_step is not None:
        os.environ[DEFAULT_STEP_ENV] = repr(args.default_step)
        global PRESCAN
        PRESCAN = default_grid(args.default_step)
    t0 = time.perf_counter()
    rows = run_study(
        _seeds(args.seeds),
        args.scenes,
        args.processes,
        args.cache,
        not args.cost_only,
        args.observe,
        args.reference_from,
        "braked" if args.braked_only else "unbraked" if args.unbraked_only else "all",
        args.settled_from,
    )
    print("\n".join(report(rows, time.perf_counter() - t0)))
    return 1 if silent_errors(rows) else 0


if __name__ == "__main__":
    sys.exit(main())
