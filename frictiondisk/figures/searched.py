"""What a figure or table of a boundary shows, without matplotlib (the tables print it
too): the key searched (mu, or the key a find_jump's `parameter` bisects) with its symbol
and unit, and the two motions of a `between` boundary."""

from __future__ import annotations

import dataclasses
import re

import xarray as xr

from frictiondisk.store.campaign_datasets import key_attrs

MU_LABEL = "friction coefficient \u03bc [-]"


def _unit_text(units) -> str | None:
    if units is None or str(units).strip() == "":
        return None
    return "-" if str(units).strip() == "1" else str(units).strip()


# display symbols of scene keys a label names (the key's last part where none is listed)
SYMBOLS = {
    "mu": "\u03bc",
    "omega_m": "\u03c9_m",
    "beta_b": "\u03b2_b",
    "phidot0": "\u03c6\u03070",
    "rho": "\u03c1",
}


@dataclasses.dataclass(frozen=True)
class SearchedKey:
    """The key a find_jump bisects or a trace follows (mu unless its `parameter` names
    another): its dotted key, display symbol ("\u03c9_m"), plain name for text tables
    ("omega_m"), unit ("rad/s"; "-" for dimensionless) and axis label."""

    key: str
    symbol: str
    name: str
    unit: str
    label: str

    @property
    def star(self) -> str:
        """The symbol of its value at the boundary, e.g. "\u03c9_m*"."""
        return f"{self.symbol}*"

    @property
    def unit_suffix(self) -> str:
        """ " rad/s" (empty for a dimensionless key)."""
        return "" if self.unit in ("-", "") else f" {self.unit}"


def searched_key(ds: xr.Dataset) -> SearchedKey:
    """The searched key of a find_jump or trace results.nc: its `parameter` attribute
    (a find_jump bisecting another key than mu; the values stay in mu_star, mu_lo, ...,
    with the key's units), else mu."""
    key = str(ds.attrs.get("parameter") or "params.mu")
    name = key.split(".")[-1]
    symbol = SYMBOLS.get(name, name)
    if key == "params.mu":
        return SearchedKey(key, symbol, name, "-", MU_LABEL)
    units = ds["mu_star"].attrs.get("units") if "mu_star" in ds.variables else None
    unit = _unit_text(units) or "-"
    long_name = str(ds["mu_star"].attrs.get("long_name", "")) if "mu_star" in ds else ""
    found = re.search(r"\[values of [^\]]+\]", long_name)
    description = _key_description(key) or (found[0] if found else key)
    return SearchedKey(key, symbol, name, unit, f"{description} {symbol} [{unit}]")


def _key_description(key: str) -> str:
    """The scene schema's description of `key` up to its first ':' or ';' ("" if unknown)."""
    try:
        long_name = key_attrs(key)["long_name"]
    except KeyError:
        return ""
    return re.split(r"[:;]", long_name, maxsplit=1)[0].strip()


def boundary_sides(ds: xr.Dataset) -> tuple[str, str] | None:
    """(below, above): the two motions of a `between` boundary (its `between` attribute,
    "[A, B]: ..."), or None for the stick jump (not_stick below, stick above)."""
    found = re.match(r"\[(\w+), (\w+)\]", str(ds.attrs.get("between", "")))
    return (found[1], found[2]) if found else None
