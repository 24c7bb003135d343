"""The compiled engine's cache directory (issue 31, security): created 0700, refused when another user owns it or
others may write to it, files in it never opened through a symbolic link, numba's pickled index files loaded only
from a directory that passed the check.

The two-user test needs root (to act as a second user: a forked child drops to another uid with ``os.setuid``
before it plants anything); it is skipped elsewhere. The victim is this process's user.
"""

from __future__ import annotations

import os
import pickle
import shutil
import stat
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

import pytest

from gearcli.engine import cachedir

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
ATTACKER_UID = 54321


class _Plant:
    """A pickle that, when loaded, writes a marker file (what a planted numba index would run)."""

    def __init__(self, marker: str) -> None:
        self.marker = marker

    def __reduce__(self):
        return (os.system, (f"touch {self.marker}",))


def _as_other_user(uid: int, action) -> None:
    """Run ``action()`` in a forked child that has dropped to ``uid`` (no exec: the interpreter's directory may be
    closed to that user); raise when it failed."""
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        code = 1
        try:
            os.setgid(uid)
            os.setuid(uid)
            action()
            code = 0
        except BaseException as exc:
            os.write(2, f"second user: {exc!r}\n".encode())
        finally:
            os._exit(code)
    _, status = os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0, "the second user's step failed"


def test_directories_are_created_0700_and_checked(tmp_path):
    base = tmp_path / "cache"
    base.mkdir()
    assert cachedir.check(base, ("gearcli", "numba", "key")) is None
    for p in (base / "gearcli", base / "gearcli" / "numba", base / "gearcli" / "numba" / "key"):
        assert stat.S_IMODE(p.stat().st_mode) == 0o700
    loose = base / "loose"
    loose.mkdir()
    loose.chmod(0o777)
    problem = cachedir.check(base, ("loose", "numba"))
    assert problem and str(loose) in problem and "writable by its group and other users" in problem
    (base / "link").symlink_to(base / "gearcli")
    assert "symbolic link" in cachedir.check(base, ("link",))
    (base / "file").write_text("x")
    assert "not a directory" in cachedir.check(base, ("file",))


def test_json_files_are_never_opened_through_a_link(tmp_path):
    target = tmp_path / "victim.txt"
    target.write_text("precious")
    link = tmp_path / "load_time.json"
    link.symlink_to(target)
    assert cachedir.read_json(link) is None  # not followed
    assert cachedir.write_json(link, {"load_s": 0.3})
    assert target.read_text() == "precious"  # the link was replaced, its target untouched
    assert not link.is_symlink() and cachedir.read_json(link) == {"load_s": 0.3}
    assert stat.S_IMODE(link.stat().st_mode) == 0o600


def test_a_cache_record_that_is_no_readable_json_reads_as_none(tmp_path):
    """A corrupted record (``ready.json``, ``load_time.json``) nested past the JSON parser's recursion limit raised
    RecursionError out of read_json, and every compiled run and sweep ended in an internal error (exit 1)."""
    for name, text in (("deep.json", "[" * 100_000), ("garbage.json", "{not json"), ("empty.json", "")):
        path = tmp_path / name
        path.write_text(text)
        assert cachedir.read_json(path) is None, name


@pytest.mark.slow  # ~10 s: three processes load the engine
@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="acting as a second user needs root")
def test_a_cache_directory_another_user_prepared_is_refused(tmp_path):
    """The attacker (another uid) creates the victim's fallback cache ``$TMPDIR/gearcli-<uid>/numba`` mode 0777
    before the victim runs, plants ``load_time.json`` as a link to a victim's file and a pickle as a numba index in
    the kernel's directory. The victim (no usable XDG_CACHE_HOME or ~/.cache) runs the compiled engine: the
    directory is refused in one line, the link's target is unchanged, the pickle never runs, and the run goes on
    (here under NUMBA_DISABLE_JIT: the whole load path without the minute of compilation)."""
    from gearcli.engine import loader

    shared = Path(tempfile.mkdtemp(prefix="gearcli-two-users-", dir="/tmp" if os.path.isdir("/tmp") else None))
    shared.chmod(0o755)  # pytest's own tmp_path is closed to other users
    tmpdir = shared / "tmp"
    tmpdir.mkdir()
    tmpdir.chmod(0o1777)  # a shared /tmp
    victim_file = tmp_path / "victim.txt"
    victim_file.write_text("precious")
    marker = tmp_path / "pickle_ran"
    own = tmpdir / f"gearcli-{os.getuid()}"
    key_dir = own / "numba" / loader._source_key()

    def plant() -> None:
        for d in (own, own / "numba", key_dir, key_dir / "engine_planted"):
            os.mkdir(d)
            os.chmod(d, 0o777)
        os.symlink(victim_file, own / "numba" / "load_time.json")
        os.symlink(victim_file, key_dir / "load_time.json")
        with open(key_dir / "ready.json", "w") as fh:
            fh.write("{}")
        for name in ("rk.rk_run-1.py311.nbi", "gearcli_dispatch.conn_force-1.py311.nbi"):
            with open(key_dir / "engine_planted" / name, "wb") as fh:
                pickle.dump(_Plant(str(marker)), fh)

    try:
        _as_other_user(ATTACKER_UID, plant)
        _victim_runs(tmp_path, tmpdir, own, victim_file, marker)
    finally:
        shutil.rmtree(shared, ignore_errors=True)


def _victim_runs(tmp_path: Path, tmpdir: Path, own: Path, victim_file: Path, marker: Path) -> None:
    blocker = tmp_path / "not-a-dir"
    blocker.write_text("")
    assert (own / "numba").stat().st_uid == ATTACKER_UID
    env = dict(os.environ, PYTHONPATH=str(ROOT), TMPDIR=str(tmpdir), XDG_CACHE_HOME=str(blocker),
               HOME=str(blocker), NUMBA_DISABLE_JIT="1")
    script = textwrap.dedent("""
        from gearcli import engine
        print(engine.expected_load_s() >= 30, engine.cache_problem() is not None)
        engine.entry("DOP853")
        print("loaded")
    """)
    res = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    assert res.stdout.split() == ["True", "True", "loaded"]  # auto prices a compilation: the cache is not trusted
    refusals = [line for line in res.stderr.splitlines() if "not using the engine cache" in line]
    assert len(refusals) == 1 and str(own) in refusals[0] and "another user" in refusals[0], res.stderr
    assert "Traceback" not in res.stderr
    assert victim_file.read_text() == "precious"
    assert not marker.exists()
    # the command line, engine = auto and compiled, the same directory: the same refusal, nothing run or written
    for engine_name in ("auto", "compiled"):
        res = subprocess.run([sys.executable, "-m", "gearcli", "simulate", str(SEED), "--format", "json",
                              "--set", f"simulation.engine={engine_name}", "--set", "simulation.duration_s=0.05",
                              "--set", "simulation.steps=50"],
                             env=env, capture_output=True, text=True, timeout=600, cwd=tmp_path)
        assert res.returncode == 0, res.stderr
        assert "Traceback" not in res.stderr and "internal error" not in res.stderr
    assert victim_file.read_text() == "precious"
    assert not marker.exists()
    assert not list(tmpdir.glob("gearcli-engine-*"))  # the private directory of the refused run is gone


def test_a_group_writable_cache_of_ones_own_is_refused(tmp_path, monkeypatch):
    from gearcli import engine
    from gearcli.engine import loader, location

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    (tmp_path / "gearcli").mkdir(mode=0o700)
    (tmp_path / "gearcli" / "numba").mkdir()
    (tmp_path / "gearcli" / "numba").chmod(0o775)
    monkeypatch.setattr(loader, "_state", {})
    monkeypatch.setattr(engine, "_state", loader._state)
    monkeypatch.setattr(location, "_memo", {})  # the cache's verdict, asked anew
    problem = engine.cache_problem()
    assert problem and "writable by its group" in problem and str(tmp_path / "gearcli" / "numba") in problem
    assert engine.expected_load_s() >= 30  # never trusted: auto prices a compilation
