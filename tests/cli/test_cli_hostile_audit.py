"""Issue 11, "What was measured": the cases no other file of tests/cli covered, one test each.

The others live in test_cli_files.py (data loss, -o), test_cli_hostile.py (bounds, literal text, tables,
resources), test_cli_interrupt.py (SIGTERM/Ctrl-C), test_cli_files_sweep_modes.py, test_cli_broken_pipe.py,
test_cli_cost_budget.py and test_cli_fuzz_findings.py. Here: the forged line from a `--set` title, long lists
in messages, the JSON Schema against validation through `gearcli schema`, and the repository's own checks
(no file citing a document outside it, ruff and mypy clean, the README's
test command with its venv).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner
from jsonschema_subset import valid

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
SEED_TEXT = SEED.read_text()


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


# ------------------------------------------------------------------------------- text reaching a terminal
@pytest.mark.parametrize("fmt", ["table", "csv", "json"])
def test_a_newline_in_a_set_title_cannot_print_a_gearcli_line(fmt):
    res = run("design", SEED, "--set", 'title="x\ngearcli: wrote /etc/passwd"', "--format", fmt)
    assert res.exit_code == 0, res.stderr
    for line in (res.stdout + res.stderr).splitlines():
        assert not line.startswith("gearcli:"), line  # the newline is escaped, never a line of its own


def test_a_newline_in_a_set_key_cannot_print_a_gearcli_line():
    res = run("design", SEED, "--set", "nope\ngearcli: all fine=1")
    assert res.exit_code == 2
    assert [line for line in res.stderr.splitlines() if line.startswith("gearcli:")] == \
        [res.stderr.splitlines()[0]]  # one message line, and the forged one is not among them


def test_a_20_kb_list_is_never_printed(tmp_path):
    # 3000 materials and a stage naming none of them: the message listed every defined name (~21 KB)
    mats = "".join(f"[materials.m{i:04d}]\ndensity_kg_m3 = 7800\nyoungs_modulus_MPa = 2.07e5\npoisson_ratio = 0.29\n"
                   for i in range(3000))
    path = tmp_path / "mats.toml"
    path.write_text(SEED_TEXT.replace('material = "steel" }', 'material = "nope" }', 1) + mats)
    res = run("design", path)
    assert res.exit_code == 2 and "Traceback" not in res.stderr and "mats.toml" in res.stderr
    assert len(res.stderr) < 2000, len(res.stderr)


# ------------------------------------------------------------------------------- schema against validation
def _schema() -> dict:
    res = run("schema")
    assert res.exit_code == 0
    return json.loads(res.stdout)


SEED_DOC = tomllib.loads(SEED_TEXT)


def _edited(table: str, **keys) -> dict:
    doc = json.loads(json.dumps(SEED_DOC))
    doc[table].update(keys)
    return doc


@pytest.mark.parametrize(("case", "doc"), [
    ("two input speeds", _edited("input", speed_rpm=600)),
    ("no input speed", {**SEED_DOC, "input": {"ramp_s": 0.18}}),
    ("two load torques", _edited("load", torque_Nm=5310)),
    ("two target speeds", _edited("target", output_speed_deg_s=138)),
    ("torque drive without a torque", _edited("input", drive="torque")),
    ("a torque with a speed drive", _edited("input", torque_Nm=100)),
    ("a coupling without an inertia", _edited("load", coupling_stiffness_Nm_rad=1e6)),
    ("a helical pair of one hand", {**SEED_DOC, "stage": [{**SEED_DOC["stage"][0], "gear": {
        **SEED_DOC["stage"][0]["gear"], "hand": "left"}}, *SEED_DOC["stage"][1:]]}),
    ("a helical pair without hands", {**SEED_DOC, "stage": [{**SEED_DOC["stage"][0], "pinion": {
        k: v for k, v in SEED_DOC["stage"][0]["pinion"].items() if k != "hand"}}, *SEED_DOC["stage"][1:]]}),
])
def test_the_schema_refuses_what_validation_refuses(case, doc, tmp_path):
    import tomli_w

    path = tmp_path / "case.toml"
    path.write_text(tomli_w.dumps(doc))
    assert run("design", path).exit_code == 2, case  # validation (or the design's input checks) refuses it
    schema = _schema()
    assert not valid(doc, schema, schema), f"the schema accepts {case}"
    assert valid(SEED_DOC, schema, schema)  # and still accepts the seed


# ------------------------------------------------------------------------------- the repository checks itself
def _tracked() -> list[str]:
    out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True)
    return out.stdout.split()


def test_no_file_cites_a_design_md_outside_the_repository():
    files = _tracked()
    assert files, "not a git checkout"
    needle = "DESIGN" + ".md"  # spelled apart so this file does not cite it
    offenders = [f for f in files if (ROOT / f).is_file() and f.endswith((".py", ".md", ".toml", ".txt"))
                 and needle in (ROOT / f).read_text(errors="replace")]
    assert offenders == []


def test_ruff_reports_nothing():
    res = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "."], cwd=ROOT, capture_output=True,
                         text=True, timeout=300)
    assert res.returncode == 0, res.stdout[-3000:]


def test_mypy_reports_nothing():
    res = subprocess.run([sys.executable, "-m", "mypy", "--cache-dir", "/dev/null"], cwd=ROOT, capture_output=True,
                         text=True, timeout=600)
    assert res.returncode == 0, res.stdout[-3000:]


def test_readme_test_command_names_the_venv():
    readme = (ROOT / "README.md").read_text()
    assert ".venv/bin/python -m pytest" in readme
    assert ".venv/bin/python -m pytest -q -p no:cacheprovider" in (ROOT / ".ci" / "run").read_text()
