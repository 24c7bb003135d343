"""The kernel's modules and its cache key: every module the compiled kernel imports is hashed into the key (a changed
module never runs stale machine code), every module holding numba dispatchers is imported anew by a fresh load, and
the engine's modules stay under the house limit (issue 34: the kernel split by concern). Read from the sources
(ast), without numba."""

from __future__ import annotations

import ast
from pathlib import Path

from gearcli.engine import location

PKG = Path(__file__).resolve().parents[2] / "gearcli"


def _imports(rel: str) -> set[str]:
    """The gearcli modules a module imports (``from gearcli.x import y``: ``gearcli.x.y`` when that is a module,
    else ``gearcli.x``)."""
    out = set()
    for node in ast.walk(ast.parse((PKG / rel).read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("gearcli"):
            subs = {f"{node.module}.{a.name}" for a in node.names}
            modules = {m for m in subs if _file_of(m)}
            out |= modules | ({node.module} if modules != subs else set())
        elif isinstance(node, ast.Import):
            out |= {a.name for a in node.names if a.name.startswith("gearcli")}
    return out


def _file_of(module: str) -> str | None:
    parts = module.split(".")[1:]
    for rel in ("/".join(parts) + ".py", "/".join(parts) + "/__init__.py"):
        if (PKG / rel).is_file():
            return rel
    return None


def test_every_module_the_kernel_imports_is_in_the_cache_key():
    """Walk the imports from the kernel's face through the engine's compiled modules and the element laws: each one
    reached is in ``KERNEL_SOURCES`` (the registered elements' own modules are hashed by the registry)."""
    seen, todo = set(), ["engine/kernel.py"]
    while todo:
        rel = todo.pop()
        if rel in seen:
            continue
        seen.add(rel)
        for mod in _imports(rel):
            f = _file_of(mod)
            if f and (f.startswith("engine/") or f.startswith("model/elements/") or f == "model/contact_lines.py"):
                todo.append(f)
    registry_hashed = {f"model/elements/{p.name}" for p in (PKG / "model" / "elements").glob("*.py")}
    cache_machinery = {"engine/cachedir.py", "engine/location.py"}  # where the cache is: no machine code in them
    missing = sorted(seen - set(location.KERNEL_SOURCES) - registry_hashed - cache_machinery)
    assert missing == []


def test_every_module_with_dispatchers_is_imported_anew_by_a_fresh_load():
    """A module that compiles functions (``@jit``/``@jit_alloc``) binds them to the cache directory at import: a
    fresh load (a repaired cache) must import it again (``location.FRESH``)."""
    compiling = set()
    for path in (PKG / "engine").glob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef) and any(
                    isinstance(d, ast.Name) and d.id in ("jit", "jit_alloc") for d in node.decorator_list):
                compiling.add(f"gearcli.engine.{path.stem}")
    compiling.add("gearcli.engine.laws")  # compiles the element laws at import (dispatch.jit_module)
    assert compiling <= set(location.FRESH)
    assert "gearcli.engine.numba_cache" not in location.FRESH  # holds the checked directory of this process


def test_the_engine_s_modules_stay_under_600_lines():
    sizes = {p.name: len(p.read_text(encoding="utf-8").splitlines()) for p in (PKG / "engine").glob("*.py")}
    assert {name: n for name, n in sizes.items() if n > 600} == {}
