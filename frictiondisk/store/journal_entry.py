"""A journal entry (frictiondisk.store.journal): the key of a run (`run_key`: the sha256 of
its canonical scene and the kernel version) and the entry's format, written (`encode`)
and verified on read (`verify`: JSON, fields, version, key, sha256, and inputs that give
the key again)."""

from __future__ import annotations

import functools
import hashlib
import json
import math
import re
from importlib import metadata
from typing import Any

from frictiondisk.version import NUMERICS_VERSION, UNCHANGED_SINCE

__all__ = [
    "ENTRY_VERSION",
    "check_key",
    "encode",
    "kernel_version",
    "key_of_inputs",
    "key_version",
    "run_key",
    "scene_key",
    "verify",
]

ENTRY_VERSION = 1
ENTRY_FIELDS = ("version", "key", "inputs", "result", "sha256")
KEY = re.compile(r"[0-9a-f]{64}")  # a sha256 hex digest, as made by run_key


# --- keys ---------------------------------------------------------------------------------

# The libraries whose versions change what a run computes (numba compiles the kernel, numpy
# and scipy do its arithmetic, scipy-radau and coulomb integrate with scipy).
NUMERICS_LIBRARIES = ("numba", "numpy", "scipy")


@functools.cache
def kernel_version(version: int | None = None) -> str:
    """Version of the numerics, part of every `run_key`, e.g.
    "numerics 1, numba 0.68.1, numpy 2.4.6, scipy 1.17.1".

    `NUMERICS_VERSION` (frictiondisk/version.py) is bumped by hand with any change that
    alters what a run computes; an edited comment or docstring leaves every key as it was.
    The library versions come from the installed distributions' metadata (nothing is
    imported): a new numba, numpy or scipy can change results in the last digits, so
    journal entries computed with other versions are not reused. Computed once per process
    and version (None: NUMERICS_VERSION).
    """
    version = NUMERICS_VERSION if version is None else version
    libraries = ", ".join(f"{name} {metadata.version(name)}" for name in NUMERICS_LIBRARIES)
    return f"numerics {version}, {libraries}"


def _coulomb_pin(scene: dict[str, Any]) -> bool:
    """Whether a canonical scene is a Coulomb pin: the scenes whose runs the grazing rules
    (verdict/grazing.py, numerics 13) can decide."""
    return scene.get("scene") == "pin" and scene["contact"]["stribeck"]["r"] >= 1.0


def key_version(scene: dict[str, Any]) -> int:
    """The numerics version in a run's key: the newest version that changed what this
    canonical scene computes (frictiondisk/version.py UNCHANGED_SINCE): NUMERICS_VERSION for
    a Coulomb pin, UNCHANGED_SINCE for every other scene."""
    return NUMERICS_VERSION if _coulomb_pin(scene) else UNCHANGED_SINCE


def run_key(config: Any) -> str:
    """Journal key of one run: sha256 hex of its canonical scene and the kernel version.

    `config` is a validated `SceneConfig` (anything with `.canonical()` works). The key is
    the sha256 of `{"scene": config.canonical(), "kernel": kernel_version(v)}` as compact,
    key-sorted JSON, v = `key_version` of the scene.
    """
    scene = config.canonical()
    return scene_key(scene, json.dumps(scene, sort_keys=True, separators=(",", ":")))


def scene_key(scene: dict[str, Any], text: str) -> str:
    """`run_key` of the canonical scene `scene` given its compact, key-sorted JSON `text`
    (canonical_json(scene)), so that a scene journaled is written once, for its key and
    its entry: the key's JSON is that text under "scene" after "kernel"."""
    kernel = json.dumps(kernel_version(key_version(scene)))
    return hashlib.sha256(f'{{"kernel":{kernel},"scene":{text}}}'.encode()).hexdigest()


class _Inputs:
    """Stored canonical inputs, seen by `run_key` as the config they came from."""

    def __init__(self, canonical: dict[str, Any]) -> None:
        self._canonical = canonical

    def canonical(self) -> dict[str, Any]:
        return self._canonical


def key_of_inputs(inputs: dict[str, Any]) -> str:
    """The key `run_key` gives the config whose canonical form is `inputs` (current numerics)."""
    return run_key(_Inputs(inputs))


def check_key(key: Any) -> str:
    """`key` if it is a valid journal key, else ValueError."""
    if not isinstance(key, str) or not KEY.fullmatch(key):
        raise ValueError(
            f"journal key {key!r} is not valid: expected a sha256 hex digest "
            "(64 lowercase hex digits), as made by run_key"
        )
    return key


# --- entries ------------------------------------------------------------------------------


def canonical_json(value: Any) -> str:
    """Compact, key-sorted JSON; ValueError on NaN or infinity."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False)


def entry_digest(key: str, inputs: Any, result: Any) -> str:
    """sha256 hex of the canonical JSON of {"key", "inputs", "result"}."""
    text = canonical_json({"key": key, "inputs": inputs, "result": result})
    return hashlib.sha256(text.encode()).hexdigest()


def non_finite_path(value: Any, path: str) -> str | None:
    """Dotted path of the first NaN or infinity inside `value`, or None."""
    if isinstance(value, float) and not math.isfinite(value):
        return path
    if isinstance(value, dict):
        items = value.items()
    elif isinstance(value, list | tuple):
        items = enumerate(value)
    else:
        return None
    for k, item in items:
        found = non_finite_path(item, f"{path}.{k}" if path else str(k))
        if found is not None:
            return found
    return None


def verify(key: str, raw: bytes) -> tuple[Any, str | None]:
    """(entry, None) if `raw` is a valid entry of `key`, else (None, reason)."""
    try:
        entry = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, ValueError) as err:
        # json.JSONDecodeError is a ValueError; so is an out-of-range number
        what = "empty file" if not raw.strip() else f"truncated or not JSON ({err})"
        return None, what
    if not isinstance(entry, dict):
        return None, f"not a JSON object but {type(entry).__name__}"
    missing = [name for name in ENTRY_FIELDS if name not in entry]
    if missing:
        return None, f"missing field(s) {', '.join(missing)}"
    if entry["version"] != ENTRY_VERSION:
        return None, f"unsupported entry version {entry['version']!r} (expected 1)"
    if entry["key"] != key:
        return None, f"key field {entry['key']!r} differs from the file's key"
    if not isinstance(entry["inputs"], dict) or not isinstance(entry["result"], dict):
        return None, "inputs and result must be JSON objects"
    try:
        digest = entry_digest(key, entry["inputs"], entry["result"])
    except ValueError:  # NaN or Infinity written by hand: json.loads accepts them
        return None, "contains NaN or infinity"
    if entry["sha256"] != digest:
        return None, "sha256 mismatch (content altered)"
    try:
        from_inputs = key_of_inputs(entry["inputs"])
    except (TypeError, ValueError) as err:
        return None, f"inputs cannot be hashed ({err})"
    if from_inputs != key:
        return None, (
            f"its inputs give key {from_inputs[:12]}..., not {key[:12]}... "
            "(an entry of another run, edited inputs, or other numerics)"
        )
    return entry, None


def encode(
    key: str, inputs: dict[str, Any], result: dict[str, Any], inputs_text: str | None = None
) -> bytes:
    """The entry of run `key` as the bytes of its file: `{"inputs", "key", "result",
    "sha256", "version": 1}` as compact, key-sorted JSON and a newline.

    `inputs` and `result` must be JSON-serializable dicts without NaN or infinity (pass
    None for a missing number): ValueError names the offending field, TypeError a value
    JSON cannot store. inputs_text: canonical_json(inputs) where already written (taken
    for inputs made of JSON's own types only)."""
    check_key(key)
    for name, value in (("inputs", inputs), ("result", result)):
        if not isinstance(value, dict):
            raise TypeError(f"journal entry {key}: {name} must be a dict, got {value!r}")
    try:
        reuse = inputs_text is not None and _plain(inputs)
        texts = [inputs_text if reuse else _as_read(inputs), _as_read(result)]
    except ValueError as err:  # NaN or infinity: walk the values only now, to name it
        for name, value in (("inputs", inputs), ("result", result)):
            bad = non_finite_path(value, name)
            if bad is not None:
                raise ValueError(
                    f"journal entry {key}: {bad} is NaN or infinite, which JSON cannot "
                    "store; pass None for a missing number"
                ) from None
        raise ValueError(f"journal entry {key}: {err}; pass None for NaN") from None
    except TypeError as err:
        raise TypeError(f"journal entry {key}: {err}") from None
    # canonical_json of {"key", "inputs", "result"} (entry_digest), and of the entry, put
    # together from the parts' texts: each dict is written once
    inputs_text, result_text = texts
    body = f'"inputs":{inputs_text},"key":{json.dumps(key)},"result":{result_text}'
    digest = hashlib.sha256(f"{{{body}}}".encode()).hexdigest()
    return f'{{{body},"sha256":"{digest}","version":{ENTRY_VERSION}}}\n'.encode()


def _as_read(value: dict[str, Any]) -> str:
    """canonical_json of `value` as a reader loads it back: the digest must be computed on
    exactly that (tuples become lists, keys strings); equal to canonical_json(value) for
    the plain JSON values runs are made of (`_plain`: no reading back needed), written a
    second time only where reading it back changes it."""
    text = canonical_json(value)
    if _plain(value):
        return text
    loaded = json.loads(text)
    return text if loaded == value else canonical_json(loaded)


_LEAVES = frozenset({str, int, float, bool, type(None)})


def _plain(value: Any) -> bool:
    """Whether `value` is made of JSON's own types only (dicts with str keys, lists, str,
    int, float, bool, None; no subclass): JSON reads its text back as an equal value."""
    kind = type(value)
    if kind is dict:
        for key, item in value.items():
            if type(key) is not str or (type(item) not in _LEAVES and not _plain(item)):
                return False
        return True
    if kind is list:
        for item in value:
            if type(item) not in _LEAVES and not _plain(item):
                return False
        return True
    return kind in _LEAVES
