"""A sweep point whose run `simulate` would refuse up front as absurdly expensive (gearcli.config.bounds.check_cost:
a unit mistake, not a scene) is refused the same way before it integrates: a failed row carrying simulate's
message, never the end of the sweep (DESIGN §6: a failed point is a row). Before, the sweep skipped the guard and
ran such a point until its computing budget stopped it.

The choice: per point, not one usage error up front. A point's cost follows its own values (speed, duration,
stiffness, rtol: any varied key may move it), so a sweep may hold refused and feasible points side by side; a
sweep whose every point is refused ends as any sweep of failed points does (exit 1), each row naming the figure
and the duration that would fit."""

from __future__ import annotations

import csv
import io
from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.errors import EXIT_FAILED, EXIT_USAGE

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"
STIFF = ("--set", "contact.stiffness=1e9")  # a 1.34 kHz highest mode: 3000 s of it is ~7.6e8 evaluations


def _rows(path: Path) -> list[dict[str, str]]:
    text = path.read_text()
    return list(csv.DictReader(io.StringIO("".join(ln for ln in text.splitlines(True) if not ln.startswith("#")))))


def _simulate_refusal(duration: str) -> str:
    res = CliRunner().invoke(cli, ["simulate", str(SEED), *STIFF, "--set", f"simulation.duration_s={duration}",
                                   "--format", "json", "-q"])
    assert res.exit_code == EXIT_USAGE, res.output  # simulate's contract: refused before it starts (exit 2)
    return res.stderr.strip().removeprefix("gearcli: ")


def test_a_refused_point_is_a_failed_row_with_simulates_message_and_the_sweep_goes_on(tmp_path):
    out = tmp_path / "sweep.csv"
    res = CliRunner().invoke(cli, ["sweep", str(SEED), *STIFF, "--vary", "simulation.duration_s=0.3,3000",
                                   "--jobs", "1", "-q", "-o", str(out)])
    assert res.exit_code == EXIT_FAILED, res.output  # a sweep with a failed point
    rows = {float(r["simulation.duration_s"]): r for r in _rows(out)}
    assert rows[0.3]["status"] == "ok" and float(rows[0.3]["nfev"]) > 0
    refused = rows[3000.0]
    assert refused["status"] == "failed"
    assert refused["message"] == _simulate_refusal("3000")
    assert refused["nfev"] == ""  # refused before any integration


def test_a_sweep_whose_every_point_is_refused_fails_with_a_row_each(tmp_path):
    out = tmp_path / "sweep.csv"
    res = CliRunner().invoke(cli, ["sweep", str(SEED), *STIFF, "--vary", "simulation.duration_s=2500,3000",
                                   "--jobs", "1", "-q", "-o", str(out)])
    assert res.exit_code == EXIT_FAILED, res.output
    rows = _rows(out)
    assert [r["status"] for r in rows] == ["failed", "failed"]
    for r in rows:
        # the fit is 1977.8 s: advised rounded down (1980 s, the nearest, needs 5.006e8 evaluations and is refused)
        assert "over the limit of 5e+08" in r["message"] and "simulation.duration_s ≤ 1.97e+03" in r["message"]
