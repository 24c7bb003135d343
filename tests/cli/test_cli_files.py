"""Issue 11, "Data loss" and files: what `-o` may and may not do, for every command (docs/output.md, "Files").

Each case was measured to lose or damage data before; each must now be exit 2 with the path named, nothing
created or changed on disk, and the check made before the computation (a refused `simulate` does not run).
The device case uses a FIFO (and a character-device mode given to the checker), never a real device.
"""

from __future__ import annotations

import json
import os
import stat
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
COMMANDS = ["design", "simulate", "report"]


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "in.toml").write_bytes(SEED.read_bytes())
    return tmp_path


def run(*args, input=None):
    return CliRunner().invoke(cli, [str(a) for a in args], input=input)


def listing(path: Path) -> list[str]:
    return sorted(os.listdir(path))


def assert_refused(res, fragment: str, named: str) -> None:
    assert res.exit_code == 2, (res.exit_code, res.output)
    assert named in res.stderr and fragment in res.stderr, res.stderr
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr
    assert res.stdout == ""


def test_output_onto_the_input_file_is_refused_and_the_input_kept(work):
    before = (work / "in.toml").read_bytes()
    res = run("design", "in.toml", "--format", "json", "-o", "in.toml")
    assert_refused(res, "is the input file", "in.toml")
    assert (work / "in.toml").read_bytes() == before
    # the same file by another name, and through a symlink
    os.symlink("in.toml", work / "alias.json")
    res = run("design", "in.toml", "--format", "json", "-o", "./alias.json")
    assert_refused(res, "is the input file", "alias.json")
    assert (work / "in.toml").read_bytes() == before and (work / "alias.json").is_symlink()


@pytest.mark.parametrize("command", COMMANDS)
def test_a_fifo_is_refused_before_the_run(work, command):
    os.mkfifo(work / "pipe.json")
    res = run(command, "in.toml", "-o", "pipe.json", "--set", "simulation.duration_s=1e-3")
    assert_refused(res, "is a FIFO", "pipe.json")
    assert stat.S_ISFIFO(os.lstat(work / "pipe.json").st_mode)  # still a FIFO, not replaced by a file
    assert listing(work) == ["in.toml", "pipe.json"]


def test_a_device_is_refused_checked_by_its_mode():
    # a character device, as os.stat reports one (/dev/full was replaced by a regular file before)
    from gearcli.io.output import _kind

    assert _kind(stat.S_IFCHR | 0o666) is not None and "device" in _kind(stat.S_IFCHR | 0o666)
    assert "device" in _kind(stat.S_IFBLK | 0o660)
    assert "FIFO" in _kind(stat.S_IFIFO | 0o644)
    assert _kind(stat.S_IFREG | 0o644) is None


def test_symlink_is_written_through_and_stays_a_link(work):
    (work / "real.json").write_text("old\n")
    os.symlink("real.json", work / "link.json")
    res = run("design", "in.toml", "-o", "link.json")
    assert res.exit_code == 0, res.stderr
    assert (work / "link.json").is_symlink() and os.readlink(work / "link.json") == "real.json"
    assert json.loads((work / "real.json").read_text())["total_ratio"] > 1
    assert listing(work) == ["in.toml", "link.json", "real.json"]


def test_dash_is_stdout_and_creates_no_file(work):
    res = run("design", "in.toml", "--format", "json", "-o", "-")
    assert res.exit_code == 0, res.stderr
    assert json.loads(res.stdout)["stages"]
    assert listing(work) == ["in.toml"]


@pytest.mark.parametrize("command", ["design", "simulate", "report", "init", "schema"])
def test_missing_parent_directory_is_exit_2_and_names_the_path(work, command):
    args = {"init": ["init", "missing/dir/x.toml"], "schema": ["schema", "-o", "missing/dir/x.json"]}.get(
        command, [command, "in.toml", "-o", "missing/dir/x.json"])
    res = run(*args)
    assert_refused(res, "no such directory", "missing/dir")
    assert listing(work) == ["in.toml"]


@pytest.mark.parametrize(("given", "fragment"), [("missing/../x.json", "no such directory"),
                                                 ("in.toml/../x.json", "not a directory")])
def test_a_parent_the_system_cannot_walk_is_refused_though_dotdot_cancels_it_textually(work, given, fragment):
    # the reference is the system's own open(): it walks 'missing' (or the file 'in.toml') before '..' and fails,
    # as a shell's `> missing/../x.json` does; realpath() cancels the pair and gearcli wrote ./x.json before
    with pytest.raises((FileNotFoundError, NotADirectoryError)):
        open(given, "w").close()
    for command in ("design", "simulate"):
        res = run(command, "in.toml", "--format", "json", "-o", given)
        assert_refused(res, fragment, given)
        assert listing(work) == ["in.toml"]


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="root may write a read-only directory")
def test_read_only_directory_is_exit_2(work):
    ro = work / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        res = run("design", "in.toml", "-o", "ro/x.json")
        assert_refused(res, "not writable", "ro/x.json")
        assert listing(ro) == []
    finally:
        ro.chmod(0o755)


@pytest.mark.parametrize("command", ["design", "simulate", "report", "init", "schema"])
def test_read_only_directory_is_exit_2_also_as_root(work, command, monkeypatch):
    """As root a read-only directory is writable; deny it the way a read-only mount would (os.access)."""
    ro = work / "ro"
    ro.mkdir()
    real = os.access
    monkeypatch.setattr(os, "access", lambda p, mode, **kw: False if Path(p) == ro and mode & os.W_OK
                        else real(p, mode, **kw))
    out = "ro/x.toml" if command == "init" else "ro/x.json"
    args = {"init": ["init", out], "schema": ["schema", "-o", out]}.get(command, [command, "in.toml", "-o", out])
    res = run(*args)
    assert_refused(res, "not writable", out)
    assert listing(work / "ro") == []


@pytest.mark.parametrize("command", COMMANDS)
def test_a_directory_and_a_trailing_slash_are_refused(work, command):
    (work / "adir").mkdir()
    res = run(command, "in.toml", "-o", "adir")
    assert_refused(res, "is a directory", "adir")
    res = run(command, "in.toml", "-o", "newdir/")
    assert_refused(res, "directory", "newdir/")
    assert listing(work) == ["adir", "in.toml"] and listing(work / "adir") == []


@pytest.mark.parametrize(("command", "name", "fragment"), [
    ("design", "x.md", "cannot write markdown"),
    ("simulate", "x.md", "cannot write markdown"),
    ("report", "r.csv", "cannot write csv"),
    ("schema", "s.csv", "cannot write csv"),
    ("simulate", "run.xlsx", "cannot write an Excel workbook"),  # not CSV under a workbook's name
    ("design", "d.parquet", "cannot write Parquet"),
])
def test_a_suffix_the_command_cannot_write_is_an_error(work, command, name, fragment):
    args = ["schema", "-o", name] if command == "schema" else [command, "in.toml", "-o", name]
    res = run(*args)
    assert_refused(res, fragment, name)
    assert listing(work) == ["in.toml"]


def test_a_suffix_contradicting_format_is_an_error(work):
    res = run("design", "in.toml", "-o", "x.json", "--format", "csv")
    assert_refused(res, "says json but --format is csv", "x.json")
    assert listing(work) == ["in.toml"]


def test_the_suffix_chooses_the_format(work):
    assert run("design", "in.toml", "-o", "d.json").exit_code == 0
    assert json.loads((work / "d.json").read_text())["stages"]
    assert run("design", "in.toml", "-o", "d.csv").exit_code == 0
    assert (work / "d.csv").read_text().splitlines()[0].startswith("index,")


def test_init_dash_is_stdout(work):
    res = run("init", "-")
    assert res.exit_code == 0 and "[[stage]]" in res.stdout
    assert listing(work) == ["in.toml"]


def test_plots_may_not_replace_the_input_or_the_output(work):
    os.symlink("in.toml", work / "spectrum.png")  # --plots . would write spectrum.png = the input
    res = run("report", "in.toml", "--quick", "--plots", ".", "-o", "r.md")
    assert_refused(res, "--plots would overwrite", "spectrum.png")
    assert (work / "in.toml").read_bytes() == SEED.read_bytes()
    res = run("report", "in.toml", "--quick", "--plots", ".", "-o", "speeds.png")
    assert res.exit_code == 2, res.stderr  # a .png report: either its suffix or the clash refuses it
    assert not (work / "speeds.png").exists() and not (work / "r.md").exists()


def test_simulate_refused_output_does_not_run(work, monkeypatch):
    import gearcli.simulate as sim

    called = []
    monkeypatch.setattr(sim, "run_simulation", lambda *a, **k: called.append(1))
    res = run("simulate", "in.toml", "-o", "nodir/x.csv")
    assert res.exit_code == 2 and called == []
