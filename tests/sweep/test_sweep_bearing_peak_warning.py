"""A sweep row carries the bearings' ISO 76 static-safety warning at the window's peak, as ``gearcli simulate`` of
the same point does (tr26f: the row's message had only the design's warning at the static load, so a point whose
vibration overloads a bearing's C_0 looked clean in the sweep).

The scene (tests/sweep/data/spur_oscillator_bearings.toml): a speed-driven spur pinion and a free gear
(J = 0.0063 kg m^2, r_bg = 37.5 cos 20 deg mm) on a linear mesh k = 2e5 N/mm with viscous damping zeta = 0.05 and a
5 um first-harmonic transmission error, no contact loss at these speeds: the mesh is one linear degree of freedom
q = delta - e with m_e = J / r_bg^2, and the normal force F_n = k q + c q' about its static value T_L / r_bg swings by
k X sqrt(1 + (2 zeta r)^2), X = e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2) (base excitation, r = mesh frequency / f_n).
The gear sits midway between two ball bearings (X0 = 1, Y0 = 0), so each bearing's P_0 is F_n / 2 and
s_0 = C_0 / P_0 with C_0 = 1.5 kN; the minimum is 1.2.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

SCENE = Path(__file__).resolve().parent / "data" / "spur_oscillator_bearings.toml"
C0, S0_MIN = 1500.0, 1.2


def peak_safety(n_rpm: float) -> float:
    """s_0 at the steady vibration's peak, by hand (module text)."""
    r_bg = 0.0375 * math.cos(math.radians(20.0))
    k, m_e, zeta, e = 2e8, 0.0063 / r_bg**2, 0.05, 5e-6
    f_n = math.sqrt(k / m_e) / (2 * math.pi)
    r = 25 * n_rpm / 60 / f_n
    x = e * r * r / math.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2)
    f_max = 70.5 / r_bg + k * x * math.sqrt(1 + (2 * zeta * r) ** 2)
    return C0 / (f_max / 2)


def test_row_warns_of_the_bearing_overloaded_at_the_window_peak(tmp_path):
    assert C0 / (70.5 / (0.0375 * math.cos(math.radians(20.0))) / 2) > S0_MIN  # the static load: no warning
    assert peak_safety(1500) == pytest.approx(1.136, abs=1e-3)  # the vibration's peak: below 1.2
    out = tmp_path / "sweep.json"
    res = CliRunner().invoke(cli, ["sweep", str(SCENE), "--vary", "input.speed_rpm=1500,1600", "--jobs", "1",
                                   "-o", str(out)])
    assert res.exit_code == 0, res.stderr
    rows = json.loads(out.read_text())["rows"]
    for row in rows:
        found = re.findall(r"bearing (\d): static safety s_0 = C_0/P_0 = ([0-9.]+) at the peak of the simulated "
                           r"window is below the minimum 1\.2", row["message"])
        assert [b for b, _ in found] == ["1", "2"], row["message"]
        for _, s0 in found:
            assert float(s0) == pytest.approx(peak_safety(row["input.speed_rpm"]), abs=5e-3)  # printed to 3 digits
    # the same warning as the one-shot run of the point
    one = CliRunner().invoke(cli, ["simulate", str(SCENE), "--set", "input.speed_rpm=1600", "--format", "json"])
    assert one.exit_code == 0, one.stderr
    said = [w["message"] for w in json.loads(one.stdout)["warnings"] if w["code"] == "bearing_static_safety_low"]
    assert len(said) == 2 and all(w in rows[1]["message"] for w in said)
