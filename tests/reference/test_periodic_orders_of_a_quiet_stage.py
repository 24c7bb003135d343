"""`report`'s mesh-order amplitudes over a periodic steady state's whole periods, on a stage with no excitation of its
own (trial tr28b).

A two-stage helical reducer (20/73 and 19/67 teeth, linear meshes 4e5 N/mm, damping_ratio 0.05) with a 4 + 1 µm
transmission error on stage 1 only, at 1470 rpm: the periodic orbit's period is stage 1's mesh period (1/490 s), and
stage 2's mesh frequency, 127.53 Hz, is no harmonic of it. The linear response holds lines at 490 Hz and 980 Hz
only; the report listed stage 2's 1x, 2x, 3x (127.5, 255, 382.6 Hz) at 525, 1223 and 1912 N, "exact for each order",
the discrete Fourier coefficient of a one-period window at a frequency between its bins (leakage of the 490 Hz line).
The reference: the steady harmonic response of the same linear model written here from docs/physics.md ("Torsional model")
(mesh forces F_bt = cos²β_b K q + c q̇ on the dynamic transmission error, c = 2 ζ √(K m_e)), solved per harmonic.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.io.report_sections import peak_text
from gearcli.report.spectrum import order_amplitude

SCENE = """title = "quiet stage 2 behind an excited stage 1"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 15
pinion = { teeth = 20, face_width_mm = 40, hand = "left", inertia_kg_m2 = 0.002 }
gear = { teeth = 73, face_width_mm = 38, hand = "right", inertia_kg_m2 = 0.15 }
mesh = { transmission_error_um = [4.0, 1.0], transmission_error_phase_deg = [0, 30] }
[[stage]]
normal_module_mm = 5
normal_pressure_angle_deg = 20
helix_angle_deg = 12
pinion = { teeth = 19, face_width_mm = 70, hand = "right", inertia_kg_m2 = 0.01 }
gear = { teeth = 67, face_width_mm = 65, hand = "left", inertia_kg_m2 = 1.2 }
[contact]
stiffness = 4.0e5
exponent = 1.0
damping_ratio = 0.05
[input]
speed_rpm = 1470
ramp_s = 0.1
[load]
torque_Nm = 900
ramp_s = 0.1
[simulation]
duration_s = 0.4
steps = 4000
steady = "periodic"
"""


def _mesh(mn: float, beta_deg: float, z1: int, z2: int) -> tuple[float, float, float, float]:
    """(r_b1, r_b2 in m, cos beta_b, cos alpha_t) of an x = 0 pair (ISO 21771)."""
    b = math.radians(beta_deg)
    at = math.atan(math.tan(math.radians(20)) / math.cos(b))
    mt = mn / math.cos(b)
    return z1 * mt / 2e3 * math.cos(at), z2 * mt / 2e3 * math.cos(at), math.cos(math.atan(math.tan(b) * math.cos(at))), \
        math.cos(at)


def _harmonic_forces() -> dict[tuple[int, float], float]:
    """{(stage, frequency): F_t amplitude} of the steady response to the TE, per harmonic, by hand."""
    r1, r2, c1b, ca1 = _mesh(3, 15, 20, 73)
    r3, r4, c2b, ca2 = _mesh(5, 12, 19, 67)
    J2, J3, K, zeta = 0.15 + 0.01, 1.2, 4.0e8, 0.05
    c1 = 2 * zeta * math.sqrt(K * J2 / r2**2)  # the speed-driven pinion counts as infinitely heavy
    c2 = 2 * zeta * math.sqrt(K * 1 / (r3**2 / J2 + r4**2 / J3))
    out = {}
    for j, e in ((1, 4e-6 * np.exp(0j)), (2, 1e-6 * np.exp(1j * math.radians(30)))):
        w = 2 * math.pi * 490.0 * j
        z1, z2 = c1b**2 * K + 1j * w * c1, c2b**2 * K + 1j * w * c2  # F_bt = z q on each mesh
        # J2 th2'' = r2 F1 - r3 F2, J3 th3'' = r4 F2 with q1 = -r2 th2 - e (the input turns uniformly), q2 = r3 th2 - r4 th3
        A = np.array([[-w**2 * J2 + r2**2 * z1 + r3**2 * z2, -r3 * r4 * z2], [-r4 * r3 * z2, -w**2 * J3 + r4**2 * z2]])
        th2, th3 = np.linalg.solve(A, np.array([-r2 * z1 * e, 0.0]))
        out[(1, 490.0 * j)] = abs(z1 * (-r2 * th2 - e)) * ca1
        out[(2, 490.0 * j)] = abs(z2 * (r3 * th2 - r4 * th3)) * ca2
    return out


def test_a_whole_periods_window_has_no_line_between_its_harmonics():
    # closed form: one period of a 490 Hz cosine, 4000 samples: its 1x is 100, and 127.53 Hz is no line of it
    t = np.arange(4000) / 4000 / 490.0
    x = 2000.0 + 100.0 * np.cos(2 * np.pi * 490.0 * t + 0.3)
    assert abs(order_amplitude(t, x, 490.0, whole_periods=True) - 100.0) < 1e-9
    assert order_amplitude(t, x, 490.0 * 19 / 73, whole_periods=True) == 0.0  # was 19.2 N, the 490 Hz line's leakage


def test_report_orders_of_a_quiet_stage_behind_an_excited_one(tmp_path: Path):
    path = tmp_path / "quiet.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["report", str(path), "--quick", "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["simulation"]["summary"]["steady"]["converged"]
    hand = _harmonic_forces()
    assert math.isclose(hand[(1, 490.0)], 757.76, rel_tol=1e-3) and math.isclose(hand[(2, 490.0)], 2250.37, rel_tol=1e-3)
    s1, s2 = (st["spectrum"] for st in doc["dynamics"])
    orders1 = {o["order"]: o["tangential_N"] for o in s1["mesh_orders"]}
    # stage 1's orders are its own lines: 1x and 2x as by hand (the orbit's residual ~1e-4), 3x none (linear)
    assert abs(orders1[1] / hand[(1, 490.0)] - 1) < 1e-3 and abs(orders1[2] / hand[(1, 980.0)] - 1) < 1e-3
    assert orders1[3] < 1e-3 * hand[(1, 980.0)]
    # stage 2's mesh orders (127.5, 255, 382.6 Hz) are no lines of the response: by hand its force holds 490 Hz
    # (2250 N) and 980 Hz only; the report said 525, 1223, 1912 N
    for o in s2["mesh_orders"]:
        assert o["tangential_N"] < 1e-3 * hand[(2, 490.0)], o
    assert abs(s2["peak_amplitude_N"] / hand[(2, 490.0)] - 1) < 1e-3 and abs(s2["peak_frequency_Hz"] - 490.0) < 1e-6


def test_a_whole_periods_peak_is_printed_as_the_harmonic_it_is(tmp_path: Path):
    # by hand: stage 1's dominant line is its 2x mesh order, 2 x 20 teeth x 1470 rpm / 60 = 980 Hz, a harmonic of the
    # 1/490 s orbit; the one-period window's bin is 490 Hz wide and the report printed "980 ± 4.9e+02"
    assert peak_text(980.0000000000003, 490.0, whole_periods=True) == "980"
    assert peak_text(978.76, 4.1649) == "978.8 ± 4.2"  # a fixed window's bin centre keeps its resolution
    path = tmp_path / "quiet.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["report", str(path), "--quick", "--format", "markdown", "-q"])
    assert res.exit_code == 0, res.output
    section = res.stdout.split("## Dominant frequency of each mesh force", 1)[1].split("\n## ", 1)[0]
    rows = {r.split("|")[1].strip(): r.split("|")[2].strip() for r in section.splitlines() if r.startswith("| 1 ")
            or r.startswith("| 2 ")}
    assert rows == {"1": f"{2 * 20 * 1470 / 60:g}", "2": f"{20 * 1470 / 60:g}"}, rows  # stage 2: stage 1's 490 Hz
