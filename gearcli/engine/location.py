"""Where the compiled kernel is cached and under which key.

The cache: ``$XDG_CACHE_HOME/gearcli/numba``, else ``~/.cache/gearcli/numba``, else ``$TMPDIR/gearcli-<uid>/numba``
(:func:`cache_choice`), one subdirectory per kernel source and numba version (:func:`cache_dir`): the key hashes
every module the kernel compiles (:data:`KERNEL_SOURCES`, the element registry and every registered element's
module), the BLAS it calls and numba's installation. The loader (:mod:`gearcli.engine.loader`) and numba's cache
(:mod:`gearcli.engine.numba_cache`) both read it here.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import tempfile
from pathlib import Path

from gearcli.engine import blas, cachedir
from gearcli.model import elements

#: the kernel's modules (numba-compiled, or read by compiled code), relative to the gearcli package: their source is
#: in the cache key (tests/engine/test_engine_layers.py checks that every module the kernel imports is here)
KERNEL_SOURCES = ("engine/kernel.py", "engine/rk.py", "engine/radau.py", "engine/common.py", "engine/guards.py",
                  "engine/rhs.py", "engine/jacobian.py", "engine/assembly.py", "engine/linalg.py", "engine/laws.py",
                  "engine/dispatch.py", "engine/tableau.py", "engine/window.py", "engine/packing.py", "engine/blas.py",
                  "engine/status.py",
                  "engine/numba_cache.py",  # its jit options (reference counting or not) are in the machine code
                  "model/elements/__init__.py", "model/elements/torque.py", "model/elements/machine.py",
                  "model/elements/profile.py", "model/elements/energy.py",
                  "model/contact_lines.py")  # + every compiled element's module (_source_key)
#: the modules holding numba dispatchers (bound to the cache directory at import): a fresh load imports them anew
FRESH = ("gearcli.engine.kernel", "gearcli.engine.rk", "gearcli.engine.radau", "gearcli.engine.common",
         "gearcli.engine.guards", "gearcli.engine.rhs", "gearcli.engine.jacobian", "gearcli.engine.assembly",
         "gearcli.engine.linalg", "gearcli.engine.laws", "gearcli.engine.window", "gearcli_dispatch")

_memo: dict = {}


def _usable_dir(path: Path) -> str | None:
    """Why ``path`` cannot hold the cache (None: it can): it must be absolute and be, or become, a writable
    directory."""
    if not path.is_absolute():
        return "not an absolute path"
    probe = path
    while not probe.exists() and probe != probe.parent:
        probe = probe.parent
    if not probe.is_dir():
        return f"{probe} is not a directory"
    if not os.access(probe, os.W_OK | os.X_OK):
        return f"{probe} is not writable"
    return None


def _candidates() -> list[tuple[str, Path, tuple[str, ...]]]:
    """(name, base, the directories gearcli owns below it) of each place the cache may go, in order."""
    xdg = os.environ.get("XDG_CACHE_HOME")
    own = f"gearcli-{os.getuid()}" if hasattr(os, "getuid") else "gearcli"
    out: list[tuple[str, Path, tuple[str, ...]]] = [("XDG_CACHE_HOME", Path(xdg), ("gearcli", "numba"))] if xdg else []
    return out + [("~/.cache", Path(os.path.expanduser("~")) / ".cache", ("gearcli", "numba")),
                  ("the temporary directory", Path(tempfile.gettempdir()), (own, "numba"))]


def _choice() -> tuple[Path, tuple[str, ...], str]:
    why = ""
    cands = _candidates()
    for name, base, parts in cands:
        problem = _usable_dir(base.joinpath(*parts))
        if problem is None:
            return base, parts, why
        why = why or f"{name} cannot hold the cache ({problem})"
    return cands[-1][1], cands[-1][2], why


def cache_choice() -> tuple[Path, str]:
    """The cache root and, when ``$XDG_CACHE_HOME`` (or the home directory) cannot hold it, why another one is
    used ('' when the first choice is used): $XDG_CACHE_HOME, else ~/.cache, else the temporary directory."""
    base, parts, why = _choice()
    return base.joinpath(*parts), why


def cache_root() -> Path:
    return cache_choice()[0]


def _source_key() -> str:
    """The kernel's cache key: its sources, the registry, numpy's BLAS, the installed numba, and where this gearcli
    is. numba's cache index records each source file's modification time and size and discards itself when they
    differ: two checkouts at different paths (same sources, other times) sharing one key would each rewrite the
    other's index and rebuild the kernel on every switch; one key per installed package keeps both."""
    h = hashlib.sha1()
    pkg = Path(__file__).resolve().parent.parent
    h.update(str(pkg).encode())
    for rel in KERNEL_SOURCES:
        h.update((pkg / rel).read_bytes())
    for et in elements.compiled_types():  # the registry: what the generated dispatch calls, and the laws' code
        h.update(f"{et.kind}:{et.name}:{et.law.__name__}".encode())
        h.update(Path(et.law.__file__ or "").read_bytes())
    h.update(blas.KEY.encode())
    spec = importlib.util.find_spec("numba")  # the installed numba (its path and version stamp), without importing it
    if spec is not None and spec.origin:
        h.update(f"{spec.origin}:{os.stat(spec.origin).st_mtime_ns}".encode())
    return h.hexdigest()[:16]


def cache_dir() -> Path:
    """Where the compiled kernel is cached (one subdirectory per kernel source and numba version)."""
    return cache_root() / _source_key()


def cache_problem() -> str | None:
    """Why the cache directory is refused (created 0700 where missing), or None: it is the user's own."""
    if "problem" not in _memo:
        base, parts, _ = _choice()
        _memo["problem"] = cachedir.check(base, (*parts, _source_key()))
    return _memo["problem"]
