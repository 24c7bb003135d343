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


# --- two helical stages, a motor (torque-speed table) on a coupling, a fan load on a coupling --------------------

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


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.0])
def test_motor_driven_two_stage_train_against_the_hand_model(tmp_path, exponent):
    """Frequencies and damping ratios, free and with the motor held, for e = 1, 1.5 (default), 2."""
    contact = "" if exponent == 1.5 else f"[contact]\nexponent = {exponent}\n"
    text = _two_stage(contact)
    design = _run(tmp_path, text, "design")
    assert not design["warnings"], design["warnings"]  # the table carries the fan at 1450 rpm: balanced
    J, K, C = _two_stage_hand([s["iso6336_mesh_stiffness_N_mm_um"] for s in design["stages"]], 0.05)
    out = _run(tmp_path, text, "modes")
    for ms in out["meshes"]:
        assert_allclose(ms["mesh_stiffness"]["linearised_N_mm"], ms["mesh_stiffness"]["iso_N_mm"], rtol=1e-9)
    for boundary, sl in (("free", slice(0, 5)), ("clamped_input", slice(1, 5))):
        Cb = C[sl, sl].copy()
        lam = _damped(J[sl], K[sl, sl], Cb)
        tool = _elastic(out, boundary)
        assert len(tool) == len(lam) == (4 if boundary == "free" else 4)
        assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J[sl], K[sl, sl])[-4:], rtol=1e-8,
                        err_msg=boundary)
        assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in lam], rtol=1e-6,
                        err_msg=boundary)


# --- a planetary stage: sun 21, three planets 27, ring 75 held, carrier driven at 300 rpm, sun loaded --------------

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


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.0])
def test_planetary_modes_against_the_hand_model(tmp_path, exponent):
    contact = "" if exponent == 1.5 else f"[contact]\nexponent = {exponent}\n"
    text = _planetary(contact)
    design = _run(tmp_path, text, "design")
    st = design["stages"][0]
    assert_allclose(st["carrier"]["planets_translational_inertia_kg_m2"], 3 * M_PLANET * 0.072**2, rtol=1e-12)
    cga = {m["name"]: m["iso6336_mesh_stiffness_N_mm_um"] for m in st["meshes"]}
    k_sp, k_pr = cga["sun_planet"] * 30e6, cga["planet_ring"] * 30e6  # spur: k_n = k_t = c_gamma_alpha b
    out = _run(tmp_path, text, "modes")
    for ms in out["meshes"]:
        k = ms["mesh_stiffness"]
        assert_allclose(k["linearised_N_mm"], k["iso_N_mm"], rtol=1e-9)
        assert_allclose(k["iso_N_mm"], (k_sp if ms["mesh"] == "sun_planet" else k_pr) / 1000, rtol=1e-9)
        assert k["exponent"] == exponent
    J, K, C = _planetary_hand(k_sp, k_pr, 0.05)
    for boundary, sl in (("free", slice(0, 5)), ("clamped_input", slice(0, 4))):
        tool = _elastic(out, boundary)
        lam = _damped(J[sl], K[sl, sl], C[sl, sl])
        assert len(tool) == len(lam) == 4
        # the planet mode (sun and carrier still) is twofold, N - 1 = 2
        assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J[sl], K[sl, sl])[-4:], rtol=1e-8,
                        err_msg=boundary)
        assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in lam], rtol=1e-6,
                        err_msg=boundary)


# --- simulate: the lone gear rings after a short start; its decay and frequency against the hand model -------------

def test_simulated_free_vibration_against_the_hand_model(tmp_path):
    """A 10 ms start leaves the gear ringing at +-13 % of the static force; the window after it is a free decay of the
    default Hertzian law (e = 1.5, linearised at the static load). An independent least-squares fit of
    F0 + A exp(-sigma t) cos(w_d t + psi) to the simulated F_t gives sigma = zeta_m w_n and w_d = w_n sqrt(1 - zeta_m^2),
    zeta_m = zeta / cos beta_b, w_n^2 = k_t r_bg^2 / J_G; F0 the static F_t = 2 T / d of the gear (DESIGN section 4:
    F_t = F_bt cos alpha_t, the reference circle). The run's ringing record names the same mode."""
    from scipy.optimize import curve_fit

    zeta, t0 = 0.005, 0.012
    text = _lone_gear(f"[contact]\ndamping_ratio = {zeta}\n",
                      f"duration_s = 0.05\nwindow_start_s = {t0}\nsteps = 20000\nrtol = 1e-9")
    text = text.replace("ramp_s = 0.02", "ramp_s = 0.01")
    cga = _run(tmp_path, text, "design")["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    out = _run(tmp_path, text, "simulate", "--series")
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    w_n = math.sqrt(cga * B * 1e6 * rg**2 / J_G)
    zeta_m = zeta / cbb
    sigma, w_d = zeta_m * w_n, w_n * math.sqrt(1 - zeta_m**2)
    d_gear = Z2 * M_N / math.cos(math.radians(BETA)) / 1000
    F_static = 2 * T_LOAD / d_gear
    assert_allclose(out["summary"]["natural_frequencies_Hz"], [w_n / (2 * math.pi)], rtol=1e-9)
    st = out["summary"]["stages"][0]
    assert_allclose(st["static_tangential_N"], F_static, rtol=1e-9)
    # the mean of a decay over a window that is not whole periods: up to A / (w_d T_window) = 363 / (11545 * 0.038) N
    assert_allclose(st["tangential_N"]["mean"], F_static, atol=1.0)
    t = np.asarray(out["series"]["time_s"])
    F = np.asarray(out["series"]["stage1_tangential_N"])
    keep = t >= t0
    t, F = t[keep] - t0, F[keep]

    def model(t, A, s, w, psi, F0):
        return F0 + A * np.exp(-s * t) * np.cos(w * t + psi)

    fits = []
    for psi in np.linspace(0.0, 2 * math.pi, 8, endpoint=False):
        p, _ = curve_fit(model, t, F, p0=[300.0, 50.0, w_n, psi, F_static], maxfev=20000)
        fits.append((float(np.sum((model(t, *p) - F) ** 2)), p))
    p = min(fits, key=lambda f: f[0])[1]
    assert abs(p[0]) > 0.05 * F_static  # it rings: the test has something to fit
    assert_allclose(p[1], sigma, rtol=2e-3)  # linear decay rate; the Hertzian law's amplitude effect is O(a^2)
    assert_allclose(p[2], w_d, rtol=5e-4)  # the Hertzian law softens +-13 % swings by ~1e-4
    assert_allclose(p[4], F_static, rtol=1e-4)
    ring = next(w for w in out["warnings"] if w.get("mode_frequency_Hz"))
    assert_allclose(ring["mode_frequency_Hz"], w_d / (2 * math.pi), rtol=1e-6)
    # it settles where the fitted envelope falls to 1 % of the static force: t0 + ln(a0 / 0.01 F) / sigma
    assert_allclose(ring["settle_time_s"], t0 + math.log(abs(p[0]) / (0.01 * F_static)) / sigma, rtol=0.02)


# --- statics: the calibrated law's deflection, the rigid-body limit, the Hertz law and stiffness_not_iso ------------

def _static_normal_force_N() -> float:
    """F_n0 = T / (r_bg cos beta_b): the load torque on the gear along the normal line of action."""
    return T_LOAD / _base_radius_m(Z2, M_N, ALPHA_N, BETA) / _cos_beta_b(ALPHA_N, BETA)


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.0])
def test_static_deflection_is_e_times_iso(tmp_path, exponent):
    """h0 = e F_n0 / k_n (docs/physics.md), in design, modes and the settled simulated penetration."""
    text = _lone_gear(f"[contact]\nexponent = {exponent}\ndamping_ratio = 0.3\n", "duration_s = 0.06")
    design = _run(tmp_path, text, "design")
    st = design["stages"][0]
    k_n = st["iso6336_mesh_stiffness_N_mm_um"] * B * 1e3 / _cos_beta_b(ALPHA_N, BETA) ** 2  # N/mm
    h0 = exponent * _static_normal_force_N() / k_n
    assert_allclose(st["static_force_N"]["normal"], _static_normal_force_N(), rtol=1e-9)
    assert_allclose(st["mesh_stiffness"]["static_approach_mm"], h0, rtol=1e-9)
    assert_allclose(_run(tmp_path, text, "modes")["meshes"][0]["mesh_stiffness"]["static_approach_mm"], h0, rtol=1e-9)
    sim = _run(tmp_path, text, "simulate")["summary"]["stages"][0]
    assert_allclose(sim["penetration_mm"]["mean"], h0, rtol=1e-5)  # settled at 30 % damping
    assert_allclose(sim["tangential_N"]["mean"], 2 * T_LOAD / (Z2 * M_N / math.cos(math.radians(BETA)) / 1000),
                    rtol=1e-6)


def test_rigid_body_limit(tmp_path):
    """A mesh 1300 times ISO's: the output turns at input / i, F_t is the static 2 T / d, the mode is at
    sqrt(K cos^2 beta_b r_bg^2 / J_G), and stiffness_not_iso says so."""
    K = 1e9  # N/mm, e = 1
    text = _lone_gear(f"[contact]\nstiffness = {K}\nexponent = 1.0\ndamping_ratio = 0.1\n", "duration_s = 0.06")
    out = _run(tmp_path, text, "simulate")
    s = out["summary"]
    assert_allclose(s["output_speed_rpm"], 1500 * Z1 / Z2, rtol=1e-9)
    assert_allclose(s["ratio"], Z2 / Z1, rtol=1e-9)
    st = s["stages"][0]
    assert_allclose(st["tangential_N"]["mean"], 2 * T_LOAD / (Z2 * M_N / math.cos(math.radians(BETA)) / 1000),
                    rtol=1e-9)
    assert st["tangential_N"]["std"] < 1e-6 * st["tangential_N"]["mean"]
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    assert_allclose(s["natural_frequencies_Hz"], [math.sqrt(K * 1e3 * cbb**2 * rg**2 / J_G) / (2 * math.pi)],
                    rtol=1e-9)
    assert_allclose(st["penetration_mm"]["mean"], _static_normal_force_N() / K, rtol=1e-6)
    assert st["mesh_stiffness"]["law"] == "given"
    assert [w["code"] for w in out["warnings"]].count("stiffness_not_iso") == 1


def test_hertz_law_is_four_thirds_sqrt_r_e_star_and_warned(tmp_path):
    """stiffness = "hertz": K = 4/3 sqrt(R) E*, E* = E / (2 (1 - nu^2)) for two steel wheels, linearised
    e K h0^(e-1) with h0 = (F_n0 / K)^(1/e): 75 % below ISO's k_n, warned the same in design, modes and simulate."""
    text = _lone_gear('[contact]\nstiffness = "hertz"\n', "duration_s = 0.06")
    design = _run(tmp_path, text, "design")
    st = design["stages"][0]
    e_star = 2.1e5 / (2 * (1 - 0.3**2))
    K = 4 / 3 * math.sqrt(st["equivalent_radius_mm"]) * e_star
    F = _static_normal_force_N()
    lin = 1.5 * K * (F / K) ** (1 / 3)
    k_n = st["iso6336_mesh_stiffness_N_mm_um"] * B * 1e3 / _cos_beta_b(ALPHA_N, BETA) ** 2
    for cmd, ms in (("design", st["mesh_stiffness"]),
                    ("modes", (m := _run(tmp_path, text, "modes"))["meshes"][0]["mesh_stiffness"]),
                    ("simulate", (s := _run(tmp_path, text, "simulate"))["summary"]["stages"][0]["mesh_stiffness"])):
        assert ms["law"] == "hertz", cmd
        assert_allclose([ms["K"], ms["linearised_N_mm"], ms["iso_N_mm"], ms["static_approach_mm"]],
                        [K, lin, k_n, (F / K) ** (2 / 3)], rtol=1e-9, err_msg=cmd)
    for out in (design, m, s):
        (w,) = [w for w in out["warnings"] if w["code"] == "stiffness_not_iso"]
        assert_allclose(w["departure"], lin / k_n - 1, rtol=1e-9)
        assert lin / k_n - 1 < -0.7


@pytest.mark.parametrize(("exponent", "ratio", "warned"),
                         [(1.0, 1.24, False), (1.0, 1.26, True), (1.0, 0.76, False), (1.0, 0.74, True),
                          (1.5, 1.24, False), (1.5, 1.26, True), (1.5, 0.76, False), (1.5, 0.74, True)])
def test_stiffness_not_iso_fires_beyond_25_percent(tmp_path, exponent, ratio, warned):
    """A given K whose tangent at F_n0 is `ratio` times k_n: K = (ratio k_n / e)^e / F_n0^(e-1)."""
    probe = _run(tmp_path, _lone_gear("", "duration_s = 0.06"), "design")["stages"][0]
    k_n = probe["iso6336_mesh_stiffness_N_mm_um"] * B * 1e3 / _cos_beta_b(ALPHA_N, BETA) ** 2
    F = _static_normal_force_N()
    K = (ratio * k_n / exponent) ** exponent / F ** (exponent - 1)
    text = _lone_gear(f"[contact]\nstiffness = {K!r}\nexponent = {exponent}\n", "duration_s = 0.06")
    for cmd in ("design", "modes"):
        out = _run(tmp_path, text, cmd)
        ms = (out["stages"][0] if cmd == "design" else out["meshes"][0])["mesh_stiffness"]
        assert_allclose(ms["linearised_N_mm"] / ms["iso_N_mm"], ratio, rtol=1e-9, err_msg=cmd)
        assert any(w["code"] == "stiffness_not_iso" for w in out["warnings"]) is warned, cmd


# --- a (nearly) unloaded train: the iso6336 law's linearisation holds at its calibration floor ----------------------

@pytest.mark.parametrize("torque", [0.0, 1e-3, 1.0])
def test_lightly_loaded_train_linearises_at_the_calibration_floor(tmp_path, torque):
    """Below 1 N/mm of face width the iso6336 law is calibrated at that floor (docs/physics.md): its tangent is
    ISO's k_n there, and design reports linearised_N_mm = k_n. modes and simulate linearised the law at the real
    static load instead: 1 N m gave the mesh mode 1588 Hz (-21 %), 1e-3 N m 548 Hz (-73 %) and 0 N m 4142 Hz (+106 %,
    a 1 um approach) against 2015 Hz of the hand model with k_n, and simulate reported linearised_N_mm 158138 and
    15814 N/mm beside design's 256714. Now all of them are the linear ISO model at the floor, continuous in the load."""
    text = _single().replace(f"torque_Nm = {T_LOAD}", f"torque_Nm = {torque}")
    design = _run(tmp_path, text, "design")
    cga = design["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    J, K, C, k_n = _single_hand(cga, 0.05)
    assert_allclose(design["stages"][0]["mesh_stiffness"]["linearised_N_mm"], k_n / 1000, rtol=1e-9)
    out = _run(tmp_path, text, "modes")
    assert_allclose(out["meshes"][0]["mesh_stiffness"]["linearised_N_mm"], k_n / 1000, rtol=1e-9)
    lam = _damped(J, K, C)
    tool = _elastic(out, "free")
    assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J, K)[1:], rtol=1e-8)
    assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in lam], rtol=1e-6)
    sim = _run(tmp_path, text.replace("duration_s = 0.4", "duration_s = 0.15"), "simulate")["summary"]
    assert_allclose(sim["stages"][0]["mesh_stiffness"]["linearised_N_mm"], k_n / 1000, rtol=1e-9)
    assert_allclose(sim["natural_frequencies_Hz"], _undamped_Hz(J[1:], K[1:, 1:]), rtol=1e-8)  # the motor held


def test_lightly_loaded_planetary_linearises_at_the_calibration_floor(tmp_path):
    """The same for both planet meshes (each at its own floor): a 0.1 N m sun load against the hand model."""
    text = _planetary().replace("torque_Nm = 100", "torque_Nm = 0.1")
    st = _run(tmp_path, text, "design")["stages"][0]
    cga = {m["name"]: m["iso6336_mesh_stiffness_N_mm_um"] for m in st["meshes"]}
    k_sp, k_pr = cga["sun_planet"] * 30e6, cga["planet_ring"] * 30e6
    out = _run(tmp_path, text, "modes")
    for ms in out["meshes"]:
        assert_allclose(ms["mesh_stiffness"]["linearised_N_mm"], ms["mesh_stiffness"]["iso_N_mm"], rtol=1e-9)
    J, K, C = _planetary_hand(k_sp, k_pr, 0.05)
    tool = _elastic(out, "clamped_input")
    assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J[:4], K[:4, :4]), rtol=1e-8)
    assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in _damped(J[:4], K[:4, :4],
                                                                                          C[:4, :4])], rtol=1e-6)


def test_transmission_error_response_against_the_hand_transfer_function(tmp_path):
    """A 1 um first-harmonic TE at the mesh frequency z_p n_p = 525 Hz on the lone gear (linear law): with u the
    dynamic deflection, m_e u'' + c (u' - e') + k_t (u - e) = 0, so q = u - e = e m_e w^2 / (k_t - m_e w^2 + i w c)
    and F_bt = (k_t + i w c) q; the window's F_t std is |F_bt| cos alpha_t / sqrt 2, the DTE rms |q| / sqrt 2."""
    text = _lone_gear("[contact]\nexponent = 1.0\ndamping_ratio = 0.05\ntransmission_error_um = [1.0]\n",
                      "duration_s = 0.12\nwindow_start_s = 0.08\nsteps = 8000\nrtol = 1e-9")
    cga = _run(tmp_path, text, "design")["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    st = _run(tmp_path, text, "simulate")["summary"]["stages"][0]
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    k_t = cga * B * 1e6
    m_e = J_G / rg**2
    c = 2 * 0.05 * math.sqrt(k_t / cbb**2 * m_e)
    w = 2 * math.pi * Z1 * 1500 / 60
    q = 1e-6 * m_e * w**2 / complex(k_t - m_e * w**2, w * c)
    F = abs(complex(k_t, w * c) * q)
    alpha_t = math.atan(math.tan(math.radians(ALPHA_N)) / math.cos(math.radians(BETA)))
    # 40 ms of window after 60 ms of settling at 5 % damping (w_n zeta t ~ 35 decay lengths): steady to < 1e-4
    assert_allclose(st["tangential_N"]["std"], F * math.cos(alpha_t) / math.sqrt(2), rtol=5e-4)
    assert_allclose(st["dte_um"]["rms"], abs(q) * 1e6 / math.sqrt(2), rtol=5e-4)


def test_motor_driven_train_with_a_flexible_intermediate_shaft(tmp_path):
    """[stage.shaft] on stage 1: shaft 2 splits into its gear end (J_g1) and pinion end (J_p2) on a 20 kN m/rad,
    0.5 N m s/rad spring; each mesh's m_e then takes the end it touches."""
    text = _two_stage().replace(
        'hand = "right", material = "steel", inertia_kg_m2 = 0.02 }',
        'hand = "right", material = "steel", inertia_kg_m2 = 0.02 }\nshaft = { stiffness_Nm_rad = 20000, '
        'damping_Nms_rad = 0.5 }', 1)
    design = _run(tmp_path, text, "design")
    out = _run(tmp_path, text, "modes")
    assert out["bodies"] == ["motor", "shaft 1", "shaft 2 gear end", "shaft 2 pinion end", "shaft 3", "drum"]
    (_, _, _, _, _, jp1, jg1), (_, _, _, _, _, jp2, jg2) = STAGES
    J = np.array([J_ROTOR, jp1, jg1, jp2, jg2, J_FAN])
    K, C = np.zeros((6, 6)), np.zeros((6, 6))
    _add(K, {0: 1.0, 1: -1.0}, K_M)
    _add(C, {0: 1.0, 1: -1.0}, C_M)
    for (m, beta, zp, zg, b, _, _), st, (p, g) in zip(STAGES, design["stages"], ((1, 2), (3, 4)), strict=True):
        rp, rg = _base_radius_m(zp, m, 20.0, beta), _base_radius_m(zg, m, 20.0, beta)
        k_t = st["iso6336_mesh_stiffness_N_mm_um"] * b * 1e6
        m_e = J[p] * J[g] / (J[p] * rg**2 + J[g] * rp**2)
        _add(K, {p: rp, g: -rg}, k_t)
        _add(C, {p: rp, g: -rg}, 2 * 0.05 * math.sqrt(k_t / _cos_beta_b(20.0, beta) ** 2 * m_e))
    _add(K, {2: 1.0, 3: -1.0}, 20000.0)
    _add(C, {2: 1.0, 3: -1.0}, 0.5)
    _add(K, {4: 1.0, 5: -1.0}, K_L)
    _add(C, {4: 1.0, 5: -1.0}, C_L)
    C[0, 0] += 300.0 / (100 * math.pi / 30)
    C[5, 5] += 2 * T_FAN / (N_IN * math.pi / 30 / RATIO)
    tool = _elastic(out, "free")
    assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J, K)[1:], rtol=1e-8)
    assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in _damped(J, K, C)], rtol=1e-6)


def test_planetary_simulate_reports_both_mesh_laws(tmp_path):
    """DESIGN section 13: simulate gives every mesh's mesh_stiffness; a planetary stage's planet–ring law is
    ``planet_ring_mesh_stiffness`` beside the sun–planet mesh's ``mesh_stiffness`` (it had none). A planet carries
    r_bp F_sp = r_bp F_pr (spur, lossless): both meshes F_n0 = T_sun / (N r_bs), h0 = e F_n0 / k_n each."""
    text = _planetary()
    st = _run(tmp_path, text, "design")["stages"][0]
    cga = {m["name"]: m["iso6336_mesh_stiffness_N_mm_um"] for m in st["meshes"]}
    sim = _run(tmp_path, text, "simulate")["summary"]["stages"][0]
    F_n0 = 100.0 / (3 * 21 * 3.0 / 2 * math.cos(math.radians(20.0)) / 1000)
    for key, name in (("mesh_stiffness", "sun_planet"), ("planet_ring_mesh_stiffness", "planet_ring")):
        k_n = cga[name] * 30 * 1e3  # N/mm, spur
        ms = sim[key]
        assert ms["law"] == "iso6336" and ms["exponent"] == 1.5
        assert_allclose([ms["linearised_N_mm"], ms["iso_N_mm"], ms["static_approach_mm"]],
                        [k_n, k_n, 1.5 * F_n0 / k_n], rtol=1e-9, err_msg=key)


def test_impact_damped_mesh_modal_damping_at_its_static_penetration(tmp_path):
    """The IMPACT law (DESIGN section 4): F_n = K h^e + STEP(h, 0, 0, d, C) h'. At the static approach h0 (inside the
    ramp here, s = h0 / d) the normal damping is C s^2 (3 - 2 s); along delta (h = cos beta_b delta, F_bt = cos beta_b
    F_n) it is cos^2 beta_b times that, so the lone gear's modal ratio is cos^2 beta_b c_n / (2 sqrt(k_t m_e))."""
    C_Ns_mm, d_mm = 10.0, 0.02
    text = _lone_gear(f"[contact]\ndamping_Ns_mm = {C_Ns_mm}\nfull_damping_penetration_mm = {d_mm}\n",
                      "duration_s = 0.1")
    st = _run(tmp_path, text, "design")["stages"][0]
    (mode,) = _elastic(out := _run(tmp_path, text, "modes"), "clamped_input")
    ms = out["meshes"][0]["mesh_stiffness"]
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    k_t = st["iso6336_mesh_stiffness_N_mm_um"] * B * 1e6
    h0 = 1.5 * _static_normal_force_N() / (k_t / cbb**2 / 1000)  # mm: the default e = 1.5, tangent k_n
    assert_allclose(ms["static_approach_mm"], h0, rtol=1e-9)
    s = h0 / d_mm
    assert 0 < s < 1  # inside the ramp
    c_n = C_Ns_mm * 1000 * s * s * (3 - 2 * s)  # N s/m
    m_e = J_G / rg**2
    assert_allclose(mode["frequency_Hz"], math.sqrt(k_t / m_e) / (2 * math.pi), rtol=1e-9)
    assert_allclose(mode["damping_ratio"], cbb**2 * c_n / (2 * math.sqrt(k_t * m_e)), rtol=1e-9)


def test_sweep_points_calibrate_at_their_own_load(tmp_path):
    """DESIGN section 13: K follows each sweep point's static load, so each point's mean DTE is its own
    h0 / cos beta_b = e F_n0 / (k_n cos beta_b), k_n from that point's c_gamma_alpha (ISO's low-load factor moves it)."""
    import csv

    text = _lone_gear("[contact]\ndamping_ratio = 0.3\n", "duration_s = 0.08\nwindow_start_s = 0.06")
    scene = tmp_path / "scene.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "sweep.csv"
    res = CliRunner().invoke(cli, ["sweep", str(scene), "--vary", "load.torque_Nm=150,600", "--jobs", "1",
                                   "-o", str(out)])
    assert res.exit_code == 0, res.output
    rows = list(csv.DictReader(line for line in out.read_text().splitlines() if not line.startswith("#")))
    cbb = _cos_beta_b(ALPHA_N, BETA)
    assert len(rows) == 2
    for row in rows:
        torque = float(row["load.torque_Nm"])
        res = CliRunner().invoke(cli, ["design", str(scene), "--set", f"load.torque_Nm={torque}", "--format", "json"])
        cga = json.loads(res.stdout)["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
        k_n = cga * B * 1e3 / cbb**2
        F_n0 = torque / _base_radius_m(Z2, M_N, ALPHA_N, BETA) / cbb
        assert_allclose(float(row["stage1_dte_um_mean"]), 1.5 * F_n0 / k_n / cbb * 1000, rtol=1e-6)


@pytest.mark.parametrize("torque", [0.0, 1.0])
def test_hertz_law_below_the_floor_reports_its_own_tangent(tmp_path, torque):
    """A Hertz law needs no calibration floor: design and modes reported its tangent at 1 N/mm of face width
    (45201 N/mm, h0 1.5 um) where simulate reported it at the static load (1 N m: 27844 N/mm, h0 0.57 um; 0 N m: 0).
    All three now give e K h0^(e-1) with h0 = (F_n0 / K)^(1/e) at the static F_n0, and warn the same departure."""
    text = _lone_gear('[contact]\nstiffness = "hertz"\n', "duration_s = 0.06").replace(
        f"torque_Nm = {T_LOAD}", f"torque_Nm = {torque}")
    st = _run(tmp_path, text, "design")["stages"][0]
    K = st["hertz_stiffness_N_mm1_5"]
    F = torque / _base_radius_m(Z2, M_N, ALPHA_N, BETA) / _cos_beta_b(ALPHA_N, BETA)
    h0 = (F / K) ** (2 / 3)
    lin = 1.5 * K * h0**0.5
    docs = {"design": (d := _run(tmp_path, text, "design"), d["stages"][0]["mesh_stiffness"]),
            "modes": (m := _run(tmp_path, text, "modes"), m["meshes"][0]["mesh_stiffness"]),
            "simulate": (s := _run(tmp_path, text, "simulate"), s["summary"]["stages"][0]["mesh_stiffness"])}
    for cmd, (doc, ms) in docs.items():
        assert_allclose([ms["static_approach_mm"], ms["linearised_N_mm"]], [h0, lin], rtol=1e-9, atol=1e-12,
                        err_msg=cmd)
        (w,) = [w for w in doc["warnings"] if w["code"] == "stiffness_not_iso"]
        assert_allclose(w["departure"], lin / ms["iso_N_mm"] - 1, rtol=1e-9, err_msg=cmd)


def test_torque_driven_planetary_damping_takes_the_free_carrier(tmp_path):
    """With a torque drive no member is prescribed: a planet mesh's m_e = 1 / sum r_j^2 / J_j over the three bodies it
    joins (sun or held ring, planet, carrier with lever r_bs + r_bp or r_br - r_bp and its N m_p r_c^2)."""
    text = _planetary().replace("speed_rpm = 300", f"speed_rpm = 300\ndrive = \"torque\"\ntorque_Nm = {100 * (1 + 75 / 21)!r}")
    st = _run(tmp_path, text, "design")["stages"][0]
    cga = {m["name"]: m["iso6336_mesh_stiffness_N_mm_um"] for m in st["meshes"]}
    k_sp, k_pr = cga["sun_planet"] * 30e6, cga["planet_ring"] * 30e6
    J, K, _ = _planetary_hand(k_sp, k_pr, 0.05)
    a = math.radians(20.0)
    rbs, rbp, rbr = (z * 1.5 * math.cos(a) / 1000 for z in (21, 27, 75))
    c_sp = 0.1 * math.sqrt(k_sp / (rbs**2 / J_SUN + rbp**2 / J_PLANET + (rbs + rbp) ** 2 / J[4]))
    c_pr = 0.1 * math.sqrt(k_pr / (rbp**2 / J_PLANET + (rbr - rbp) ** 2 / J[4]))
    C = np.zeros((5, 5))
    for p in (1, 2, 3):
        _add(C, {0: rbs, p: rbp, 4: -(rbs + rbp)}, c_sp)
        _add(C, {p: rbp, 4: rbr - rbp}, c_pr)
    tool = _elastic(_run(tmp_path, text, "modes"), "free")
    assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J, K)[1:], rtol=1e-8)
    assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in _damped(J, K, C)], rtol=1e-6)
