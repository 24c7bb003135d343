"""Field test (an engineer's own scenes, not configs/): the forced response of one linear spur mesh to a
sinusoidal transmission error and of a free pinion-gear pair to an input torque ripple against the closed-form
1-DOF oscillator, a speed sweep's peak at the hand resonance speed, the Campbell crossings, a coupling in series
with a flexible shaft (k_eq and the coupling's modal damping by hand), the 10 % resonance-warning band, and the
contact-loss and aliasing warnings.

Hand model (one mesh, viscous damping_ratio zeta on q = delta - e, linear K = k):
  m_e q'' + c q' + k q = -m_e e''  (pinion speed prescribed: m_e = J_g / r_bg^2),
  so q = e r^2 / D and the mesh force F = k q + c q' = k e r^2 sqrt(1 + (2 zeta r)^2) / D,
  D = sqrt((1 - r^2)^2 + (2 zeta r)^2), r = f_mesh / f_n, F_t = F cos(alpha) for a spur gear.
(The often-quoted k e / D is the amplitude of k * delta, the total deflection, not of the mesh force: it agrees
at r = 1 only; at r = 0.5 the gear follows the error almost kinematically and the force is r^2 smaller.)
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ALPHA = math.radians(20.0)
K = 2e5  # N/mm
ZETA = 0.05
E_MM = 1e-3  # 1 um
J_G = 0.0063  # kg m^2
R_B_MM = 25 * 3 * math.cos(ALPHA) / 2  # 35.24 mm
M_E = J_G / (R_B_MM * 1e-3) ** 2 * 1e-3  # N s^2/mm (5.073 kg)
F_N = math.sqrt(K / M_E) / (2 * math.pi)  # 999.3 Hz
N_RES = 60 * F_N / 25  # 2398 rpm: 25 n / 60 = f_n

TE_SCENE = """
title = "one linear spur mesh, 1 um transmission error"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = {{ teeth = 25, face_width_mm = 20, hand = "spur" }}
gear   = {{ teeth = 25, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.0063 }}
[contact]
stiffness = 2e5
exponent = 1
damping_ratio = 0.05
transmission_error_um = [1.0]
[input]
speed_rpm = {speed}
ramp_s = 0.02
[load]
torque_Nm = 200
ramp_s = 0.02
[simulation]
duration_s = 0.15
steps = 12000
{steady}
"""

RIPPLE_SCENE = """
title = "free pinion and gear, input torque ripple"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = {{ teeth = 25, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.002 }}
gear   = {{ teeth = 50, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.0063 }}
[contact]
stiffness = 2e5
exponent = 1
damping_ratio = 0.05
[input]
drive = "torque"
torque_Nm = 100
speed_rpm = 1500
ramp_s = 0.02
torque_ripple = [{{ amplitude_percent = 10, order = {order} }}]
[load]
torque_Nm = 200
ramp_s = 0.02
[simulation]
duration_s = 0.15
steps = {steps}
"""

SERIES_SCENE = """
title = "motor coupling in series with a flexible intermediate shaft"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = { teeth = 20, face_width_mm = 30, hand = "spur", inertia_kg_m2 = 1e-4 }
gear   = { teeth = 40, face_width_mm = 30, hand = "spur", inertia_kg_m2 = 1e-4 }
[stage.shaft]
stiffness_Nm_rad = 5e4
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
pinion = { teeth = 20, face_width_mm = 40, hand = "spur", inertia_kg_m2 = 1e-4 }
gear   = { teeth = 60, face_width_mm = 40, hand = "spur", inertia_kg_m2 = 5.0 }
[contact]
stiffness = 1e7
exponent = 1
damping_ratio = 0.05
[input]
speed_rpm = 1500
inertia_kg_m2 = 0.1
coupling_stiffness_Nm_rad = 2e4
coupling_damping_Nms_rad = 2.0
[load]
torque_Nm = 500
[simulation]
duration_s = 0.1
"""


def _write(tmp_path: Path, text: str, name: str = "scene.toml") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def _json(args: list[str]) -> dict:
    result = CliRunner().invoke(cli, [*args, "--format", "json"])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


def _amplitude(stat: dict) -> float:
    return (stat["max"] - stat["min"]) / 2


@pytest.mark.parametrize("r", [0.5, 1.0, 2.0])
def test_te_forced_response_is_the_one_dof_oscillator(tmp_path, r):
    """Whole periods (steady = "periodic") of a linear, backlash-free mesh: the DTE amplitude e r^2 / D and
    the tangential force amplitude k e r^2 sqrt(1 + (2 zeta r)^2) / D cos(alpha), to 1e-3 (the periodic
    window's residual transient and the output sampling)."""
    speed = r * N_RES
    path = _write(tmp_path, TE_SCENE.format(speed=speed, steady='steady = "periodic"'))
    stage = _json(["simulate", path])["summary"]["stages"][0]
    d = math.sqrt((1 - r * r) ** 2 + (2 * ZETA * r) ** 2)
    q_hand_um = E_MM * 1e3 * r * r / d
    f_hand = K * E_MM * r * r * math.sqrt(1 + (2 * ZETA * r) ** 2) / d * math.cos(ALPHA)
    assert _amplitude(stage["dte_um"]) == pytest.approx(q_hand_um, rel=1e-3)
    assert _amplitude(stage["tangential_N"]) == pytest.approx(f_hand, rel=1e-3)
    # the mean is the static load: T / r_bg cos(alpha) = 200 N m / 35.24 mm x cos 20 deg
    assert stage["tangential_N"]["mean"] == pytest.approx(200e3 / R_B_MM * math.cos(ALPHA), rel=1e-6)
    assert stage["contact_loss_fraction"] == 0.0 and stage["back_flank_fraction"] == 0.0


def test_torque_ripple_response_by_hand(tmp_path):
    """Free pinion (J_p) and gear (J_g): m_e delta'' + c delta' + k delta = m_e r_bp T(t) / J_p + const,
    m_e = J_p J_g / (J_p r_bg^2 + J_g r_bp^2); a 10 % ripple of 100 N m at order 53.44 (1336 Hz at 1500 rpm,
    r = 0.5 of f_n = 2672 Hz) gives F = m_e r_bp T_r / J_p sqrt(1 + (2 zeta r)^2) / D, F_t = F cos(alpha)."""
    j_p, j_g, r_p, r_g = 0.002, 0.0063, R_B_MM * 1e-3, 2 * R_B_MM * 1e-3
    m_e = j_p * j_g / (j_p * r_g**2 + j_g * r_p**2)  # kg
    f_n = math.sqrt(K * 1e3 / m_e) / (2 * math.pi)
    order = 0.5 * f_n / 25.0  # r = 0.5 at 1500 rpm (25 rev/s)
    data = _json(["simulate", _write(tmp_path, RIPPLE_SCENE.format(order=order, steps=12000))])
    summary = data["summary"]
    assert summary["natural_frequencies_Hz"] == [pytest.approx(f_n, rel=1e-9)]
    r = order * summary["input_speed_rpm"] / 60 / f_n  # the run's mean speed (the ripple follows rotation)
    d = math.sqrt((1 - r * r) ** 2 + (2 * ZETA * r) ** 2)
    f_hand = m_e * r_p * 10.0 / j_p * math.sqrt(1 + (2 * ZETA * r) ** 2) / d * math.cos(ALPHA)
    # 2e-3: the window is not whole periods and the speed itself fluctuates with the ripple
    assert _amplitude(summary["stages"][0]["tangential_N"]) == pytest.approx(f_hand, rel=2e-3)


def test_ripple_resonance_crossing_participation_and_warning(tmp_path):
    """The free mode's shape by momentum (J_p + J_g (1/2) phi_g = 0 against the rigid mode (1, 1/2)):
    phi_g = -J_p / (J_g / 2); the pinion's kinetic-energy share J_p / (J_p + J_g phi_g^2) and the gain
    share / (2 zeta); the ripple order's crossing at 60 f_n / order rpm; a warning at resonance only."""
    j_p, j_g = 0.002, 0.0063
    phi_g = -j_p / (j_g * 0.5)
    share = j_p / (j_p + j_g * phi_g**2)
    r_p, r_g = R_B_MM * 1e-3, 2 * R_B_MM * 1e-3
    f_n = math.sqrt(K * 1e3 / (j_p * j_g / (j_p * r_g**2 + j_g * r_p**2))) / (2 * math.pi)
    order = f_n / 25.0  # the ripple at f_n at 1500 rpm
    data = _json(["modes", _write(tmp_path, RIPPLE_SCENE.format(order=order, steps=12000))])
    (rigid, mode) = data["boundaries"]["free"]
    assert rigid["frequency_Hz"] == 0.0
    assert mode["frequency_Hz"] == pytest.approx(f_n, rel=1e-9)
    assert mode["damping_ratio"] == pytest.approx(ZETA, rel=1e-9)  # c = 2 zeta sqrt(k m_e), both sides free
    assert mode["shape"]["shaft 2"] == pytest.approx(phi_g, rel=1e-9)
    (ripple,) = [c for c in mode["crossings"] if c["source"] == "input_torque_ripple"]
    assert ripple["input_speed_rpm"] == pytest.approx(60 * f_n / order, rel=1e-9)
    assert ripple["participation"] == pytest.approx(share, rel=1e-9)
    assert ripple["amplification"] == pytest.approx(share / (2 * ZETA), rel=1e-9)
    (warning,) = [w for w in data["warnings"] if w["code"] == "resonance"]
    assert warning["source"] == "input_torque_ripple" and warning["boundary"] == "free"
    off = _json(["modes", _write(tmp_path, RIPPLE_SCENE.format(order=order / 2, steps=12000), "off.toml")])
    assert [w for w in off["warnings"] if w["code"] == "resonance"] == []


def test_campbell_crossings_and_damping_of_the_te_scene(tmp_path):
    """Clamped input: one mode at f_n = sqrt(k / m_e) / 2 pi with the file's zeta; mesh order h crosses it at
    60 f_n / (25 h) rpm, the mesh holding all the strain energy (gain 1 / (2 zeta) = 10)."""
    data = _json(["modes", _write(tmp_path, TE_SCENE.format(speed=N_RES, steady=""))])
    (mode,) = data["boundaries"]["clamped_input"]
    assert mode["frequency_Hz"] == pytest.approx(F_N, rel=1e-9)
    assert mode["damping_ratio"] == pytest.approx(ZETA, rel=1e-9)
    crossings = {c["order"]: c for c in mode["crossings"] if c["source"] == "mesh"}
    assert sorted(crossings) == [1, 2, 3]
    for h, c in crossings.items():
        assert c["input_speed_rpm"] == pytest.approx(60 * F_N / (25 * h), rel=1e-9)
        assert c["amplification"] == pytest.approx(1 / (2 * ZETA), rel=1e-9)


@pytest.mark.parametrize(("r", "warned"), [(0.895, False), (0.905, True), (1.095, True), (1.105, False)])
def test_resonance_warning_band_is_ten_percent(tmp_path, r, warned):
    """The mesh 1x order at r f_n: warned within 10 % of the mode, not outside (2x and 3x lie far away)."""
    path = _write(tmp_path, TE_SCENE.format(speed=r * N_RES, steady=""))
    data = _json(["design", path])
    resonance = [w for w in data["warnings"] if w["code"] == "resonance"]
    assert bool(resonance) is warned
    if warned:
        assert resonance[0]["excitation"] == "stage 1 mesh 1x"


def test_speed_sweep_peaks_at_the_hand_resonance_speed(tmp_path):
    """Sweep 2200 ... 2600 rpm in 50 rpm steps: the DTE rms peaks at the point nearest n = 60 f_n / 25
    (2398 rpm) and every point's rms is e r^2 / D / sqrt 2 (2e-3: a fixed window, not whole periods)."""
    path = _write(tmp_path, TE_SCENE.format(speed=N_RES, steady=""))
    out = tmp_path / "sweep.csv"
    result = CliRunner().invoke(
        cli, ["sweep", path, "--vary", "input.speed_rpm=2200:2600:9", "--jobs", "1", "-o", str(out)]
    )
    assert result.exit_code == 0, result.output
    rows = list(csv.DictReader(line for line in out.read_text().splitlines() if not line.startswith("#")))
    speeds = [float(row["input.speed_rpm"]) for row in rows]
    rms = [float(row["stage1_dte_um_rms"]) for row in rows]
    assert speeds[rms.index(max(rms))] == min(speeds, key=lambda n: abs(n - N_RES))
    for n, value in zip(speeds, rms, strict=True):
        r = n / N_RES
        d = math.sqrt((1 - r * r) ** 2 + (2 * ZETA * r) ** 2)
        assert value == pytest.approx(E_MM * 1e3 * r * r / d / math.sqrt(2), rel=2e-3)


def test_coupling_in_series_with_a_shaft_by_hand(tmp_path):
    """Motor held (speed drive), a 2e4 N m/rad coupling, two stiff meshes (k_n r_b^2) and a 5e4 N m/rad shaft
    in series (intermediate inertias 1e-4 kg m^2, negligible) against a 5 kg m^2 output gear: referred to the
    output, 1/k_eq = 1/(k_c i^2) + 1/(k_m1 r_bg1^2 i_2^2) + 1/(k_s i_2^2) + 1/(k_m2 r_bg2^2), i = 2 x 3;
    f = sqrt(k_eq / J) / 2 pi. The coupling's damping adds zeta = share_c c_c omega / (2 k_c) to the mode."""
    r_b = lambda z, m: z * m * math.cos(ALPHA) / 2e3  # noqa: E731 (m)
    k_c, k_s, c_c = 2e4, 5e4, 2.0
    k_m1, k_m2 = 1e10 * r_b(40, 3) ** 2, 1e10 * r_b(60, 4) ** 2  # 1e7 N/mm = 1e10 N/m, on the gears
    k_eq = 1 / (1 / (k_c * 36) + 1 / (k_m1 * 9) + 1 / (k_s * 9) + 1 / k_m2)
    f_hand = math.sqrt(k_eq / 5.0) / (2 * math.pi)  # 37.40 Hz
    data = _json(["modes", _write(tmp_path, SERIES_SCENE)])
    first = data["boundaries"]["clamped_input"][0]
    # 2e-4: the 1e-4 kg m^2 intermediate bodies lower it by a few 1e-5 (Rayleigh)
    assert first["frequency_Hz"] == pytest.approx(f_hand, rel=2e-4)
    # series springs carry one torque: strain-energy shares are in the ratio of the compliances
    compliance = {"input coupling": 1 / (k_c * 36), "shaft 2": 1 / (k_s * 9)}
    total = 1 / k_eq
    for name, value in compliance.items():
        assert first["energy_share"][name] == pytest.approx(value / total, rel=1e-3)
    omega = 2 * math.pi * first["frequency_Hz"]
    zeta_hand = first["energy_share"]["input coupling"] * c_c * omega / (2 * k_c)
    # the stiff meshes' own zeta = 0.05 acts at omega / omega_mesh ~ 1e-2 on a 1e-3 share: below 1e-3 of it
    assert first["damping_ratio"] == pytest.approx(zeta_hand, rel=2e-3)


def test_contact_loss_warned_when_te_response_exceeds_static_deflection(tmp_path):
    """At resonance a 5 um error drives q to e / (2 zeta) = 50 um about the static 28.4 um (F / k): the loaded
    flank lets go for part of every period, and the run says so (contact_loss)."""
    path = _write(tmp_path, TE_SCENE.format(speed=N_RES, steady='steady = "periodic"'))
    data = _json(["simulate", path, "--set", "contact.transmission_error_um=[5.0]"])
    assert "contact_loss" in [w["code"] for w in data["warnings"]]
    stage = data["summary"]["stages"][0]
    # linear both flanks (no backlash): still the linear response, q_static - 50 um < 0 part of the time
    assert _amplitude(stage["dte_um"]) == pytest.approx(5.0 / (2 * ZETA), rel=2e-3)
    fraction = stage["back_flank_fraction"] + stage["contact_loss_fraction"]
    q0 = 200e3 / R_B_MM / K * 1e3  # um
    assert fraction == pytest.approx(math.acos(q0 / 50.0) / math.pi, abs=0.02)


def test_ripple_above_the_output_sampling_is_warned(tmp_path):
    """300 samples over 0.15 s (2 kHz) and a 1336 Hz ripple: aliased in the samples, warned."""
    j_p, j_g, r_p, r_g = 0.002, 0.0063, R_B_MM * 1e-3, 2 * R_B_MM * 1e-3
    f_n = math.sqrt(K * 1e3 / (j_p * j_g / (j_p * r_g**2 + j_g * r_p**2))) / (2 * math.pi)
    data = _json(["simulate", _write(tmp_path, RIPPLE_SCENE.format(order=0.5 * f_n / 25, steps=300))])
    (warning,) = [w for w in data["warnings"] if w["code"] == "excitation_undersampled"]
    assert "ripple" in warning["message"]


@pytest.mark.parametrize(
    "setting",
    [
        "input.torque_ripple=[{amplitude_percent=5,order=0}]",
        "input.torque_ripple=[{amplitude_percent=-5,order=2}]",
        "load.fluctuation=[{amplitude_percent=5,frequency_Hz=0}]",
        "load.fluctuation=[{amplitude_percent=-5,frequency_Hz=10}]",
    ],
)
def test_order_zero_and_negative_amplitudes_are_refused(tmp_path, setting):
    path = _write(tmp_path, RIPPLE_SCENE.format(order=10, steps=1000))
    result = CliRunner().invoke(cli, ["simulate", path, "--set", setting, "--format", "json"])
    assert result.exit_code == 2
    assert "Traceback" not in result.output and (
        "order" in result.output or "amplitude" in result.output or "frequency" in result.output
    )


def test_modes_table_writes_whole_numbers_out(tmp_path):
    """The TE scene's mesh holds all of its mode's strain energy: the table says (100 %, 10), not
    (1e+02 %, 10); a °/s file's 1x crossing at 60 f_n / 25 rpm x 6 = 14389 °/s is 14389, not 1.439e+04."""
    text = TE_SCENE.format(speed=N_RES, steady="").replace(f"speed_rpm = {N_RES}", f"speed_deg_s = {6 * N_RES}")
    result = CliRunner().invoke(cli, ["modes", _write(tmp_path, text), "--format", "table"])
    assert result.exit_code == 0, result.output
    assert "e+0" not in result.stdout
    assert "(100 %, 10)" in result.stdout
    assert f"stage 1 mesh 1x @ {6 * N_RES:.0f} " in result.stdout


@pytest.mark.parametrize(
    ("x", "digits", "text"),
    [
        (100.0, 2, "100"),
        (14389.46, 4, "14389"),
        (99.4, 2, "99"),
        (0.0031, 2, "0.0031"),
        (4.9e-6, 2, "4.9e-06"),
        (9.96, 2, "10"),
        (0.0, 2, "0"),
        (1.5e9, 4, "1.5e+09"),
    ],
)
def test_figure_keeps_significant_digits_without_exponents_for_whole_numbers(x, digits, text):
    from gearcli.io.modes_out import figure

    assert figure(x, digits) == text


MOTOR_SCENE = """
title = "motor on a coupling, second-order torque ripple"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = { teeth = 25, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.01 }
gear   = { teeth = 50, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.16 }
[contact]
stiffness = 1e8
exponent = 1
damping_ratio = 0.05
[input]
drive = "torque"
torque_Nm = 100
speed_rpm = 1500
inertia_kg_m2 = 0.05
coupling_stiffness_Nm_rad = 1e4
coupling_damping_Nms_rad = 1.0
torque_ripple = [{amplitude_percent = 10, order = 2}]
[load]
torque_Nm = 200
[simulation]
duration_s = 1.0
steps = 40000
"""


def test_motor_coupling_ripple_by_hand(tmp_path):
    """Motor J_m = 0.05 on a 1e4 N m/rad, 1 N m s/rad coupling to a stiff reducer of J_r = 0.01 + 0.16 / 2^2
    = 0.05 kg m^2 (input side): the free mode at sqrt(k (J_m + J_r) / (J_m J_r)) / 2 pi = 100.66 Hz with
    zeta = c / (2 sqrt(k mu)), mu = J_m J_r / (J_m + J_r); the 10 N m ripple at 2 per revolution (50 Hz,
    r = 0.497) gives a coupling torque of mu T_r / J_m sqrt(1 + (2 zeta r)^2) / D (the last 0.1 s, after
    ~15 decay times)."""
    j_m, j_r, k, c = 0.05, 0.01 + 0.16 / 4, 1e4, 1.0
    mu = j_m * j_r / (j_m + j_r)
    omega_n, zeta = math.sqrt(k / mu), c / (2 * math.sqrt(k * mu))
    path = _write(tmp_path, MOTOR_SCENE)
    modes = _json(["modes", path])
    free = modes["boundaries"]["free"][1]
    # 1e-4: the 1e8 N/mm mesh's compliance in series (its own mode at 19.8 kHz)
    assert free["frequency_Hz"] == pytest.approx(omega_n / (2 * math.pi), rel=1e-4)
    assert free["damping_ratio"] == pytest.approx(zeta, rel=1e-3)
    result = CliRunner().invoke(cli, ["simulate", path, "--format", "csv", "-q"])
    assert result.exit_code == 0, result.output
    rows = list(csv.DictReader(line for line in result.stdout.splitlines() if not line.startswith("#")))
    late = [row for row in rows if float(row["time_s"]) > 0.9]
    torque = [float(row["input_coupling_torque_Nm"]) for row in late]
    n = sum(float(row["motor_speed_rpm"]) for row in late) / len(late)
    r = 2 * n / 60 * 2 * math.pi / omega_n
    d = math.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2)
    hand = mu * 10.0 / j_m * math.sqrt(1 + (2 * zeta * r) ** 2) / d
    assert (max(torque) - min(torque)) / 2 == pytest.approx(hand, rel=1e-3)
    assert sum(torque) / len(torque) == pytest.approx(100.0, rel=1e-3)


def _parametric(tmp_path, s: float, fmt: str):
    """The TE scene at r = 2 (mesh frequency 2 f_n) with a first stiffness harmonic s and no error."""
    path = _write(tmp_path, TE_SCENE.format(speed=2 * N_RES, steady=""), f"parametric_{s}.toml")
    args = [
        "simulate",
        path,
        "--set",
        "contact.transmission_error_um=[0.0]",
        "--set",
        f"contact.stiffness_harmonics=[{s}]",
    ]
    result = CliRunner().invoke(cli, [*args, "--format", fmt])
    assert result.exit_code == 0, result.output
    return result.stdout


def test_parametric_instability_is_not_taken_for_a_steady_state(tmp_path):
    """K (1 - s cos 2 omega_n t) on a linear mesh: the damped Mathieu equation's principal instability
    (q'' + 2 zeta omega_n q' + omega_n^2 (1 - s cos 2 omega_n t) q = 0) grows as exp(sigma t) with
    sigma = (s / 4 - zeta) omega_n, unstable for s > 4 zeta = 0.2 (first order in s). At s = 0.4 the window's
    F_t grew 1e12x and the run called it settled (steady.settled true, no warning), its mean 9e18 N taken for
    the steady load; now the window is unsettled, the warning naming the growth. Below the threshold (s = 0.1)
    the response is bounded and settled."""
    rows = list(
        csv.DictReader(line for line in _parametric(tmp_path, 0.4, "csv").splitlines() if not line.startswith("#"))
    )
    t = [float(row["time_s"]) for row in rows]
    q = [float(row["stage1_dte_um"]) for row in rows]

    def ptp(a: float, b: float) -> float:
        part = [x for tt, x in zip(t, q, strict=True) if a <= tt < b]
        return max(part) - min(part)

    sigma = math.log(ptp(0.13, 0.14) / ptp(0.06, 0.07)) / 0.07
    # 2 %: the first-order Mathieu rate (the s^2 detuning) and a 10 ms envelope of 10 cycles
    assert sigma == pytest.approx((0.4 / 4 - ZETA) * 2 * math.pi * F_N, rel=0.02)
    data = json.loads(_parametric(tmp_path, 0.4, "json"))
    assert data["summary"]["steady"]["settled"] is False
    (warning,) = [w for w in data["warnings"] if w["code"] == "window_not_settled"]
    assert "grows through the window" in warning["message"] and warning["stage"] == 1
    bounded = json.loads(_parametric(tmp_path, 0.1, "json"))
    assert bounded["summary"]["steady"]["settled"] is True
    assert "window_not_settled" not in [w["code"] for w in bounded["warnings"]]
