"""The manual's shell examples run as a newcomer types them from the repository root: every input file a
``gearcli`` command in a README or docs/ code block reads is in the repository (a placeholder such as
``gearbox.toml`` or ``history.csv`` made the example exit 2), every benchmark a table names is run through
Python (the scripts are not executable), and the measured history the life page shows is classed as its rows
say, counted here by hand."""

from __future__ import annotations

import json
import re
import shlex
from pathlib import Path

from click.testing import CliRunner

ROOT = Path(__file__).resolve().parents[2]
GENERATED = {"cli.md", "api.md", "design-file.md"}  # --help texts and the schema: placeholders by design
PAGES = [ROOT / "README.md"] + sorted(p for p in (ROOT / "docs").glob("*.md") if p.name not in GENERATED)
# options whose value is a file the command writes (or a directory it creates), not one it reads
WRITES = {"-o", "--output", "--plots"}


def _shell_lines(text: str) -> list[str]:
    """The command lines of the page's fenced and indented code blocks (prompt and comment stripped, a
    backslash continuation joined)."""
    text = re.sub(r"\\\n\s*", " ", text)
    lines: list[str] = []
    for block in re.findall(r"```[a-z]*\n(.*?)```", text, re.S):
        lines += block.splitlines()
    lines += re.findall(r"^ {4}(gearcli .*)", text, re.M)
    out = []
    for line in lines:
        line = line.strip().removeprefix("$ ")
        # a command, not a line of output (a benchmark's table) or of the usage synopsis (FILE, [options])
        if line.startswith("gearcli ") and (".toml" in line or " build" in line) and "FILE" not in line:
            out.append(line.split("#", 1)[0].split("|", 1)[0].strip())
    return out


def _inputs(command: str) -> list[str]:
    words = shlex.split(command)
    if words[1] == "init":  # it writes its file
        return []
    return [w for prev, w in zip(words, words[1:], strict=False)
            if prev not in WRITES and re.fullmatch(r"[\w./-]+\.(toml|csv)", w)]


def test_every_file_a_shown_command_reads_is_in_the_repository():
    missing = [(page.name, command, name) for page in PAGES for command in _shell_lines(page.read_text())
               for name in _inputs(command) if not (ROOT / name).is_file()]
    assert not missing, missing
    # the scan sees the examples it guards
    life = _shell_lines((ROOT / "docs" / "life.md").read_text())
    assert any("--series configs/mixer_history.csv" in c for c in life)
    assert any("--table bearings" in c for c in _shell_lines((ROOT / "docs" / "bearings.md").read_text()))


def test_the_readme_tables_benchmark_commands_run_through_python():
    readme = (ROOT / "README.md").read_text()
    commands = re.findall(r"\| `([^`]*benchmarks/[^`]*)` \|", readme)
    assert commands
    for command in commands:
        script = shlex.split(command)[1]
        assert command.startswith("python "), command
        assert (ROOT / script).is_file(), script


def test_the_life_pages_history_is_classed_as_its_rows_say(tmp_path):
    """configs/mixer_history.csv, by hand: each row holds until the next; idle rows (0 rpm) are dropped; 10
    classes of equal width over the loaded torques 300-650 kN·m (35 kN·m each), a class at its largest torque,
    its time summed and its speed time-weighted."""
    from gearcli.cli import cli

    rows = [[float(x) for x in line.split(",")]
            for line in (ROOT / "configs" / "mixer_history.csv").read_text().splitlines()[1:]]
    held: dict[int, list[tuple[float, float, float]]] = {}
    loaded = [(t1 - t0, torque, speed) for (t0, torque, speed), (t1, _, _) in zip(rows, rows[1:], strict=False)
              if speed != 0]
    low, high = min(r[1] for r in loaded), max(r[1] for r in loaded)
    width = (high - low) / 10
    for seconds, torque, speed in loaded:
        held.setdefault(min(int((torque - low) / width), 9), []).append((seconds, torque, speed))
    expected = {f"class {k + 1}": (sum(s for s, _, _ in v) / 3600, max(t for _, t, _ in v),
                                   sum(s * n for s, _, n in v) / sum(s for s, _, _ in v))
                for k, v in held.items()}
    assert expected == {"class 1": (240 / 3600, 300000, 600), "class 6": (840 / 3600, 500000, 600),
                        "class 10": (120 / 3600, 650000, 450)}

    out = tmp_path / "life.json"
    res = CliRunner().invoke(cli, ["life", str(ROOT / "configs" / "mixer_duty.toml"), "--series",
                                   str(ROOT / "configs" / "mixer_history.csv"), "--static", "-q", "-o", str(out)])
    assert res.exit_code == 0, res.output
    points = json.loads(out.read_text())["life"]["points"]
    got = {p["name"]: (p["hours"], p["torque_Nm"], p["speed_rpm"]) for p in points}
    assert got.keys() == expected.keys()
    for name, (hours, torque, speed) in expected.items():
        assert abs(got[name][0] - hours) <= 1e-12 * hours
        assert got[name][1] == torque and abs(got[name][2] - speed) <= 1e-12 * speed


def test_every_shown_command_is_one_a_shell_can_run():
    """No prose inside a command line: a note in parentheses after a command (``-o f.csv  (54 points, ...)``) is
    a shell syntax error when the line is pasted; a note is a ``#`` comment."""
    bad = [(page.name, command) for page in PAGES for command in _shell_lines(page.read_text())
           if any(word[:1] in "()" for word in shlex.split(command))]
    assert not bad, bad
