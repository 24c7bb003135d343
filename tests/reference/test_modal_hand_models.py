"""`gearcli modes` and `simulate` on scenes of this file against linear models assembled here by hand.

Round 5's premise: modes reported 49 % off with the default mesh law and damping 0.2-110 % off. Every scene here
is this file's own (not configs/); the hand models write the mass, stiffness and damping matrices out with numpy
from the scene's numbers (inertias, couplings, base radii from ISO 21771 written out below) and solve them with
scipy.linalg.eig. The one number taken from gearcli is ISO 6336-1's c_gamma_alpha (design JSON
``iso6336_mesh_stiffness_N_mm_um``), which the ISO tests check; the hand model turns it into the mesh's normal
stiffness k_n = c_gamma_alpha b / cos^2 beta_b (DESIGN section 13) and its transverse tangent k_t = c_gamma_alpha b.

Damping: DESIGN section 6 sizes a viscous mesh c = 2 zeta sqrt(k_lin m_e) with k_lin the normal tangent k_n and
m_e = J_p J_g / (J_p r_bg^2 + J_g r_bp^2); the force c q' acts along the transverse line of action on the
transverse DTE q (gearcli/model/elements/mesh.py). A lone mesh's modal damping ratio is then
c / (2 sqrt(k_t m_e)) = zeta / cos beta_b (docs/physics.md), checked here in closed form.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import scipy.linalg
from click.testing import CliRunner
from numpy.testing import assert_allclose

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


# --- a single helical stage, motor and drum on couplings, speed drive -------------------------------------------

M_N, ALPHA_N, BETA = 3.0, 20.0, 20.0
Z1, Z2, B = 21, 67, 40.0
J_MOTOR, J_P, J_G, J_DRUM = 0.03, 0.002, 0.05, 0.4
K_IN, K_OUT = 5000.0, 40000.0
T_LOAD = 300.0


def _single(contact: str = "", simulation: str = "duration_s = 0.4") -> str:
    return MATERIAL + f"""
[[stage]]
normal_module_mm = {M_N}
normal_pressure_angle_deg = {ALPHA_N}
helix_angle_deg = {BETA}
pinion = {{ teeth = {Z1}, face_width_mm = {B}, hand = "left", material = "steel", inertia_kg_m2 = {J_P} }}
gear   = {{ teeth = {Z2}, face_width_mm = {B}, hand = "right", material = "steel", inertia_kg_m2 = {J_G} }}
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


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.0])
def test_single_stage_modes_against_the_hand_model(tmp_path, exponent):
    """Frequencies of both boundaries and the mesh's tangent for e = 1, 1.5 (default), 2: the tangent is k_n."""
    contact = "" if exponent == 1.5 else f"[contact]\nexponent = {exponent}\n"
    text = _single(contact)
    design = _run(tmp_path, text, "design")
    cga = design["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    J, K, C, k_n = _single_hand(cga, 0.05)
    out = _run(tmp_path, text, "modes")
    ms = out["meshes"][0]["mesh_stiffness"]
    assert ms["law"] == "iso6336" and ms["exponent"] == exponent
    assert_allclose(ms["iso_N_mm"], k_n / 1000, rtol=1e-9)  # c_gamma_alpha b / cos^2 beta_b
    assert_allclose(ms["linearised_N_mm"], k_n / 1000, rtol=1e-9)  # the tangent stays k_n for every e
    # K = k_n^e / (e^e F_n0^(e-1)), F_n0 = T / (r_bg cos beta_b)
    F_n0 = T_LOAD / _base_radius_m(Z2, M_N, ALPHA_N, BETA) / _cos_beta_b(ALPHA_N, BETA)
    K_law = (k_n / 1000) ** exponent / (exponent**exponent * F_n0 ** (exponent - 1))
    assert_allclose(ms["K"], K_law, rtol=1e-9)
    assert not any(w["code"] == "stiffness_not_iso" for w in out["warnings"])
    # free: (motor, shaft 1, shaft 2, drum); clamped_input: the motor held (it follows the prescribed speed)
    hand_free = _undamped_Hz(J, K)[1:]  # the rigid mode first
    hand_clamped = _undamped_Hz(J[1:], K[1:, 1:])
    assert_allclose([m["frequency_Hz"] for m in _elastic(out, "free")], hand_free, rtol=1e-8)
    assert_allclose([m["frequency_Hz"] for m in _elastic(out, "clamped_input")], hand_clamped, rtol=1e-8)


@pytest.mark.parametrize("zeta", [0.02, 0.1])
def test_single_stage_damping_ratios_against_the_hand_eigenvalues(tmp_path, zeta):
    """Each mode's damping ratio is -Re lambda / |lambda| of the hand model's damped eigenvalue."""
    text = _single(f"[contact]\ndamping_ratio = {zeta}\n")
    cga = _run(tmp_path, text, "design")["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    J, K, C, _ = _single_hand(cga, zeta)
    out = _run(tmp_path, text, "modes")
    for boundary, sl in (("free", slice(0, 4)), ("clamped_input", slice(1, 4))):
        lam = _damped(J[sl], K[sl, sl], C[sl, sl])
        tool = _elastic(out, boundary)
        assert len(tool) == len(lam)
        assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in lam], rtol=1e-6,
                        err_msg=boundary)
        assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J[sl], K[sl, sl])[-len(lam):], rtol=1e-8)


def _lone_gear(contact: str, simulation: str) -> str:
    """The stage alone: the pinion follows the prescribed speed, the gear (J_G) is the one degree of freedom."""
    return MATERIAL + f"""
[[stage]]
normal_module_mm = {M_N}
normal_pressure_angle_deg = {ALPHA_N}
helix_angle_deg = {BETA}
pinion = {{ teeth = {Z1}, face_width_mm = {B}, hand = "left", material = "steel", inertia_kg_m2 = {J_P} }}
gear   = {{ teeth = {Z2}, face_width_mm = {B}, hand = "right", material = "steel", inertia_kg_m2 = {J_G} }}
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


def test_lone_mesh_modal_damping_is_zeta_over_cos_beta_b(tmp_path):
    """One DOF: omega^2 = k_t r_bg^2 / J_G, and c = 2 zeta sqrt(k_n m_e) on the transverse q' with m_e = J_G / r_bg^2
    (the speed-driven pinion infinitely heavy) gives the modal ratio c / (2 sqrt(k_t m_e)) = zeta / cos beta_b."""
    zeta = 0.05
    text = _lone_gear("", "duration_s = 0.1")
    cga = _run(tmp_path, text, "design")["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    k_t = cga * B * 1e6
    w_n = math.sqrt(k_t * rg**2 / J_G)
    (mode,) = _elastic(_run(tmp_path, text, "modes"), "clamped_input")
    assert_allclose(mode["frequency_Hz"], w_n / (2 * math.pi), rtol=1e-9)
    assert_allclose(mode["damping_ratio"], zeta / cbb, rtol=1e-9)
