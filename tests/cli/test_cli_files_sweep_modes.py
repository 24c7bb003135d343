"""Issue 11, files: `gearcli modes` and `gearcli sweep` honour the same `-o` rules as the other commands
(docs/output.md, "Files"). sweep's `-o` is resumable (it reads the file back), so a symlink, a directory, a
FIFO, the input itself or a missing parent must be refused before anything is read or computed: the
refusal comes before the design is loaded (no design warning is printed), exit 2, the path named, and
nothing is created. The device case uses a FIFO stand-in, never a real device.
"""

from __future__ import annotations

import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
SWEEP = ["--vary", "input.speed_rpm=500,600", "--jobs", "1", "--set", "simulation.duration_s=0.05",
         "--set", "simulation.steps=50"]
ARGS = {"modes": [], "sweep": SWEEP}


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "in.toml").write_bytes(SEED.read_bytes())
    return tmp_path


def run(command, *extra):
    return CliRunner().invoke(cli, [command, "in.toml", *ARGS[command], *[str(a) for a in extra]])


def assert_refused_before_loading(res, fragment: str, named: str) -> None:
    assert res.exit_code == 2, (res.exit_code, res.output)
    assert f"gearcli: {named}" in res.stderr and fragment in res.stderr, res.stderr
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr
    assert "warning:" not in res.stderr  # the seed's target-speed warning comes right after loading
    assert res.stdout == ""


@pytest.mark.parametrize("command", ["modes", "sweep"])
@pytest.mark.parametrize(("make", "out", "fragment"), [
    (lambda w: (w / "d").mkdir(), "d", "is a directory"),
    (lambda w: None, "newdir/", "is a directory path"),
    (lambda w: os.mkfifo(w / "pipe.csv"), "pipe.csv", "is a FIFO"),
    (lambda w: None, "in.toml", "is the input file"),
    (lambda w: os.symlink("in.toml", w / "alias.csv"), "alias.csv", "is the input file"),
    (lambda w: None, "missing/dir/x.csv", "no such directory"),
    (lambda w: None, "x.md", "cannot write markdown"),
])
def test_refused_outputs(work, command, make, out, fragment):
    make(work)
    before = sorted(os.listdir(work))
    seed = (work / "in.toml").read_bytes()
    res = run(command, "-o", out)
    assert_refused_before_loading(res, fragment, out)
    assert sorted(os.listdir(work)) == before  # nothing created (no temporary file either)
    assert (work / "in.toml").read_bytes() == seed


@pytest.mark.parametrize("command", ["modes", "sweep"])
def test_read_only_directory_is_refused(work, command, monkeypatch):
    ro = work / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    if os.access(ro, os.W_OK):  # root writes anywhere: deny the directory as a read-only mount would
        real = os.access
        monkeypatch.setattr(os, "access", lambda p, mode, **kw: False if Path(p) == ro and mode & os.W_OK
                            else real(p, mode, **kw))
    try:
        assert_refused_before_loading(run(command, "-o", "ro/x.csv"), "not writable", "ro/x.csv")
        assert os.listdir(ro) == []
    finally:
        ro.chmod(0o755)


@pytest.mark.parametrize("command", ["modes", "sweep"])
def test_suffix_and_format_must_agree(work, command):
    assert_refused_before_loading(run(command, "--format", "csv", "-o", "x.json"), "--format is csv", "x.json")


@pytest.mark.parametrize("command", ["modes", "sweep"])
def test_a_fifo_does_not_hang_the_command(work, command):
    """Opening a FIFO for writing blocks until a reader comes: a real process, with a timeout."""
    os.mkfifo(work / "f.json")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    res = subprocess.run([sys.executable, "-m", "gearcli", command, "in.toml", *ARGS[command], "-o", "f.json"],
                         capture_output=True, text=True, timeout=60, env=env, cwd=work)
    assert res.returncode == 2 and "f.json: is a FIFO" in res.stderr, res.stderr


def test_modes_writes_through_a_symlink_and_keeps_it(work):
    os.symlink("target.json", work / "link.json")
    res = run("modes", "-o", "link.json")
    assert res.exit_code == 0, res.stderr
    assert (work / "link.json").is_symlink() and os.readlink(work / "link.json") == "target.json"
    assert json.loads((work / "target.json").read_text())["input_sha256"]


def test_modes_dash_is_stdout(work):
    res = run("modes", "--format", "json", "-o", "-")
    assert res.exit_code == 0, res.stderr
    json.loads(res.stdout)
    assert not (work / "-").exists()


def _rows(path: Path) -> list[dict]:
    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    return list(csv.DictReader(lines))


def test_sweep_writes_and_resumes_through_a_symlink(work):
    os.symlink("target.csv", work / "link.csv")
    res = run("sweep", "-o", "link.csv")
    assert res.exit_code == 0, res.stderr
    assert (work / "link.csv").is_symlink() and os.readlink(work / "link.csv") == "target.csv"
    rows = _rows(work / "target.csv")
    assert [float(r["input.speed_rpm"]) for r in rows] == [500.0, 600.0]
    res = run("sweep", "-o", "link.csv")  # the same sweep again: nothing to do, the file intact
    assert res.exit_code == 0, res.stderr
    assert (work / "link.csv").is_symlink()
    again = _rows(work / "target.csv")
    assert [r["input.speed_rpm"] for r in again] == [r["input.speed_rpm"] for r in rows]
    assert [r["wall_s"] for r in again] == [r["wall_s"] for r in rows]  # not re-run: the same wall times


def test_sweep_dash_is_stdout(work):
    res = run("sweep", "-o", "-")
    assert res.exit_code == 0, res.stderr
    assert "input.speed_rpm" in res.stdout
    assert not (work / "-").exists()


def test_sweep_plots_may_not_replace_the_input(work):
    (work / "campbell.png").symlink_to("in.toml")
    res = run("sweep", "--plots", ".")
    assert_refused_before_loading(res, "would overwrite", "campbell.png")
