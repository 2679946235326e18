"""What every campaign figure shares, its common layers: axis labels, outcome styles, the
caption line, the figure frame (plot, note, caption), the note box, the rug strip for
points without a value, every run as a dot. Each task draws its own figure
(frictiondisk/tasks/<task>/figure*.py) from these; nothing here imports a task, nor the
kernel.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
import xarray as xr
import yaml
from matplotlib.axes import Axes
from matplotlib.figure import Figure, SubFigure
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.ticker import FuncFormatter

from frictiondisk.figures.footer import FOOTER_GID, FOOTER_SEP, chars_per_line, wrap_parts
from frictiondisk.figures.searched import (  # noqa: F401 (re-exported for the task figures)
    MU_LABEL,
    SYMBOLS,
    SearchedKey,
    boundary_sides,
    searched_key,
)
from frictiondisk.figures.style import CAPTION_FONT_PT, NOTE_FONT_PT, SLIDE_COLOR, STICK_COLOR  # noqa: F401
from frictiondisk.verdict.horizon import horizon_key
from frictiondisk.verdict.outcomes import FAIL_COLOR, OUTCOMES, RECORDS, UNDETERMINED

MU_STAR_LABEL = "\u03bc* [-]"
SIZE_LABEL = "size (sticking radius) [m]"
A_LABEL = "deviation from circle a [m]"

SLIDE_GREY = "0.55"
NON_MONOTONE_COLOR = "tab:orange"
LINE_COLOR = "0.15"
RUG_Y = 0.03  # axes fraction at which points without a value are drawn
MAX_LISTED = 8  # failed points listed by name; the rest are counted
LIST_WIDTH = 112  # characters per line of the failure list (fits 7.2 in at NOTE_FONT_PT)
REGION_FONT_PT = 12.0

# marker style and legend text of each outcome, from its record (verdict/outcomes.py)
OUTCOME_STYLE: dict[str, dict[str, Any]] = {
    r.name: {"color": r.color, "edge": r.edge, "marker": r.marker} for r in RECORDS
}
OUTCOME_LABEL = {r.name: r.legend for r in RECORDS}


def outcome_style(outcome: str) -> dict[str, Any]:
    """The marker style of `outcome` (that of `undetermined` for a name no record has)."""
    return OUTCOME_STYLE.get(outcome, OUTCOME_STYLE[UNDETERMINED])


# ---- labels and caption -----------------------------------------------------------------
def _unit_text(units: Any) -> str | None:
    if units is None or str(units).strip() == "":
        return None
    return "-" if str(units).strip() == "1" else str(units).strip()


def axis_label(coord: xr.DataArray) -> str:
    """Axis label of a varied coordinate from its attributes, e.g. "axes offset x_ms [m]".

    The description is the coordinate's long_name up to its first ':' or ';' (without a
    trailing "[unit]"); the symbol is the last part of its scene_key; "1" shows as "[-]".
    mu is always labelled `MU_LABEL`.
    """
    key = str(coord.attrs.get("scene_key", coord.name))
    if key == "params.mu":
        return MU_LABEL
    name = key.split(".")[-1]
    long_name = re.sub(r"\s*\[[^\]]*\]\s*$", "", str(coord.attrs.get("long_name", "")))
    description = re.split(r"[:;]", long_name, maxsplit=1)[0].strip()
    words = re.findall(r"[\w]+", description)
    text = description if name in words else f"{description} {name}".strip()
    unit = _unit_text(coord.attrs.get("units"))
    return f"{text} [{unit}]" if unit else text


def value_text(coord: xr.DataArray, value: float) -> str:
    """ "x_ms = 0.1 m": a point's value of a varied key, with its unit."""
    name = str(coord.attrs.get("scene_key", coord.name)).split(".")[-1]
    unit = _unit_text(coord.attrs.get("units"))
    return f"{name} = {value:.6g}{' ' + unit if unit and unit != '-' else ''}"


def _fmt(value: Any) -> str:
    if isinstance(value, float | np.floating):
        return f"{float(value):g}"
    return str(value)


def _caption_parts(ds: xr.Dataset, mode: str | None = None) -> list[str]:
    attrs = ds.attrs
    parts = [f"campaign {attrs.get('campaign_name', '?')}", f"task {attrs.get('task', '?')}"]
    if "tol" in attrs:
        parts.append(f"tol {_fmt(float(attrs['tol']))}")
    try:
        numerics = yaml.safe_load(str(attrs.get("numerics_yaml", ""))) or {}
    except yaml.YAMLError:
        numerics = {}
    if not isinstance(numerics, dict):
        numerics = {}
    mode = mode or numerics.get("mode")
    horizon = horizon_key(mode)
    numerics_text = ", ".join(
        f"{label}{_fmt(numerics[key])}{unit}"
        for key, label, unit in (
            ("method", "", ""),
            ("rtol", "rtol ", ""),
            ("atol", "atol ", ""),
            (horizon, f"{horizon} ", " s"),
        )
        if key in numerics
    )
    if numerics_text or mode:
        parts.append(f"numerics {numerics_text}" + (f", mode {mode}" if mode else ""))
    physics = physics_text(ds)
    if physics:
        parts.append(physics)
    parts.append(f"frictiondisk {attrs.get('frictiondisk_version', '?')}")
    if attrs.get("kernel_version"):
        parts.append(str(attrs["kernel_version"]))
    return parts


# physical parameters a caption always names where they are fixed: (param attribute,
# symbol, unit, disk only); any other scene key is named where it differs from its default
CAPTION_PARAMS = (
    ("x_ms", "x_ms", "m", False),
    ("x0", "x0", "m", False),
    ("beta_b", "$\\beta_b$", "N m s/rad", True),
    ("phidot0", "$\\dot{\\varphi}_0$", "rad/s", True),
)
# the scene sections whose keys a caption names (numerics have their own part)
CAPTION_SECTIONS = ("params", "contact")


def _scene(ds: xr.Dataset) -> dict[str, Any]:
    try:
        return yaml.safe_load(str(ds.attrs.get("scene_yaml", ""))) or {}
    except yaml.YAMLError:
        return {}


def scene_title(ds: xr.Dataset) -> str:
    """ "Pin" or "Disk (12 contact points)": what a figure shows, from its resolved scene."""
    scene = _scene(ds)
    name = str(scene.get("scene", "") or "")
    if name == "disk":
        points = (scene.get("contact") or {}).get("points")
        return f"Disk ({points} contact points)" if points else "Disk"
    return name.capitalize() or str(ds.attrs.get("campaign_name", ""))


def _flat(section: dict[str, Any], prefix: str) -> dict[str, Any]:
    """{dotted key: value} of a nested scene section."""
    flat: dict[str, Any] = {}
    for key, value in section.items():
        if isinstance(value, dict):
            flat |= _flat(value, f"{prefix}.{key}")
        else:
            flat[f"{prefix}.{key}"] = value
    return flat


def _default_scene(scene: dict[str, Any]) -> dict[str, Any]:
    """The canonical default scene of the same kind and contact layout ({} if unknown)."""
    from frictiondisk.model.scene import ConfigError, scene_from_dict

    layout = (scene.get("contact") or {}).get("layout")
    data: dict[str, Any] = {"scene": scene.get("scene")}
    if layout and scene.get("scene") == "disk":
        data["contact"] = {"layout": layout}
    try:
        return scene_from_dict(data).canonical()
    except (ConfigError, ValueError):
        return {}


def changed_keys(ds: xr.Dataset) -> dict[str, Any]:
    """{dotted key: value} of every params and contact key of the results' resolved scene
    (scene_yaml) that differs from the default scene of its kind, in key order."""
    scene = _scene(ds)
    default = _default_scene(scene)
    changed = {}
    for section in CAPTION_SECTIONS:
        mine = _flat(scene.get(section) or {}, section)
        base = _flat(default.get(section) or {}, section)
        changed |= {k: v for k, v in mine.items() if k not in base or base[k] != v}
    return changed


def varied_keys(ds: xr.Dataset) -> set[str]:
    """The dotted keys without one value in the results: varied, sampled, traced or
    bisected (a find_jump's `parameter`, else mu for a boundary's results)."""
    varied = {str(ds[c].attrs.get("scene_key", "")) for c in ds.coords}
    varied |= {str(ds.attrs["trace_key"])} if "trace_key" in ds.attrs else set()  # a plane's key
    varied |= {str(key) for key in sample_spec(ds)}  # sampled: no single value either
    if "mu_star" in ds.variables:
        varied.add(str(ds.attrs.get("parameter") or "params.mu"))
    return varied


def _key_text(key: str, value: Any) -> str:
    """ "c_s 1.5 N/m": a scene key's name (its symbol where known), value and unit."""
    from frictiondisk.model.scene import describe_key

    name = key.split(".")[-1]
    symbol = SYMBOLS.get(name, name) if key.startswith("params.") else key.split(".", 1)[1]
    try:
        unit = describe_key(key)[0]
    except KeyError:
        unit = None
    unit_text = f" {unit}" if unit and unit != "1" else ""
    return f"{symbol} {_fmt(value)}{unit_text}"


def physics_text(ds: xr.Dataset) -> str:
    """The scene and its physical parameters that are not varied, e.g. "pin, x_ms 0.1 m,
    x0 0 m, c_s 1.5 N/m": x_ms and x0 always (a disk: also beta_b and phidot0), then every
    other params or contact key that differs from its default; empty for results without
    the resolved scene."""
    if "scene_yaml" not in ds.attrs:
        return ""
    varied = varied_keys(ds)
    scene = _scene(ds).get("scene", "")
    shown = [
        f"{symbol} {_fmt(float(ds.attrs[f'param_{key}']))} {unit}"
        for key, symbol, unit, disk_only in CAPTION_PARAMS
        if f"param_{key}" in ds.attrs
        and f"params.{key}" not in varied
        and (scene == "disk" or not disk_only)
    ]
    always = {f"params.{key}" for key, *_ in CAPTION_PARAMS}
    shown += [
        _key_text(key, value)
        for key, value in changed_keys(ds).items()
        if key not in varied and key not in always and _fixed(ds, key)
    ]
    return ", ".join([str(scene or "scene"), *shown])


def _fixed(ds: xr.Dataset, key: str) -> bool:
    """False for a params key the results hold no single value of (no param_ attribute:
    varied, sampled or searched; scene_attrs leaves those out)."""
    section, name = key.split(".", 1)
    return section != "params" or f"param_{name}" in ds.attrs


def sample_spec(ds: xr.Dataset) -> dict[str, Any]:
    """A basin campaign's sampled scene keys and their distributions (its sample_yaml
    attribute: {key: {kind: [a, b]}}); {} for any other results."""
    try:
        sample = yaml.safe_load(str(ds.attrs.get("sample_yaml", ""))) or {}
    except yaml.YAMLError:
        return {}
    return sample if isinstance(sample, dict) else {}


def caption_text(ds: xr.Dataset, mode: str | None = None) -> str:
    """One line on how the results were made: campaign name, task, tolerance, numerics
    (method, rtol, atol, horizon, mode; from the numerics_yaml attribute, or `mode`: the
    one the task ran every point in), the physical parameters that are not varied, and the
    package and numerics versions."""
    return FOOTER_SEP.join(_caption_parts(ds, mode))


def new_figure(
    results: xr.Dataset, width: float, height: float, note_lines: int, mode: str | None = None
) -> tuple[Figure, SubFigure, SubFigure | None]:
    """A Figure of three stacked subfigures: the plot (height [in]), a note of `note_lines`
    monospace lines (none if 0) and the caption (wrapped to the figure width; `mode` as in
    caption_text).

    Returns the figure, the plot's subfigure and the note's (or None). Separate subfigures
    keep the note and caption out of the plot's constrained layout.
    """
    chars = chars_per_line(width)
    caption = wrap_parts(_caption_parts(results, mode), chars)
    caption_h = 0.1 + 0.14 * len(caption)
    note_h = 0.125 * note_lines + 0.2 if note_lines else 0.0
    ratios = [height, *([note_h] if note_lines else []), caption_h]
    fig = Figure(figsize=(width, sum(ratios)), layout="constrained")
    subs = fig.subfigures(len(ratios), 1, height_ratios=ratios, hspace=0.0)
    subs[-1].text(
        0.01,
        0.5,
        "\n".join(caption),
        ha="left",
        va="center",
        fontsize=CAPTION_FONT_PT,
        color="0.3",
        gid=FOOTER_GID,
    )
    return fig, subs[0], (subs[1] if note_lines else None)


# ---- legends ----------------------------------------------------------------------------
def fitted_legend(ax: Axes, ncols: int, **kwargs: Any) -> Legend:
    """`ax.legend(ncols=ncols, **kwargs)` with as many of `ncols` columns as fit: laid out
    with the figure, a legend that reaches past its left or right edge gets one column
    fewer (long labels side by side were cut off at the right edge)."""
    fig = ax.get_figure(root=True)
    for n in range(max(1, ncols), 0, -1):
        legend = ax.legend(ncols=n, **kwargs)
        fig.draw_without_rendering()
        box = legend.get_window_extent()
        if n == 1 or (box.x0 >= fig.bbox.x0 and box.x1 <= fig.bbox.x1):
            return legend
        legend.remove()
    raise AssertionError("unreachable: one column is always returned")


def legend_above(ax: Axes, handles: list, ncols: int) -> Legend:
    """The legend of `handles` in a band just above the axes, left-aligned, without a
    frame (`fitted_legend`: as many of `ncols` columns as fit)."""
    return fitted_legend(
        ax,
        ncols,
        handles=handles,
        loc="lower left",
        bbox_to_anchor=(0.0, 1.01),
        fontsize="small",
        frameon=False,
    )


# ---- the note under the plot ------------------------------------------------------------
def add_note(note: SubFigure, lines: list[str], title: str) -> None:
    """`title` and `lines` in a monospace box in the note subfigure (new_figure)."""
    note.text(
        0.015,
        0.96,
        "\n".join([title, *lines]),
        ha="left",
        va="top",
        fontsize=NOTE_FONT_PT,
        family="monospace",
        bbox={"boxstyle": "round,pad=0.4", "facecolor": "#fff5f0", "edgecolor": FAIL_COLOR},
        gid="failed_list",
    )


# ---- axes -------------------------------------------------------------------------------
def make_rug_room(ax: Axes, frac: float) -> None:
    """Extend the y axis downwards so that the data keep the upper 1 - `frac` of it; the strip
    below (for marks of points without a value) is set off by a dotted line and has no tick
    labels, so that nobody reads a value off a mark there."""
    lo, hi = ax.get_ylim()
    new_lo = lo - frac / (1.0 - frac) * (hi - lo)
    ax.set_ylim(new_lo, hi)
    ax.axhline(lo, color="0.6", linewidth=0.6, linestyle=":", zorder=1, gid="rug_line")

    def label(value: float, pos: int | None = None) -> str:
        return "" if value < lo - 1e-9 * abs(hi - lo) else f"{value:.6g}"

    ax.yaxis.set_major_formatter(FuncFormatter(label))


def padded(lo: float, hi: float, frac: float) -> tuple[float, float]:
    """(lo, hi) widened by `frac` of the span on each side (by 0.5 if lo == hi)."""
    span = hi - lo
    pad = frac * span if span > 0 else 0.5 * (abs(lo) or 1.0)
    return lo - pad, hi + pad


def cell_edges(values: np.ndarray) -> np.ndarray:
    """Cell edges around sorted centres: midpoints, half a step beyond the ends (a single
    centre: a cell half its magnitude wide on each side)."""
    v = np.asarray(values, dtype=float)
    if v.size == 1:
        half = 0.5 * (abs(v[0]) or 1.0)
        return np.array([v[0] - half, v[0] + half])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])


# ---- inputs -----------------------------------------------------------------------------
def check_vars(ds: xr.Dataset, names: tuple[str, ...], what: str) -> None:
    """ValueError naming the variables of `names` that `ds` lacks."""
    missing = [name for name in names if name not in ds.variables]
    if missing:
        raise ValueError(
            f"{what} lacks the variable(s) {', '.join(missing)}: "
            "not written by this version of frictiondisk?"
        )


# ---- runs -------------------------------------------------------------------------------
def run_dots(ax: Axes, x: np.ndarray, mu: np.ndarray, outcome: np.ndarray) -> list[Line2D]:
    """Every run as a small dot at (x, mu) in its outcome's colour and marker (one style
    table: OUTCOME_STYLE), outcomes no record names as undetermined; returns the legend
    entries, "run: <outcome>", in the listing order."""
    outcome = np.asarray(outcome).astype(str)
    known = np.isin(outcome, OUTCOMES)
    handles = []
    for name in OUTCOMES:
        mask = (outcome == name) | (~known if name == UNDETERMINED else False)
        if not mask.any():
            continue
        style = outcome_style(name)
        look = {
            "linestyle": "none",
            "marker": style["marker"],
            "color": style["color"],
            "markeredgecolor": style["edge"],
            "markeredgewidth": 0.4 if style["marker"] != "x" else 1.0,
        }
        ax.plot(x[mask], mu[mask], markersize=3.0, alpha=0.9, zorder=2, **look)
        handles.append(Line2D([], [], markersize=4, label=f"run: {name}", **look))
    return handles
