"""A name that holds a line break (a duty point's ``name = "charging\\nline2"``) stays inside its warning's one
stderr line, written as ``\\n`` as every control character of a name is (docs/output.md, "Text fields"), so stderr
lists the warnings the JSON lists, one ``warning:`` line each (trial tr30a, 2026-12-01). ``warn`` split each message
at its line breaks: configs/mixer_duty.toml's three per-point warnings of such a point printed six lines, three of
them starting ``warning: line2: stage 1: ...`` as if they were warnings of their own (9 warnings, 12 lines)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_a_duty_point_name_with_a_newline_keeps_each_warning_on_one_line(tmp_path):
    text = (ROOT / "configs" / "mixer_duty.toml").read_text()
    assert 'name = "charging"' in text
    scene = tmp_path / "duty.toml"
    scene.write_text(text.replace('name = "charging"', 'name = "charging\\nline2"'))
    res = subprocess.run([sys.executable, "-m", "gearcli", "life", str(scene), "--static", "--format", "json"],
                         capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert res.returncode == 0, res.stderr
    warnings = json.loads(res.stdout)["warnings"]
    of_point = [w for w in warnings if w.get("point") == "charging\nline2"]
    assert of_point  # the scene's hertz law warns per duty point (stiffness_not_iso): three for this point
    lines = res.stderr.splitlines()
    assert all(line.startswith("warning: ") for line in lines), lines
    assert len(lines) == len(warnings)
    for w in of_point:  # the message as JSON has it, its line break written as the two characters \n
        assert "warning: " + w["message"].replace("\n", "\\n") in lines
