"""A torque-driven spur pair (both wheels free, a fan-law load holding the speed) excited by its transmission error
just below its one elastic mode, against the single-degree-of-freedom base-excitation closed form by hand.

Reduced to its elastic mode the pair is m_e q'' + c q' + k q = F_s - m_e e'' with m_e = J_p J_g / (J_p r_bg^2 +
J_g r_bp^2) (both inertias given: no speed-prescribed side), k the linear mesh stiffness, c = 2 zeta sqrt(k m_e)
(DESIGN §6's law), e = E cos(Omega t): the DTE's steady amplitude is X = E r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2),
r = Omega / omega_n, the line-of-action force's k X sqrt(1 + (2 zeta r)^2), and the tangential force's that times
cos(alpha_t). The clamped-input (speed drive) case is tests/reference/test_excitation_oscillator.py; this one checks
that a free pinion's inertia enters m_e and c as the closed form says, through the command line. The fan load's
dT/domega couples the rigid-body motion weakly: measured 2e-4 off on the std and the DTE rms (tolerance 2e-3) and
1.2e-3 of the dynamic part on K_v, a window max (tolerance 3e-3).
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner

from gearcli.cli import cli

J_P, J_G = 5e-4, 6.3e-3  # kg m^2, both given
K_N = 2e8  # N/m, linear mesh along the line of action
ZETA, E_TE = 0.05, 5e-6  # mesh damping ratio, TE amplitude (m)
T_IN = 200.0  # N m on a 25/25 spur pair, m = 3 mm: r = 37.5 mm
ALPHA = math.radians(20.0)
R_B = 0.0375 * math.cos(ALPHA)
R_TARGET = 0.9  # mesh frequency / natural frequency


def _hand() -> tuple[float, float, float]:
    """(input speed rpm for r = 0.9, steady tangential amplitude N, DTE amplitude m)."""
    m_e = J_P * J_G / (J_P * R_B**2 + J_G * R_B**2)
    f_n = math.sqrt(K_N / m_e) / (2 * math.pi)
    rpm = R_TARGET * f_n / 25 * 60
    r = R_TARGET
    x = E_TE * r**2 / math.sqrt((1 - r**2) ** 2 + (2 * ZETA * r) ** 2)
    return rpm, K_N * x * math.sqrt(1 + (2 * ZETA * r) ** 2) * math.cos(ALPHA), x


def test_free_pinion_te_response_is_the_sdof_closed_form(tmp_path):
    rpm, ft_amp, x = _hand()
    scene = tmp_path / "te_free.toml"
    scene.write_text(f"""title = "TE-excited free spur pair"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = {{ teeth = 25, face_width_mm = 20, hand = "spur", inertia_kg_m2 = {J_P} }}
gear   = {{ teeth = 25, face_width_mm = 20, hand = "spur", inertia_kg_m2 = {J_G} }}
[contact]
stiffness = {K_N / 1e3}
exponent = 1
damping_ratio = {ZETA}
transmission_error_um = [{E_TE * 1e6}]
[input]
drive = "torque"
speed_rpm = {rpm:.4f}
torque_Nm = {T_IN}
ramp_s = 0.02
[load]
torque_Nm = {T_IN}
ramp_s = 0.02
speed_exponent = 2
[simulation]
duration_s = 0.1
steps = 20000
""")
    res = CliRunner().invoke(cli, ["simulate", str(scene), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    st = json.loads(res.output)["summary"]["stages"][0]
    static = T_IN / 0.0375
    assert abs(st["tangential_N"]["mean"] / static - 1) < 2e-3
    assert abs(st["dynamic_factor"] - (1 + ft_amp / static)) < 3e-3 * (ft_amp / static)
    assert abs(st["tangential_N"]["std"] / (ft_amp / math.sqrt(2)) - 1) < 2e-3
    assert abs(st["dte_um"]["rms"] / (x / math.sqrt(2) * 1e6) - 1) < 2e-3
