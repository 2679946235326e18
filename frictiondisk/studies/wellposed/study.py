"""The study run end to end, on the engine: locate every scene's jumps under each setting,
then watch every disagreement, then assemble the rows.

Both steps are campaigns run into one output folder (frictiondisk.studies.campaigns), so
an interrupted study resumes from its journals: run the same command again.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from frictiondisk.studies import campaigns
from frictiondisk.studies.wellposed.found import read_found
from frictiondisk.studies.wellposed.judge import (
    certified_ends,
    combine_watches,
    contradicted_ends,
    disagrees,
    disputed,
    lower_reference,
)
from frictiondisk.studies.wellposed.rows import known_watches, read_rows, write_rows
from frictiondisk.studies.wellposed.scenes import coulomb_pin, draw
from frictiondisk.studies.wellposed.settings import (
    DEFAULT_STEP,
    PERSIST_STEPS,
    TOL,
    locate_campaign,
    locate_name,
    watch_campaign,
    watch_prefix,
    watch_scene,
)
from frictiondisk.verdict.outcomes import STICK, UNDETERMINED

SCENES_PER_CALL = 20  # scenes whose campaigns go to the engine together


@dataclasses.dataclass(frozen=True)
class Options:
    """How a study runs. reference False: the default and uncertified settings only (the
    cost of certification). observe: the default's certification watches
    (certify.observe). step: the default's prescan step. reference_from: a rows file or
    study folder whose references are taken instead of located again (the reference
    dominates the study's cost). settled_from: rows files or study folders whose settling
    runs are taken where the same scene and mu are disputed again. generator: the scene
    generator (scenes.GENERATORS)."""

    workers: int = 2
    reference: bool = True
    observe: bool = False
    step: float = DEFAULT_STEP
    reference_from: Path | None = None
    settled_from: tuple[Path, ...] = ()
    generator: int = 1
    watch_ends: bool = True
    exact_horizon: float | None = None
    recheck_confirmed: bool = False


def run_study(jobs: list[tuple[int, int]], out: Path, options: Options = Options()) -> list[dict]:
    """Every (seed, index) of `jobs`, located and settled into `out`; the rows, in job
    order, also written to out/rows.jsonl."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    references = read_rows(options.reference_from) if options.reference_from else {}
    rows: list[dict] = []
    scenes = {}
    for start in range(0, len(jobs), SCENES_PER_CALL):
        part = jobs[start : start + SCENES_PER_CALL]
        located, defaults = locate(part, out, options, references)
        rows += located
        scenes.update(defaults)
    if options.reference:
        known = known_watches(list(options.settled_from))
        settle(rows, scenes, out, options, known)
        recheck_contradicted_ends(rows, scenes, out, options)
    write_rows(out, rows)
    return rows


def locate(jobs, out: Path, options: Options, references: dict):
    """Rows with each setting's `Found` for `jobs`, and each scene's default point scene
    (the watches start from it)."""
    settings = ("default", "uncertified") + (("reference",) if options.reference else ())
    planned = {}  # (seed, index, setting) -> validated campaign
    generator = options.generator
    for seed, index in jobs:
        scene = draw(generator, seed, index)
        for setting in settings:
            if setting == "reference" and (seed, index) in references:
                continue
            name = locate_name(seed, index, setting, options.step, options.observe, generator)
            numerics = None
            if setting == "reference":
                num = planned[(seed, index, "default")].base.numerics
                numerics = {"t_decide": num.t_decide, "rtol": num.rtol, "atol": num.atol}
            data = locate_campaign(name, scene, setting, numerics, options.step, options.observe)
            planned[(seed, index, setting)] = campaigns.campaign(data)
    campaigns.run(planned.values(), out, options.workers)
    rows, defaults = [], {}
    for seed, index in jobs:
        row = {"seed": seed, "index": index, "scene": draw(generator, seed, index)}
        if generator != 1:
            row["generator"] = generator
        for setting in settings:
            campaign = planned.get((seed, index, setting))
            if campaign is None:
                row[setting] = references[(seed, index)]["reference"]
            else:
                row[setting] = read_found(out / campaign.name, campaign)
        row["settled"], row["persisted"], row["ends"] = [], [], []
        rows.append(row)
        defaults[(seed, index)] = planned[(seed, index, "default")].points()[0].config
    return rows, defaults


def watched_mu(row: dict) -> tuple[list[float], list[float], list[float]]:
    """The disputed mu of a disagreeing row, those above the reference's lower mu_hi
    watched for a jump the default missed (none where the scenes agree), and the ends of
    the default's headline bracket where it is certified (judge.end_contradicted)."""
    ends = certified_ends(row["default"])
    if not disagrees(row["default"], row["reference"]):
        return [], [], ends
    persist = []
    if lower_reference(row):
        persist = [row["reference"].mu_hi + k * TOL for k in PERSIST_STEPS]
    return disputed(row["default"], row["reference"]), persist, ends


def watches_of(scene: dict) -> tuple[str, ...]:
    """The watches a scene's disputes get: the regularized one; on a Coulomb pin the exact
    Coulomb integrator's too."""
    return ("regularized", "coulomb") if coulomb_pin(scene) else ("regularized",)


def settle(rows: list[dict], scenes: dict, out: Path, options: Options, known: dict) -> None:
    """Watch every disagreement at its disputed mu and every certified bracket's ends (a
    scan campaign per scene and watch, of the mu no earlier study watched), then give each
    row its settling runs."""
    scans = {}  # (seed, index, watch) -> the scan campaign of the mu it watches here
    for row in rows:
        key = (row["seed"], row["index"])
        wanted = sorted({mu for mus in _watched(row, options.watch_ends) for mu in mus})
        earlier = known.get(key, {})
        for watch in watches_of(row["scene"]):
            todo = [mu for mu in wanted if earlier_watch(earlier.get(mu), watch) is None]
            if todo:
                exact = watch == "coulomb"
                scene = watch_scene(scenes[key], exact=exact, exact_horizon=options.exact_horizon)
                prefix = watch_prefix(*key, watch, scene, options.generator)
                scans[(*key, watch)] = watch_campaign(prefix, scene, todo)
    campaigns.run(scans.values(), out, options.workers)
    shown = {where: read_watches(out / scan["name"]) for where, scan in scans.items()}
    for row in rows:
        settled, persisted, ends = _watched(row, options.watch_ends)
        row["settled"] = [settling_run(row, mu, shown, known) for mu in settled]
        row["persisted"] = [settling_run(row, mu, shown, known) for mu in persisted]
        row["ends"] = [settling_run(row, mu, shown, known) for mu in ends]


def recheck_contradicted_ends(rows: list[dict], scenes: dict, out: Path, options: Options) -> None:
    """Watch again, at rtol and atol / 100 more (settings.RECHECK_RTOL), each certified end
    whose regularized watch contradicts it: a slip of 1e-10 m a revolution read as a
    ratchet can be the watch's own integration error. The stricter watch takes the
    regularized one's place where it decides; the first stays in the run as `first`. An end
    the exact Coulomb integrator contradicts is not watched again (its tolerances are its
    own). options.recheck_confirmed: the ends their watches confirmed too, the control of
    that one-sided check."""
    scans = {}
    for row in rows:
        mus = to_recheck(row, options.recheck_confirmed)
        if mus:
            key = (row["seed"], row["index"])
            scene = watch_scene(scenes[key], stricter=True)
            prefix = watch_prefix(*key, "regularized", scene, options.generator)
            scans[key] = watch_campaign(prefix, scene, mus)
    if not scans:
        return
    campaigns.run(scans.values(), out, options.workers)
    for row in rows:
        key = (row["seed"], row["index"])
        if key in scans:
            stricter = read_watches(out / scans[key]["name"])
            row["ends"] = [rewatched(run, stricter.get(run["mu"])) for run in row["ends"]]


def to_recheck(row: dict, confirmed: bool = False) -> list[float]:
    """The contradicted ends of a row (judge.contradicted_ends), and with `confirmed` the
    confirmed ones too, that the exact Coulomb watch has not decided itself."""
    runs = {run["mu"]: run for run in row.get("ends", [])}
    contradicted = contradicted_ends(row)
    chosen = [
        mu
        for mu, run in runs.items()
        if run["sticks"] is not None and (confirmed or mu in contradicted)
    ]

    def exact_shows(run: dict) -> bool:
        exact = run.get("coulomb")
        return (
            exact is not None
            and exact["outcome"] != UNDETERMINED
            and (exact["outcome"] == STICK) == run["sticks"]
        )

    return [mu for mu in chosen if not exact_shows(runs[mu])]


def rewatched(run: dict, stricter: dict | None) -> dict:
    """The end's settling run with its regularized watch replaced by the stricter one
    where that decides (None, or undetermined: the run as it was, the re-watch noted)."""
    if stricter is None:
        return run
    if stricter["outcome"] == UNDETERMINED:
        return {**run, "stricter": stricter}
    first = {k: run[k] for k in ("outcome", "t_end", "reason")}
    again = combine_watches(run["mu"], stricter, run.get("coulomb"))
    return {**again, "first": first, "stricter": stricter}


def _watched(row: dict, watch_ends: bool) -> tuple[list[float], list[float], list[float]]:
    """watched_mu, without the bracket's ends where they are not watched."""
    settled, persisted, ends = watched_mu(row)
    return settled, persisted, ends if watch_ends else []


def earlier_watch(run: dict | None, watch: str) -> dict | None:
    """The watch `watch` of an earlier settling run, if it has one (a run without the
    exact Coulomb watch, from before it, has its regularized watch only)."""
    if run is None:
        return None
    if watch in run:
        return run[watch]
    if watch == "regularized":
        return {k: run[k] for k in ("outcome", "t_end", "reason")}
    return None


def settling_run(row: dict, mu: float, shown: dict, known: dict) -> dict:
    """The settling run at mu of a row: its watches, from this study's scans or from an
    earlier study's rows (then marked `reused`)."""
    key = (row["seed"], row["index"])
    earlier = known.get(key, {}).get(mu)
    watches, reused = {}, False
    for watch in watches_of(row["scene"]):
        found = earlier_watch(earlier, watch)
        reused |= found is not None
        watches[watch] = found if found is not None else shown[(*key, watch)][mu]
    run = combine_watches(mu, watches["regularized"], watches.get("coulomb"))
    return {**run, "reused": True} if reused else run


def read_watches(folder: Path) -> dict[float, dict]:
    """mu -> outcome, t_end and reason of every run of a watch scan."""
    ds = campaigns.results(folder)
    return {
        float(mu): {
            "outcome": str(ds.outcome.values[k]),
            "t_end": float(ds.t_end.values[k]),
            "reason": str(ds.reason.values[k]),
        }
        for k, mu in enumerate(ds.mu.values)
    }
