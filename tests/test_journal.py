"""Campaign storage: run keys, the journal, the campaign lock and atomic netCDF files.

Fast tests, no kernel runs: journal entries hold hand-made results.
"""

from __future__ import annotations

import hashlib
import json
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from frictiondisk.model.scene import scene_from_dict
from frictiondisk.store import journal_entry as journal_module
from frictiondisk.store.files import (
    atomic_write_bytes,
    atomic_write_netcdf,
    atomic_write_text,
    netcdf_is_valid,
)
from frictiondisk.store.journal import Journal
from frictiondisk.store.journal_audit import moved_aside
from frictiondisk.store.journal_entry import kernel_version, run_key
from frictiondisk.store.lock import CampaignLock, CampaignLocked

RESULT = {"outcome": "stick_slip", "t_stick": None, "x_amplitude": 0.0123456789, "n_events": 42}
_CANONICAL: dict[str, dict] = {}  # key -> the canonical scene it was made from


def _key(n: int) -> str:
    """The run key of the n-th test scene (a pin with its own mu); `_inputs` gives its
    canonical inputs, which a verified entry must hold (the key is recomputed from them)."""
    config = scene_from_dict({"scene": "pin", "params": {"mu": 1e-3 * (n + 1)}})
    key = run_key(config)
    _CANONICAL[key] = config.canonical()
    return key


def _inputs(key: str) -> dict:
    return _CANONICAL[key]


# --- keys ---------------------------------------------------------------------------------


def test_kernel_version_names_the_numerics_and_library_versions():
    from importlib import metadata

    from frictiondisk.version import NUMERICS_VERSION

    version = kernel_version()
    assert version.startswith(f"numerics {NUMERICS_VERSION}, ")
    for name in ("numba", "numpy", "scipy"):
        assert f"{name} {metadata.version(name)}" in version
    assert kernel_version() == version
    assert run_key(scene_from_dict({"scene": "pin"})) == run_key(scene_from_dict({"scene": "pin"}))


def test_kernel_version_follows_the_numerics_version_not_the_sources(monkeypatch):
    before = kernel_version()
    monkeypatch.setattr(journal_module, "NUMERICS_VERSION", 10**6)
    kernel_version.cache_clear()
    try:
        assert kernel_version() != before and "numerics 1000000" in kernel_version()
    finally:
        monkeypatch.undo()
        kernel_version.cache_clear()
    assert kernel_version() == before


def test_a_run_key_names_the_last_version_that_changed_its_scene():
    """A version that changes only Coulomb pins (13: the grazing rules) changes their keys
    alone; every other scene keeps the key of UNCHANGED_SINCE."""
    from frictiondisk.store.journal_entry import key_version
    from frictiondisk.version import NUMERICS_VERSION, UNCHANGED_SINCE

    annulus = {"layout": "annulus", "inner_radius": 0.03, "outer_radius": 0.08, "points": 16}
    stribeck = {"stribeck": {"r": 0.5, "v_s": 0.01, "delta": 1.0}}
    cases = {
        "pin above the critical speed": ({"scene": "pin"}, NUMERICS_VERSION),
        "pin below it": ({"scene": "pin", "params": {"omega_m": 0.9}}, NUMERICS_VERSION),
        "Stribeck pin": ({"scene": "pin", "contact": stribeck}, UNCHANGED_SINCE),
        "braked ring": ({"scene": "disk", "params": {"beta_b": 0.005}}, UNCHANGED_SINCE),
        "unbraked annulus": ({"scene": "disk", "contact": annulus}, UNCHANGED_SINCE),
        "braked annulus": (
            {"scene": "disk", "params": {"beta_b": 0.005}, "contact": annulus},
            UNCHANGED_SINCE,
        ),
    }
    assert NUMERICS_VERSION >= UNCHANGED_SINCE
    for name, (data, version) in cases.items():
        canonical = scene_from_dict(data).canonical()
        assert key_version(canonical) == version, name
        text = json.dumps(
            {"scene": canonical, "kernel": kernel_version(version)},
            sort_keys=True,
            separators=(",", ":"),
        )
        assert run_key(scene_from_dict(data)) == hashlib.sha256(text.encode()).hexdigest()


def test_kernel_version_follows_a_library_version(monkeypatch):
    real = journal_module.metadata.version
    before = kernel_version()
    monkeypatch.setattr(
        journal_module.metadata, "version", lambda n: "9.9" if n == "scipy" else real(n)
    )
    kernel_version.cache_clear()
    try:
        assert "scipy 9.9" in kernel_version() and kernel_version() != before
    finally:
        monkeypatch.undo()
        kernel_version.cache_clear()


@pytest.mark.parametrize(
    "override",
    [
        {"scene": "disk"},
        {"params": {"mu": 0.1300001}},
        {"params": {"x_ms": 0.2}},
        {"contact": {"stribeck": {"r": 0.5}}},
        {"numerics": {"rtol": 1e-7}},
        {"numerics": {"stop_on_stick": False}},
    ],
)
def test_run_key_changes_with_any_scene_value(override):
    base = run_key(scene_from_dict({"scene": "pin"}))
    assert run_key(scene_from_dict({"scene": "pin", **override})) != base


def test_run_key_ignores_how_defaults_are_written():
    implicit = scene_from_dict({"scene": "pin"})
    explicit = scene_from_dict({"scene": "pin", "params": {"mu": 0.13}, "contact": {"points": 1}})
    assert run_key(implicit) == run_key(explicit)


def test_run_key_changes_with_kernel_version(monkeypatch):
    config = scene_from_dict({"scene": "pin"})
    before = run_key(config)
    monkeypatch.setattr(journal_module, "kernel_version", lambda version=None: "fedcba9876543210")
    assert run_key(config) != before


# --- journal ------------------------------------------------------------------------------


def test_put_get_round_trip(tmp_path):
    journal = Journal(tmp_path)
    key = _key(0)
    assert journal.get(key) is None and len(journal) == 0
    journal.put(key, _inputs(key), RESULT)
    assert journal.get(key) == RESULT
    assert Journal(tmp_path).get(key) == RESULT  # a fresh reader, e.g. after a restart
    assert journal.keys() == [key] and len(journal) == 1 and key in journal
    entry = json.loads(journal.entry_path(key).read_text())
    assert entry["version"] == 1 and entry["key"] == key and entry["inputs"] == _inputs(key)
    assert journal.entry_path(key) == tmp_path / "journal" / key[:2] / f"{key}.json"
    assert journal.n_corrupt == 0
    assert _temp_files(tmp_path) == []


def test_put_rejects_nan_with_the_field_named(tmp_path):
    journal = Journal(tmp_path)
    with pytest.raises(ValueError, match=r"result\.x_amplitude is NaN or infinite.*pass None"):
        journal.put(_key(1), _inputs(_key(1)), {**RESULT, "x_amplitude": float("nan")})
    with pytest.raises(ValueError, match=r"inputs\.mu\.1 is NaN or infinite"):
        journal.put(_key(1), {"mu": [0.1, np.inf]}, RESULT)
    with pytest.raises(TypeError, match=r"not JSON serializable"):
        journal.put(_key(1), _inputs(_key(1)), {"x": object()})
    with pytest.raises(ValueError, match=r"not valid: expected a sha256 hex digest"):
        journal.put("../../etc", {}, RESULT)
    assert journal.get(_key(1)) is None and journal.keys() == []
    assert _temp_files(tmp_path) == []


def _truncate(path: Path) -> None:
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])


def _flip_result_digit(path: Path) -> None:
    raw = path.read_bytes()
    assert raw.count(b"0.0123456789") == 1
    path.write_bytes(raw.replace(b"0.0123456789", b"0.0123456788"))  # one byte differs


def _wrong_key_field(path: Path) -> None:
    entry = json.loads(path.read_text())
    entry["key"] = _key(999)
    path.write_text(json.dumps(entry))


def _inputs_of_another_run(path: Path) -> None:
    """A mix-up: another run's inputs, with the sha256 made consistent again."""
    entry = json.loads(path.read_text())
    entry["inputs"] = _inputs(_key(999))
    entry["sha256"] = journal_module.entry_digest(entry["key"], entry["inputs"], entry["result"])
    path.write_text(json.dumps(entry))


def _not_json(path: Path) -> None:
    path.write_bytes(b"\x00\xff garbage, not JSON\n")


@pytest.mark.parametrize(
    ("damage", "reason"),
    [
        (_truncate, "truncated or not JSON"),
        (_flip_result_digit, "sha256 mismatch"),
        (_wrong_key_field, "differs from the file's key"),
        (_inputs_of_another_run, "its inputs give key"),
        (_not_json, "truncated or not JSON"),
    ],
)
def test_damaged_entry_is_detected_moved_and_recomputable(tmp_path, damage, reason):
    journal = Journal(tmp_path)
    key, other = _key(0xABC), _key(0xDEF)
    journal.put(key, _inputs(key), RESULT)
    journal.put(other, _inputs(other), RESULT)
    damage(journal.entry_path(key))

    assert journal.get(key) is None
    assert journal.n_corrupt == 1
    assert len(journal.corrupt_reasons) == 1 and journal.corrupt_reasons[0].startswith(key)
    assert reason in journal.corrupt_reasons[0]
    assert not journal.entry_path(key).exists()
    moved = sorted(p.name for p in (tmp_path / "journal" / "corrupt").iterdir())
    assert moved == [f"{key}.1.json", "reasons.log"]
    assert moved_aside(tmp_path) == [f"{key}.1.json: {journal.corrupt_reasons[0][66:]}"]
    assert journal.keys() == [other] and journal.get(other) == RESULT

    assert journal.get(key) is None and journal.n_corrupt == 1  # now missing, not corrupt
    journal.put(key, _inputs(key), RESULT)  # the recomputed run
    assert journal.get(key) == RESULT and journal.n_corrupt == 1

    damage(journal.entry_path(key))  # damaged again: kept next to the first one
    assert journal.get(key) is None and journal.n_corrupt == 2
    assert (tmp_path / "journal" / "corrupt" / f"{key}.2.json").exists()


def test_peek_verifies_but_never_writes(tmp_path):
    journal = Journal(tmp_path)
    journal.put(_key(1), _inputs(_key(1)), {"outcome": "stick", "R1": 0.0123456789})
    assert Journal.peek(tmp_path, _key(1)) == {"outcome": "stick", "R1": 0.0123456789}
    assert Journal.peek(tmp_path, _key(2)) is None
    assert Journal.peek(tmp_path / "elsewhere", _key(1)) is None
    assert not (tmp_path / "elsewhere").exists()
    _flip_result_digit(journal.entry_path(_key(1)))
    assert Journal.peek(tmp_path, _key(1)) is None
    assert journal.entry_path(_key(1)).exists()  # left for the driver's get() to move
    assert not journal.corrupt_dir.exists()


def test_entry_with_missing_field_or_empty_file_is_corrupt(tmp_path):
    journal = Journal(tmp_path)
    journal.put(_key(1), _inputs(_key(1)), RESULT)
    entry = json.loads(journal.entry_path(_key(1)).read_text())
    del entry["sha256"]
    journal.entry_path(_key(1)).write_text(json.dumps(entry))
    journal.put(_key(2), _inputs(_key(2)), RESULT)
    journal.entry_path(_key(2)).write_bytes(b"")
    assert journal.get(_key(1)) is None and journal.get(_key(2)) is None
    assert journal.n_corrupt == 2
    assert "missing field(s) sha256" in journal.corrupt_reasons[0]
    assert "empty file" in journal.corrupt_reasons[1]


def test_a_batch_put_as_one_pack_reads_back_like_single_entries(tmp_path):
    journal = Journal(tmp_path)
    keys = [_key(n) for n in range(3)]
    journal.put_many([(key, _inputs(key), {**RESULT, "n_events": n}) for n, key in enumerate(keys)])
    journal.put(_key(3), _inputs(_key(3)), RESULT)
    assert len(list((tmp_path / "journal" / "packs").iterdir())) == 1  # one file, three runs
    fresh = Journal(tmp_path)  # a resume reads the pack again
    assert [fresh.get(key)["n_events"] for key in keys] == [0, 1, 2]
    assert fresh.entry(keys[1])["inputs"] == _inputs(keys[1])
    assert fresh.keys() == sorted([*keys, _key(3)]) and len(fresh) == 4 and keys[2] in fresh
    assert Journal.count(tmp_path) == 4
    assert fresh.computed_counts() == {key: 1 for key in [*keys, _key(3)]}


def test_a_damaged_line_of_a_pack_is_reported_and_computed_again(tmp_path):
    journal = Journal(tmp_path)
    keys = [_key(n) for n in range(3)]
    journal.put_many([(key, _inputs(key), RESULT) for key in keys])
    (pack,) = (tmp_path / "journal" / "packs").iterdir()
    pack.write_bytes(pack.read_bytes().replace(b"0.0123456789", b"0.0123456780", 1))
    fresh = Journal(tmp_path)
    assert [fresh.get(key) is None for key in keys] == [True, False, False]
    assert fresh.n_corrupt == 1 and "sha256 mismatch" in fresh.corrupt_reasons[0]
    assert any("packs/" in line for line in moved_aside(tmp_path))
    fresh.put_many([(keys[0], _inputs(keys[0]), RESULT)])  # computed again: a later pack wins
    assert Journal(tmp_path).get(keys[0]) == RESULT


def test_a_torn_pack_left_by_a_killed_put_is_removed(tmp_path):
    journal = Journal(tmp_path)
    journal.put_many([(_key(0), _inputs(_key(0)), RESULT)])
    torn = tmp_path / "journal" / "packs" / ".00000002.pack.123.x.tmp"
    torn.write_bytes(b"half a batch")
    assert Journal(tmp_path).clean_temp_files() == 1 and not torn.exists()
    assert Journal(tmp_path).keys() == [_key(0)]


def test_computed_counts_counts_repeated_puts(tmp_path):
    journal = Journal(tmp_path)
    assert journal.computed_counts() == {}
    for key in (_key(1), _key(2), _key(1), _key(1)):
        journal.put(key, _inputs(key), RESULT)
    assert journal.computed_counts() == {_key(1): 3, _key(2): 1}
    assert len(journal) == 2 and journal.get(_key(1)) == RESULT  # overwritten atomically
    assert Journal(tmp_path).computed_counts() == {_key(1): 3, _key(2): 1}


def test_truncated_last_log_line_is_ignored_and_next_put_still_logged(tmp_path):
    journal = Journal(tmp_path)
    journal.put(_key(1), _inputs(_key(1)), RESULT)
    with open(journal.log_path, "ab") as fh:
        fh.write(_key(2)[:30].encode())  # a write cut short by a crash
    assert journal.computed_counts() == {_key(1): 1}
    journal.put(_key(3), _inputs(_key(3)), RESULT)
    assert journal.computed_counts() == {_key(1): 1, _key(3): 1}


# --- lock ---------------------------------------------------------------------------------

_HOLDER_SCRIPT = textwrap.dedent(
    """
    import sys, time
    from frictiondisk.store.lock import CampaignLock
    with CampaignLock(sys.argv[1]):
        print("locked", flush=True)
        time.sleep(60)
    """
)


@pytest.fixture
def lock_holder(tmp_path):
    """A separate process holding the lock of tmp_path / "campaign"; killed at the end."""
    campaign = tmp_path / "campaign"
    proc = subprocess.Popen(
        [sys.executable, "-c", _HOLDER_SCRIPT, str(campaign)],
        stdout=subprocess.PIPE,
        text=True,
        cwd=Path(__file__).resolve().parent.parent,
    )
    try:
        assert proc.stdout.readline().strip() == "locked"
        yield campaign, proc
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(timeout=10)
        proc.stdout.close()


def test_second_lock_is_refused_naming_dir_and_pid(lock_holder):
    campaign, proc = lock_holder
    assert CampaignLock.holder(campaign) == proc.pid
    with pytest.raises(CampaignLocked, match=rf"in use .*\(PID {proc.pid}, started ") as info:
        with CampaignLock(campaign):
            pass
    assert info.value.pid == proc.pid and str(campaign) in str(info.value)
    assert info.value.directory == campaign


def test_sigkilled_holder_leaves_no_stuck_lock(lock_holder):
    campaign, proc = lock_holder
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait(timeout=10)
    assert CampaignLock.holder(campaign) is None
    with CampaignLock(campaign) as lock:
        assert lock.held
        assert CampaignLock.holder(campaign) == os.getpid()
    assert not lock.held
    assert CampaignLock.holder(campaign) is None


def test_lock_in_one_process_is_exclusive_and_reusable(tmp_path):
    assert CampaignLock.holder(tmp_path) is None  # no lock file yet
    assert not (tmp_path / "lock").exists()
    with CampaignLock(tmp_path):
        with pytest.raises(CampaignLocked, match=rf"PID {os.getpid()}"):
            CampaignLock(tmp_path).acquire()
    with CampaignLock(tmp_path):
        pass
    assert CampaignLock.holder(tmp_path) is None


def test_forked_child_does_not_keep_the_lock(tmp_path):
    lock = CampaignLock(tmp_path).acquire()
    pid = os.fork()
    if pid == 0:  # child: sleeps while the parent releases
        import time

        time.sleep(5)
        os._exit(0)
    try:
        lock.release()
        assert CampaignLock.holder(tmp_path) is None  # the live child does not hold it
    finally:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)


# --- atomic files -------------------------------------------------------------------------


def _temp_files(directory: Path) -> list[Path]:
    return [p for p in directory.rglob("*") if p.name.endswith(".tmp")]


def _dataset() -> xr.Dataset:
    rng = np.random.default_rng(0)
    return xr.Dataset(
        {
            "outcome": (("mu", "x_ms"), rng.integers(0, 3, (200, 50)).astype(np.int8)),
            "amplitude": (("mu", "x_ms"), rng.normal(size=(200, 50)), {"units": "m"}),
        },
        coords={"mu": np.linspace(0.05, 0.2, 200), "x_ms": np.linspace(0.0, 0.2, 50)},
        attrs={"title": "test"},
    )


def test_atomic_write_netcdf_round_trip_and_truncation_detected(tmp_path):
    path = tmp_path / "sub" / "results.nc"
    assert not netcdf_is_valid(path)
    ds = _dataset()
    assert atomic_write_netcdf(ds, path) == path
    assert netcdf_is_valid(path)
    with xr.open_dataset(path) as back:
        xr.testing.assert_identical(back.load(), ds)
    assert _temp_files(tmp_path) == []

    _truncate(path)
    assert not netcdf_is_valid(path)
    atomic_write_netcdf(ds, path)  # repair: replaces the truncated file
    assert netcdf_is_valid(path)


def test_netcdf_is_valid_rejects_garbage_and_empty(tmp_path):
    (tmp_path / "empty.nc").write_bytes(b"")
    (tmp_path / "text.nc").write_text("not netCDF")
    assert not netcdf_is_valid(tmp_path / "empty.nc")
    assert not netcdf_is_valid(tmp_path / "text.nc")
    assert not netcdf_is_valid(tmp_path)  # a directory


def test_failed_netcdf_write_keeps_old_file_and_leaves_no_temp(tmp_path):
    path = tmp_path / "results.nc"
    atomic_write_netcdf(_dataset(), path)
    before = path.read_bytes()
    bad = xr.Dataset({"x": ("t", np.array([object(), object()]))})  # netCDF cannot store
    with pytest.raises(Exception):  # noqa: B017 - whatever the backend raises
        atomic_write_netcdf(bad, path)
    assert path.read_bytes() == before and netcdf_is_valid(path)
    assert _temp_files(tmp_path) == []


def test_atomic_write_bytes_and_text(tmp_path):
    path = tmp_path / "a" / "b.txt"
    atomic_write_text(path, "first\n")
    atomic_write_bytes(path, b"second\n")
    assert path.read_bytes() == b"second\n"
    assert sorted(p.name for p in path.parent.iterdir()) == ["b.txt"]


@pytest.mark.parametrize(
    "scene",
    [
        {"scene": "pin", "params": {"mu": 0.2, "x0": -0.0}},
        {"scene": "disk", "contact": {"points": 3}, "params": {"beta_b": 0.1}},
        {
            "scene": "disk",
            "params": {"beta_b": 0.1},
            "contact": {"layout": "points", "positions": [[0.0, 0.01], [0.02, 0.0]]},
        },
    ],
)
def test_a_scene_written_once_gives_the_key_and_the_entry_of_run_key(scene):
    """scene_key on canonical_json's text is run_key, and an entry encoded with that text
    is byte for byte the one encoded from the inputs alone."""
    config = scene_from_dict(scene)
    canonical = config.canonical()
    text = journal_module.canonical_json(canonical)
    key = journal_module.scene_key(canonical, text)
    assert key == run_key(config)
    result = {"outcome": "stick", "R1": 0.01, "n_steps": 3, "a": None}
    assert journal_module.encode(key, canonical, result, text) == journal_module.encode(
        key, canonical, result
    )
    # inputs that are not JSON's own types are read back, whatever text comes with them
    tupled = {**canonical, "extra": (1, 2)}
    assert journal_module.encode(key, tupled, result, "{}") == journal_module.encode(
        key, tupled, result
    )
