"""Issue 11, hostile input through every command: each refused with exit 2 naming the file (or <stdin>),
no traceback, and never a hang (a FIFO without a writer, /dev/zero, a symlink loop), nor minutes of work
(a sweep axis of a billion values)."""

from __future__ import annotations

import gzip
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
SEED_BYTES = SEED.read_bytes()
COMMANDS = {"design": [], "simulate": [], "report": [], "modes": [],
            "sweep": ["--vary", "input.speed_rpm=500,600", "--jobs", "1"]}


def run(command, file, *, input=None):
    return CliRunner().invoke(cli, [command, str(file), *COMMANDS[command]], input=input)


def assert_refused(res, named: str, fragment: str) -> None:
    assert res.exit_code == 2, (res.exit_code, res.output)
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr, res.stderr
    first = [line for line in res.stderr.splitlines() if line.startswith("gearcli: ")][0]
    assert first.startswith(f"gearcli: {named}: ") and fragment in first, first


def _make(tmp_path: Path, kind: str) -> Path:
    p = tmp_path / f"{kind}.toml"
    if kind == "loop":
        os.symlink(tmp_path / "other.toml", p)
        os.symlink(p, tmp_path / "other.toml")
    elif kind == "zero":
        os.symlink("/dev/zero", p)
    elif kind == "dir":
        p.mkdir()
    elif kind == "gzip":
        p.write_bytes(gzip.compress(SEED_BYTES))
    elif kind == "utf16":
        p.write_bytes(SEED_BYTES.decode().encode("utf-16"))
    elif kind == "stages":
        p.write_bytes(SEED_BYTES + b"[[stage]]\n" * 100_000)
    elif kind == "deep":
        p.write_bytes(SEED_BYTES + b"x = " + b"[" * 100_000 + b"]" * 100_000 + b"\n")
    elif kind == "wide_inline":
        p.write_bytes(SEED_BYTES + b"x = {" + b", ".join(b"k%d = 1" % i for i in range(60_000)) + b"}\n")
    elif kind == "array":
        p.write_bytes(b"stage = [" + b"1," * 500_000 + b"]\n")
    elif kind == "over_1mib":
        p.write_bytes(SEED_BYTES + b"#" * (2**20 - len(SEED_BYTES)) + b"\n")
    return p


CASES = [("loop", "symbolic links"), ("zero", "larger than 1 MiB"), ("dir", "is a directory"),
         ("gzip", "gzip"), ("utf16", "UTF-16"), ("stages", "keys and tables"), ("deep", "nested"),
         ("wide_inline", "keys and tables"), ("array", "at most 50 entries"), ("over_1mib", "larger than 1 MiB")]


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize(("kind", "fragment"), CASES, ids=[c[0] for c in CASES])
def test_hostile_files_through_every_command(tmp_path, command, kind, fragment):
    path = _make(tmp_path, kind)
    assert_refused(run(command, path), str(path), fragment)


def test_exactly_1_mib_is_still_read(tmp_path):
    path = tmp_path / "big.toml"
    path.write_bytes(SEED_BYTES + b"#" * (2**20 - len(SEED_BYTES) - 1) + b"\n")
    assert path.stat().st_size == 2**20
    assert run("design", path).exit_code == 0


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize(("data", "fragment"), [(b"\x00\x01\x02binary" * 100, "binary data"),
                                                (gzip.compress(SEED_BYTES), "gzip"),
                                                (b"\xff\xfe" + SEED_BYTES.decode().encode("utf-16-le"), "UTF-16")])
def test_binary_stdin_through_every_command(command, data, fragment):
    assert_refused(run(command, "-", input=data), "<stdin>", fragment)


@pytest.mark.parametrize("command", COMMANDS)
def test_a_fifo_without_a_writer_as_input_does_not_hang(tmp_path, command):
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    res = subprocess.run([sys.executable, "-m", "gearcli", command, str(fifo), *COMMANDS[command]],
                         capture_output=True, text=True, timeout=60, env=env, stdin=subprocess.DEVNULL)
    assert res.returncode == 2 and f"{fifo}: is a FIFO with nothing written to it" in res.stderr, res.stderr


def test_a_fifo_with_a_writer_is_read(tmp_path):
    """Process substitution and `mkfifo` pipelines keep working: a writer is there, the file is read."""
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen([sys.executable, "-m", "gearcli", "design", str(fifo), "--format", "json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, text=True)
    with open(fifo, "wb") as w:  # blocks until gearcli has opened the FIFO for reading
        w.write(SEED_BYTES)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0, err
    assert '"ratio"' in out


@pytest.mark.parametrize("command", ["init", "schema"])
@pytest.mark.parametrize(("kind", "fragment"), [("loop", "symbolic links"), ("dir", "is a directory"),
                                                ("fifo", "is a FIFO"), ("empty", "empty file name")])
def test_init_and_schema_refuse_hostile_destinations(tmp_path, command, kind, fragment):
    if kind == "fifo":
        target = tmp_path / "f.json"
        os.mkfifo(target)
    elif kind == "empty":
        target = ""
    else:
        target = _make(tmp_path, kind).with_suffix(".json") if kind != "loop" else _make(tmp_path, kind)
        if kind == "dir":
            target.mkdir()
    args = ["init", str(target)] if command == "init" else ["schema", "-o", str(target)]
    if command == "schema" and kind == "loop":
        args = ["schema", "-o", str(target)]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 2 and fragment in res.stderr and "Traceback" not in res.stderr, res.stderr


def test_a_billion_point_sweep_axis_is_refused_before_it_is_built():
    res = CliRunner().invoke(cli, ["sweep", str(SEED), "--vary", "input.speed_rpm=1:2:1000000000", "--jobs", "1"])
    assert res.exit_code == 2 and "1000000000 values is more than" in res.stderr, res.stderr


def test_many_set_options_are_one_capped_message():
    args = [a for i in range(20_000) for a in ("--set", f"nope{i}=1")]
    res = CliRunner().invoke(cli, ["design", str(SEED), *args])
    assert res.exit_code == 2 and "Traceback" not in res.stderr
    assert len(res.stderr.splitlines()) <= 25 and "--set" in res.stderr
