"""$XDG_CACHE_HOME that cannot hold the engine cache (a file, say): the cache goes to ~/.cache as documented, and the
build and `gearcli engine build` say why, in one line naming the variable, instead of silently ignoring the
user's setting."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from gearcli import api
from gearcli.cli import cli
from gearcli.core import announce
from gearcli.engine import builder, loader


def _refused_xdg(tmp_path: Path, monkeypatch) -> Path:
    not_a_dir = tmp_path / "cachefile"
    not_a_dir.write_text("")
    monkeypatch.setenv("XDG_CACHE_HOME", str(not_a_dir))
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.delitem(loader._state, "quiet", raising=False)
    monkeypatch.setattr(announce, "_reporter", [])  # no reporter an earlier command (-q, say) left installed
    return not_a_dir


def test_the_build_names_the_refused_variable(tmp_path, monkeypatch, capsys):
    not_a_dir = _refused_xdg(tmp_path, monkeypatch)
    monkeypatch.setattr(builder, "run", lambda cdir, reporter: 0.0)  # the compilation itself is not under test
    cdir = loader.cache_dir()
    assert cdir.is_relative_to(tmp_path / "home" / ".cache")  # the documented next choice
    loader._build(cdir, quiet=False)
    err = capsys.readouterr().err
    assert "XDG_CACHE_HOME cannot hold the cache" in err and str(not_a_dir) in err
    assert str(tmp_path / "home" / ".cache") in err and "Traceback" not in err
    loader._build(cdir, quiet=True)
    assert capsys.readouterr().err == ""


def test_engine_build_says_it_too(tmp_path, monkeypatch):
    not_a_dir = _refused_xdg(tmp_path, monkeypatch)
    cdir = loader.cache_dir()
    monkeypatch.setattr(api, "engine_build", lambda force, quiet: loader.Built(cdir, 0.0, 0.3, None))
    res = CliRunner().invoke(cli, ["engine", "build"])
    assert res.exit_code == 0, res.stderr
    assert "XDG_CACHE_HOME cannot hold the cache" in res.stderr and str(not_a_dir) in res.stderr
    assert res.stdout.startswith(f"engine: already compiled; cached in {cdir}")
    quiet = CliRunner().invoke(cli, ["engine", "build", "-q"])
    assert quiet.exit_code == 0 and quiet.stderr == ""
