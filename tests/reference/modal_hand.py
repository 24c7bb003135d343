"""Hand-made linear models for tests/reference/test_modal_hand_*.py: their own scenes (a helical stage, a
motor-driven two-stage train, a planetary stage) and their mass, stiffness and damping matrices written out with
numpy from the scenes' numbers (the test modules say what each checks)."""

from __future__ import annotations

import json
import math

import numpy as np
import scipy.linalg
from click.testing import CliRunner

from gearcli.cli import cli

MATERIAL = """
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.1e5
poisson_ratio = 0.3
"""


def _run(tmp_path, text: str, *args: str) -> dict:
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    res = CliRunner().invoke(cli, [args[0], str(path), "--format", "json", *args[1:]])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _base_radius_m(teeth: int, m_n: float, alpha_n_deg: float, beta_deg: float) -> float:
    """ISO 21771: r_b = z m_n / (2 cos beta) cos alpha_t, tan alpha_t = tan alpha_n / cos beta (m)."""
    beta = math.radians(beta_deg)
    alpha_t = math.atan(math.tan(math.radians(alpha_n_deg)) / math.cos(beta))
    return teeth * m_n / (2 * math.cos(beta)) * math.cos(alpha_t) / 1000


def _cos_beta_b(alpha_n_deg: float, beta_deg: float) -> float:
    """sin beta_b = sin beta cos alpha_n (ISO 21771)."""
    return math.cos(math.asin(math.sin(math.radians(beta_deg)) * math.cos(math.radians(alpha_n_deg))))


def _add(K: np.ndarray, lever: dict[int, float], k: float) -> None:
    """A spring k on the deflection sum_j lever_j theta_j: K += k l l^T."""
    v = np.zeros(len(K))
    for j, r in lever.items():
        v[j] = r
    K += k * np.outer(v, v)


def _undamped_Hz(J: np.ndarray, K: np.ndarray) -> np.ndarray:
    w2 = scipy.linalg.eig(K, np.diag(J), right=False).real
    return np.sort(np.sqrt(np.clip(w2, 0.0, None))) / (2 * math.pi)


def _damped(J: np.ndarray, K: np.ndarray, C: np.ndarray) -> list[complex]:
    """The oscillatory eigenvalues (Im > 0) of J x'' + C x' + K x = 0, by frequency."""
    n = len(J)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K / J[:, None], -C / J[:, None]]])
    lam = scipy.linalg.eig(A, right=False)
    return sorted((z for z in lam if z.imag > 1e-2 * abs(z) and abs(z) > 1.0), key=lambda z: abs(z))


def _elastic(modes_json: dict, boundary: str) -> list[dict]:
    return [m for m in modes_json["boundaries"][boundary] if not m["rigid"]]


M_N, ALPHA_N, BETA = 3.0, 20.0, 20.0


Z1, Z2, B = 21, 67, 40.0


J_MOTOR, J_P, J_G, J_DRUM = 0.03, 0.002, 0.05, 0.4


K_IN, K_OUT = 5000.0, 40000.0


T_LOAD = 300.0


_STAGE = f"""
[[stage]]
normal_module_mm = {M_N}
normal_pressure_angle_deg = {ALPHA_N}
helix_angle_deg = {BETA}
pinion = {{ teeth = {Z1}, face_width_mm = {B}, hand = "left", material = "steel", inertia_kg_m2 = {J_P} }}
gear   = {{ teeth = {Z2}, face_width_mm = {B}, hand = "right", material = "steel", inertia_kg_m2 = {J_G} }}
"""  # the single helical stage of _single and _lone_gear


def _single(contact: str = "", simulation: str = "duration_s = 0.4") -> str:
    return MATERIAL + _STAGE + f"""
{contact}
[input]
speed_rpm = 1500
ramp_s = 0.1
inertia_kg_m2 = {J_MOTOR}
coupling_stiffness_Nm_rad = {K_IN}
[load]
torque_Nm = {T_LOAD}
ramp_s = 0.1
inertia_kg_m2 = {J_DRUM}
coupling_stiffness_Nm_rad = {K_OUT}
[simulation]
{simulation}
"""


def _single_hand(c_gamma_alpha: float, zeta: float):
    """J, K, C over (motor, shaft 1, shaft 2, drum), free; the mesh's transverse k_t and its viscous c."""
    rp = _base_radius_m(Z1, M_N, ALPHA_N, BETA)
    rg = _base_radius_m(Z2, M_N, ALPHA_N, BETA)
    cbb = _cos_beta_b(ALPHA_N, BETA)
    k_t = c_gamma_alpha * B * 1e6  # N/m along the transverse line of action
    k_n = k_t / cbb**2
    m_e = J_P * J_G / (J_P * rg**2 + J_G * rp**2)
    c = 2 * zeta * math.sqrt(k_n * m_e)  # DESIGN section 6, acting on the transverse q'
    J = np.array([J_MOTOR, J_P, J_G, J_DRUM])
    K, C = np.zeros((4, 4)), np.zeros((4, 4))
    _add(K, {0: 1.0, 1: -1.0}, K_IN)
    _add(K, {1: rp, 2: -rg}, k_t)
    _add(C, {1: rp, 2: -rg}, c)
    _add(K, {2: 1.0, 3: -1.0}, K_OUT)
    return J, K, C, k_n


def _lone_gear(contact: str, simulation: str) -> str:
    """The stage alone: the pinion follows the prescribed speed, the gear (J_G) is the one degree of freedom."""
    return MATERIAL + _STAGE + f"""
{contact}
[input]
speed_rpm = 1500
ramp_s = 0.02
[load]
torque_Nm = {T_LOAD}
ramp_s = 0.02
[simulation]
{simulation}
"""


STAGES = ((2.5, 15.0, 19, 61, 35.0, 0.001, 0.02), (4.0, 10.0, 17, 71, 60.0, 0.004, 0.3))  # m_n, beta, z, z, b, J, J


J_ROTOR, J_FAN, K_M, C_M, K_L, C_L = 0.08, 3.0, 3000.0, 1.5, 60000.0, 20.0


N_IN = 1450.0


RATIO = 61 / 19 * 71 / 17


T_FAN = 150.0 * RATIO  # the fan's torque at its nominal speed: 150 N m at the motor, the table's torque at 1450 rpm


def _two_stage(contact: str = "") -> str:
    (m1, b1, z1, z2, f1, jp1, jg1), (m2, b2, z3, z4, f2, jp2, jg2) = STAGES
    return MATERIAL + f"""
[[stage]]
normal_module_mm = {m1}
normal_pressure_angle_deg = 20
helix_angle_deg = {b1}
pinion = {{ teeth = {z1}, face_width_mm = {f1}, hand = "left", material = "steel", inertia_kg_m2 = {jp1} }}
gear   = {{ teeth = {z2}, face_width_mm = {f1}, hand = "right", material = "steel", inertia_kg_m2 = {jg1} }}
[[stage]]
normal_module_mm = {m2}
normal_pressure_angle_deg = 20
helix_angle_deg = {b2}
pinion = {{ teeth = {z3}, face_width_mm = {f2}, hand = "right", material = "steel", inertia_kg_m2 = {jp2} }}
gear   = {{ teeth = {z4}, face_width_mm = {f2}, hand = "left", material = "steel", inertia_kg_m2 = {jg2} }}
{contact}
[input]
speed_rpm = {N_IN}
drive = "motor"
motor = {{ torque_speed = [[0, 400], [1400, 300], [1500, 0]] }}
inertia_kg_m2 = {J_ROTOR}
coupling_stiffness_Nm_rad = {K_M}
coupling_damping_Nms_rad = {C_M}
[load]
torque_Nm = {T_FAN}
speed_exponent = 2
inertia_kg_m2 = {J_FAN}
coupling_stiffness_Nm_rad = {K_L}
coupling_damping_Nms_rad = {C_L}
[simulation]
duration_s = 1.0
"""


def _two_stage_hand(cgas: list[float], zeta: float):
    """J, K, C over (motor, shaft 1, shaft 2, shaft 3, fan), free. The motor's table falls 300 N m over
    1400 .. 1500 rpm, so -dT/dw = 300 / (100 pi / 30) N m s/rad; the table gives 150 N m at 1450 rpm, which the fan's
    reflected T_FAN (n / 1450)^2 / i takes there: the operating point is 1450 rpm, and the fan adds
    dT_L/dw = 2 T_FAN / w_n at its nominal speed w_n = 1450 rpm / i."""
    (m1, b1, z1, z2, f1, jp1, jg1), (m2, b2, z3, z4, f2, jp2, jg2) = STAGES
    J = np.array([J_ROTOR, jp1, jg1 + jp2, jg2, J_FAN])
    K, C = np.zeros((5, 5)), np.zeros((5, 5))
    _add(K, {0: 1.0, 1: -1.0}, K_M)
    _add(C, {0: 1.0, 1: -1.0}, C_M)
    for (m, beta, zp, zg, b, _, _), cga, (p, g) in zip(STAGES, cgas, ((1, 2), (2, 3)), strict=True):
        rp, rg = _base_radius_m(zp, m, 20.0, beta), _base_radius_m(zg, m, 20.0, beta)
        k_t = cga * b * 1e6
        m_e = J[p] * J[g] / (J[p] * rg**2 + J[g] * rp**2)
        _add(K, {p: rp, g: -rg}, k_t)
        _add(C, {p: rp, g: -rg}, 2 * zeta * math.sqrt(k_t / _cos_beta_b(20.0, beta) ** 2 * m_e))
    _add(K, {3: 1.0, 4: -1.0}, K_L)
    _add(C, {3: 1.0, 4: -1.0}, C_L)
    C[0, 0] += 300.0 / (100 * math.pi / 30)
    C[4, 4] += 2 * T_FAN / (N_IN * math.pi / 30 / RATIO)
    return J, K, C


J_SUN, J_PLANET, M_PLANET, J_CARRIER = 0.01, 0.004, 2.0, 0.3


def _planetary(contact: str = "") -> str:
    return MATERIAL + f"""
[[stage]]
type = "planetary"
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 0
sun    = {{ teeth = 21, face_width_mm = 30, material = "steel", inertia_kg_m2 = {J_SUN} }}
planet = {{ teeth = 27, face_width_mm = 30, material = "steel", count = 3, inertia_kg_m2 = {J_PLANET}, mass_kg = {M_PLANET} }}
ring   = {{ teeth = 75, face_width_mm = 30, material = "steel" }}
carrier = {{ inertia_kg_m2 = {J_CARRIER} }}
fixed = "ring"
input = "carrier"
{contact}
[input]
speed_rpm = 300
ramp_s = 0.1
[load]
torque_Nm = 100
ramp_s = 0.1
[simulation]
duration_s = 0.3
"""


def _planetary_hand(k_sp: float, k_pr: float, zeta: float):
    """J, K, C over (sun, planets 1-3, carrier), torsional only, angles in one absolute sense. In the carrier's frame
    each mesh is a fixed-axis pair: delta_sp = r_bs (th_s - th_c) + r_bp (th_p - th_c) (external),
    delta_pr = r_bp (th_p - th_c) - r_br (0 - th_c) (internal, ring held). The carrier carries N m_p r_c^2,
    r_c = m (z_s + z_p) / 2 = 72 mm. Viscous c = 2 zeta sqrt(k m_e) with the speed-driven carrier infinitely heavy
    (DESIGN section 6): m_e = 1 / (r_bs^2 / J_s + r_bp^2 / J_p) on a sun mesh, J_p / r_bp^2 on a ring mesh."""
    a = math.radians(20.0)
    rbs, rbp, rbr = (z * 3.0 / 2 * math.cos(a) / 1000 for z in (21, 27, 75))
    J = np.array([J_SUN, J_PLANET, J_PLANET, J_PLANET, J_CARRIER + 3 * M_PLANET * 0.072**2])
    K, C = np.zeros((5, 5)), np.zeros((5, 5))
    c_sp = 2 * zeta * math.sqrt(k_sp / (rbs**2 / J_SUN + rbp**2 / J_PLANET))
    c_pr = 2 * zeta * math.sqrt(k_pr * J_PLANET / rbp**2)
    for p in (1, 2, 3):
        for M, (k, c) in ((K, (k_sp, k_pr)), (C, (c_sp, c_pr))):
            _add(M, {0: rbs, p: rbp, 4: -(rbs + rbp)}, k)
            _add(M, {p: rbp, 4: rbr - rbp}, c)
    return J, K, C


def _static_normal_force_N() -> float:
    """F_n0 = T / (r_bg cos beta_b): the load torque on the gear along the normal line of action."""
    return T_LOAD / _base_radius_m(Z2, M_N, ALPHA_N, BETA) / _cos_beta_b(ALPHA_N, BETA)

