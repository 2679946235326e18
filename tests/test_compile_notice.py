"""The "compiling the kernel" line: printed only when numba will really compile."""

from __future__ import annotations

import io
from types import SimpleNamespace

from frictiondisk.simulation import compile_notice
from frictiondisk.simulation.compile_notice import MESSAGE, announce_compile, needs_compiling


def _dispatcher(signatures, index=None, broken=False):
    def load_index():
        if broken:
            raise OSError("unreadable cache")
        return index

    cache = SimpleNamespace(_cache_file=SimpleNamespace(_load_index=load_index))
    return SimpleNamespace(signatures=signatures, _cache=cache)


def test_cold_cache_compiles_warm_cache_and_loaded_kernel_do_not():
    assert needs_compiling(_dispatcher([], index={})) is True  # nothing on disk
    assert needs_compiling(_dispatcher([], index={"sig": "entry"})) is False  # cache hit
    assert needs_compiling(_dispatcher(["(float64[:],)"])) is False  # loaded in this process
    assert needs_compiling(_dispatcher([], broken=True)) is True  # cannot tell: say it
    assert needs_compiling(SimpleNamespace()) is False  # NUMBA_DISABLE_JIT: plain Python


def test_the_line_goes_to_the_given_stream(monkeypatch):
    out = io.StringIO()
    monkeypatch.setattr(compile_notice, "needs_compiling", lambda: True)
    announce_compile(out)
    assert out.getvalue() == MESSAGE + "\n"
    assert f"about {compile_notice.COMPILE_S} s" in MESSAGE  # one estimate for every command
    monkeypatch.setattr(compile_notice, "needs_compiling", lambda: False)
    quiet = io.StringIO()
    announce_compile(quiet)
    assert quiet.getvalue() == ""
