"""CF metadata (Climate and Forecast conventions, CF-1.10) for every netCDF file we write:
results.nc (of every task, a trace's included), runs.nc, trajectory.nc and accuracy.nc.

`complete(ds, title)` adds the global attributes (`Conventions`, `title`, `institution`,
`source`, `history`, `references`) and, per variable, what the builder left out: the flag
attributes of the 0/1 (and -1/0/1) indicator variables, `units` of the integer counters and
a `long_name` and `comment` for the text variables. The tables here hold what every file
shares; a task's builder passes its own (`flags`, `texts`, `dimensionless`: its package's
datasets.py). A numeric variable without units that is listed nowhere raises, so a new
variable cannot slip through undocumented. Text variables
carry no `units` (CF gives strings none); flags carry `flag_values` and `flag_meanings`
(and units "1": they are dimensionless).

`history` holds no clock time on purpose: results.nc is rebuilt from the journal on every
run or resume, and the same campaign must give identical files whatever the worker count.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from typing import Any

import numpy as np
import xarray as xr

from frictiondisk.model.search_settings import CERTIFICATION_FLAGS
from frictiondisk.verdict import outcomes
from frictiondisk.version import NUMERICS_VERSION, __version__

CONVENTIONS = "CF-1.10"
REFERENCES = (
    "W. Stamm and A. Fidlin, Radial dynamics of rigid friction disks with alternating "
    "sticking and sliding; model: docs/model.md in the frictiondisk repository"
)
OUTCOMES = " ".join(outcomes.OUTCOMES)
# each outcome with what it means, from its record
OUTCOME_MEANINGS = "; ".join(f"{r.name}: {r.description}" for r in outcomes.RECORDS)

Flag = tuple[tuple[int, ...], str]  # (flag_values, flag_meanings)

# the certification of a point: pending (-1, partial results) or a CERTIFICATION_FLAGS code
CERTIFICATION: Flag = (
    tuple(range(-1, len(CERTIFICATION_FLAGS))),
    " ".join(("pending", *CERTIFICATION_FLAGS)),
)

# variable -> (flag_values, flag_meanings)
FLAGS: dict[str, Flag] = {
    "mode": ((0, 1), "slide stick"),  # trajectory.nc: contact mode
}

# text variable -> (long_name if the builder gave none, comment)
TEXT: dict[str, tuple[str, str]] = {
    "outcome": (
        "outcome of the run",
        f"one of: {OUTCOMES} (docs/model.md section 6). {OUTCOME_MEANINGS}",
    ),
    "reason": ("why this outcome", "free text; for undetermined: what went wrong"),
    "decided_by": (
        "the rule that decided the outcome",
        "one of frictiondisk/verdict/deciding_rule.py DECIDING_RULES; empty: the exact "
        "Coulomb pin, or a run journaled before NUMERICS_VERSION 8",
    ),
    "status": (
        "status of the point",
        "converged (mu* found), no_jump (no value of the prescan grid sticks, each decided) "
        "or failed; pending: not finished (partial)",
    ),
    "mode": ("numerics.mode of the run", "decide or converge"),
    "key": ("journal key", "sha256 of the canonical scene and the numerics version"),
}

# integer counters and indices that the builders leave without units
DIMENSIONLESS = {"point", "level", "strict", "n_runs", "contact"}
# numeric variables whose unit differs from row to row, named by a text variable beside them
MIXED_UNITS = {"value": "value_units"}


def flag_meanings(var: xr.DataArray) -> dict[int, str]:
    """flag_values -> flag_meanings of a CF flag variable ({} if it has none); flag_values
    default to 0, 1, ... as in the builders."""
    names = str(var.attrs.get("flag_meanings", "")).split()
    values = var.attrs.get("flag_values", range(len(names)))
    return {int(v): name for v, name in zip(values, names, strict=False)}


def _source() -> str:
    from frictiondisk.store.journal_entry import kernel_version

    return f"frictiondisk {__version__} simulation ({kernel_version()})"


def _complete_variable(name: str, var: xr.Variable, flags, texts, dimensionless) -> None:
    attrs = var.attrs
    if var.dtype.kind in "USO":
        long_name, comment = texts.get(name, (name.replace("_", " "), ""))
        attrs.setdefault("long_name", long_name)
        if comment:
            attrs.setdefault("comment", comment)
        attrs.pop("units", None)
        return
    if name in flags and var.dtype.kind in "iu":
        values, meanings = flags[name]
        attrs["flag_values"] = np.array(values, dtype=var.dtype)
        attrs["flag_meanings"] = meanings
        attrs["units"] = "1"
        attrs.setdefault("long_name", name.replace("_", " "))
        return
    if name in MIXED_UNITS:
        attrs.setdefault("comment", f"units differ per row: see the variable {MIXED_UNITS[name]}")
        return
    if "units" not in attrs:
        if name not in dimensionless:
            raise ValueError(f"variable {name!r} has no units: give it units in its builder")
        attrs["units"] = "1"
    if "long_name" not in attrs:
        raise ValueError(f"variable {name!r} has no long_name: give it one in its builder")


def complete(
    ds: xr.Dataset,
    title: str,
    what: str,
    flags: Mapping[str, Flag] | None = None,
    texts: Mapping[str, tuple[str, str]] | None = None,
    dimensionless: Collection[str] = (),
) -> xr.Dataset:
    """Add the CF attributes to `ds` in place (see the module docstring) and return it.

    title: a one-line description of the file; what: how it was made, for `history`
    (e.g. "frictiondisk run: campaign demo_line, task find_jump"). flags, texts,
    dimensionless: the builder's own variables, beside the shared FLAGS, TEXT and
    DIMENSIONLESS.
    """
    flags = {**FLAGS, **(flags or {})}
    texts = {**TEXT, **(texts or {})}
    units_one = DIMENSIONLESS | set(dimensionless)
    for name, var in ds.variables.items():
        _complete_variable(str(name), var, flags, texts, units_one)
    ds.attrs.update(
        {
            "Conventions": CONVENTIONS,
            "title": title,
            "institution": "frictiondisk",
            "source": _source(),
            "history": f"{what}; written by frictiondisk {__version__} "
            f"(numerics version {NUMERICS_VERSION})",
            "references": REFERENCES,
        }
    )
    return ds


def scene_attrs(config: Any, unfixed: Collection[str] = ()) -> dict[str, Any]:
    """The resolved physical parameters of a scene as attributes: `scene_yaml` (every key,
    defaults filled in) and one `param_<name>` per physical parameter, in SI units, but
    none for the dotted keys `unfixed` (varied, sampled or searched: no one value holds)."""
    canonical = config.canonical()
    attrs: dict[str, Any] = {"scene_yaml": str(config.to_yaml())}
    for name, value in canonical["params"].items():
        if f"params.{name}" not in unfixed:
            attrs[f"param_{name}"] = float(value)
    for name, kind in (("points", int), ("stiffness", float)):
        if f"contact.{name}" not in unfixed:
            attrs[f"param_contact_{name}"] = kind(canonical["contact"][name])
    return attrs
