"""gearcli.engine.numba_cache's entries round-trip: an entry written in the fast format (machine code and the symbols
it defines, the linkable IR parsed on first link) and, where numba's internals are not the ones that format follows,
numba's own entry rebuilt numba's own way. Checked by calling the rebuilt function: 2 x + 1 at x = 20 is 41."""

from __future__ import annotations

import pytest

numba = pytest.importorskip("numba")

from gearcli.engine import numba_cache  # noqa: E402 - after the importorskip


def _compiled():
    f = numba.njit(lambda x: 2.0 * x + 1.0)
    f(1.0)
    (cres,) = f.overloads.values()
    return f, cres


def test_the_fast_entry_rebuilds_a_working_function():
    f, cres = _compiled()
    impl = numba_cache._Impl.__new__(numba_cache._Impl)
    entry = impl.reduce(cres)
    assert entry[0] == numba_cache._FORMAT and entry[1]  # the symbols its machine code defines
    rebuilt = impl.rebuild(f.targetctx, entry)
    assert isinstance(rebuilt.library, numba_cache._Library)
    assert rebuilt.entry_point(20.0) == 41.0


def test_with_other_numba_internals_the_entry_is_numbas_own(monkeypatch):
    monkeypatch.setattr(numba_cache, "_fast_load", lambda: False)
    f, cres = _compiled()
    impl = numba_cache._Impl.__new__(numba_cache._Impl)
    entry = impl.reduce(cres)
    assert entry[0] == numba_cache._NUMBA and entry[1] is None
    rebuilt = impl.rebuild(f.targetctx, entry)
    assert not isinstance(rebuilt.library, numba_cache._Library)
    assert rebuilt.entry_point(20.0) == 41.0

