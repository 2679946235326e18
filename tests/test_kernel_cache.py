"""The numba cache follows every kernel source (issue 22): numba itself checks only the
timestamp of a function's own file, so an edit to monitor.py could run with a stale
compiled driver.run. kernel/jit.py names the cache folder by a hash of all of them."""

from __future__ import annotations

import shutil
from pathlib import Path

import numba

from frictiondisk.kernel import jit

KERNEL = Path(jit.__file__).resolve().parent


def _copy(tmp_path: Path) -> Path:
    sources = tmp_path / "kernel"
    sources.mkdir()
    for source in KERNEL.glob("*.py"):
        shutil.copy(source, sources / source.name)
    return sources


def test_the_cache_in_use_is_named_by_the_current_sources():
    assert numba.config.CACHE_DIR == jit.kernel_cache_dir(KERNEL)


def test_an_edit_to_any_kernel_file_moves_the_cache(tmp_path, monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    sources = _copy(tmp_path)
    before = jit.kernel_cache_dir(sources)
    assert jit.kernel_cache_dir(sources) == before  # same sources, same folder
    for name in ("monitor.py", "verdict.py", "model.py"):  # not the dispatcher's own file
        with (sources / name).open("a") as file:
            file.write("\n# edited\n")
        after = jit.kernel_cache_dir(sources)
        assert after != before, name
        before = after


def test_a_new_kernel_file_moves_the_cache(tmp_path, monkeypatch):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    sources = _copy(tmp_path)
    before = jit.kernel_cache_dir(sources)
    (sources / "helpers.py").write_text("X = 1\n")
    assert jit.kernel_cache_dir(sources) != before
