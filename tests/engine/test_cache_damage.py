"""A damaged engine cache (issue 31): garbage or an empty numba index (.nbi), a truncated data file (.nbc), a
directory where a file belongs. Each is detected, reported in one line naming the cache directory, discarded and
rebuilt: the run goes on (exit 0, its result), and the next run finds the cache whole (no message).

Each test damages its own copy of the built cache (``XDG_CACHE_HOME`` in a temporary directory): the output
channels' function ``connector_series``, which every compiled run loads and whose rebuild takes seconds."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"

pytest.importorskip("numba")
pytestmark = [pytest.mark.slow]  # ~10 s each: two runs and a partial rebuild


def _env(**extra: str) -> dict[str, str]:
    return dict(os.environ, PYTHONPATH=str(ROOT), **extra)


@pytest.fixture(scope="module")
def built() -> Path:
    """The user's built cache (built now when missing: ``gearcli engine build``, in a child process)."""
    subprocess.run([sys.executable, "-m", "gearcli", "engine", "build", "-q"], env=_env(), check=True,
                   stdout=subprocess.DEVNULL, timeout=900)
    from gearcli import engine

    return engine.cache_dir()


def _copy(built: Path, tmp_path: Path) -> tuple[Path, Path]:
    xdg = tmp_path / "xdg"
    dest = xdg / "gearcli" / "numba" / built.name
    shutil.copytree(built, dest, symlinks=True, ignore=shutil.ignore_patterns("*.tmp.*", "build.lock"))
    for d in (xdg / "gearcli", xdg / "gearcli" / "numba", dest):
        d.chmod(0o700)
    return xdg, dest


def _entry_files(dest: Path) -> tuple[Path, Path]:
    # numba keeps one index set per source directory (engine_<sha1 of its path>): two checkouts of the same
    # source share the key directory, so take this checkout's, the one the child process (PYTHONPATH=ROOT) loads
    from numba.core.caching import _CacheLocator

    engine_dir = _CacheLocator.get_suitable_cache_subpath(str(ROOT / "gearcli" / "engine" / "kernel.py"))
    (index,) = (dest / engine_dir).glob("kernel.connector_series-*.nbi")
    (data,) = index.parent.glob(index.name[: -len("nbi")] + "*.nbc")
    return index, data


def _run(xdg: Path, tmp_path: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "gearcli", "simulate", str(SEED), "--format", "json",
                           "--set", "simulation.engine=compiled", "--set", "simulation.duration_s=0.05",
                           "--set", "simulation.steps=50"], env=_env(XDG_CACHE_HOME=str(xdg)), cwd=tmp_path,
                          capture_output=True, text=True, timeout=900)


def _garbage(index: Path, data: Path) -> None:
    index.write_bytes(b"\x80\x05not a pickle at all" * 7)


def _empty(index: Path, data: Path) -> None:
    index.write_bytes(b"")


def _truncated(index: Path, data: Path) -> None:
    raw = data.read_bytes()
    data.write_bytes(raw[: len(raw) // 2])


def _index_is_a_directory(index: Path, data: Path) -> None:
    index.unlink()
    index.mkdir()
    (index / "x").write_text("x")


def _data_is_a_directory(index: Path, data: Path) -> None:
    data.unlink()
    data.mkdir()


@pytest.mark.parametrize("damage", [_garbage, _empty, _truncated, _index_is_a_directory, _data_is_a_directory],
                         ids=lambda f: f.__name__.strip("_"))
def test_a_damaged_entry_is_named_discarded_and_rebuilt(damage, built, tmp_path):
    xdg, dest = _copy(built, tmp_path)
    damage(*_entry_files(dest))
    res = _run(xdg, tmp_path)
    assert res.returncode == 0, res.stderr
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr
    said = [line for line in res.stderr.splitlines() if "is damaged" in line]
    assert len(said) == 1 and str(dest) in said[0] and "connector_series" in said[0], res.stderr
    doc = json.loads(res.stdout)
    assert doc["solver"]["engine"] == "compiled"
    again = _run(xdg, tmp_path)  # rebuilt: whole again
    assert again.returncode == 0 and "damaged" not in again.stderr and "compiling" not in again.stderr, again.stderr
    assert json.loads(again.stdout)["summary"] == doc["summary"]


def test_a_directory_where_the_ready_mark_belongs(built, tmp_path):
    xdg, dest = _copy(built, tmp_path)
    (dest / "ready.json").unlink()
    (dest / "ready.json").mkdir()
    res = _run(xdg, tmp_path)
    assert res.returncode == 0, res.stderr
    said = [line for line in res.stderr.splitlines() if "is damaged" in line]
    assert len(said) == 1 and str(dest) in said[0] and "ready.json" in said[0], res.stderr
    assert (dest / "ready.json").is_file()
    again = _run(xdg, tmp_path)
    assert again.returncode == 0 and "damaged" not in again.stderr, again.stderr
