"""`gearcli modes` on a three-stage drivetrain with a power-law (Hertz-type) mesh law and IMPACT damping, against a
hand model (this file's own scene, no configs/ file, no gearcli number taken as a reference).

The scene: a motor rotor on a coupling to pinion 1, three helical stages, both intermediate shafts flexible (each
splits into its gear end and its pinion end), a drum on a coupling to the last gear; every inertia given. Each
mesh follows F_n = K h^1.5 + STEP(h, 0, 0, d, C) h' with K given (DESIGN section 4). The hand model:

- static normal force of stage s: F_n = T_g / (r_bg cos beta_b), T_g the load torque on its gear brought back
  through the later stages (efficiency 1); the static approach h0 = (F_n / K)^(2/3) and the tangent
  k_n = 1.5 K sqrt(h0) (DESIGN section 13: linearised models at the static load);
- along the transverse line of action delta = r_bp theta_p - r_bg theta_g the stiffness is k_n cos^2 beta_b and
  the damping c_n cos^2 beta_b with c_n = C s^2 (3 - 2 s), s = h0 / d (inside the ramp);
- base radii from ISO 21771 (tests/reference/modal_hand.py), sin beta_b = sin beta cos alpha_n.

Frequencies are the undamped eigenvalues of (K, J), the damping ratio -Re(lambda)/|lambda| of the damped state
matrix, the strain-energy shares k_c (R phi)_c^2 / sum over the elements; a speed drive clamps the motor
(`clamped_input`), `free` lets it turn (its rigid mode first, with shares all 0).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
from modal_hand import MATERIAL, _add, _base_radius_m, _cos_beta_b, _damped, _elastic, _run
from numpy.testing import assert_allclose

ALPHA_N = 20.0
# m_n, beta, z_p, z_g, J_p, J_g (kg m^2), K (N/mm^1.5)
STAGES = ((4.0, 12.0, 19, 61, 0.004, 0.35, 9.0e5), (6.0, 10.0, 17, 53, 0.03, 2.2, 1.2e6),
          (8.0, 8.0, 18, 59, 0.12, 14.0, 1.6e6))
K_SHAFT, C_SHAFT = (4.0e4, 2.5e5), (3.0, 12.0)  # N m/rad, N m s/rad: shafts 2 and 3
J_MOTOR, K_IN, C_IN = 0.08, 6.0e3, 4.0
J_DRUM, K_OUT, C_OUT = 60.0, 9.0e4, 80.0
T_LOAD = 4000.0  # N m on the drum
C_IMPACT, D_IMPACT = 30.0, 0.1  # N s/mm, mm
ELEMENTS = ["input coupling", "stage 1 mesh", "shaft 2", "stage 2 mesh", "shaft 3", "stage 3 mesh", "load coupling"]


def _scene() -> str:
    text = f'title = "three Hertz stages, flexible shafts, couplings"\n{MATERIAL}'
    hands = (("left", "right"), ("right", "left"), ("left", "right"))
    for k, ((m, beta, zp, zg, jp, jg, law), (hp, hg)) in enumerate(zip(STAGES, hands, strict=True)):
        text += (f"[[stage]]\nnormal_module_mm = {m}\nnormal_pressure_angle_deg = {ALPHA_N}\nhelix_angle_deg = {beta}\n"
                 f'pinion = {{ teeth = {zp}, face_width_mm = {10 * m}, hand = "{hp}", material = "steel", '
                 f"inertia_kg_m2 = {jp} }}\n"
                 f'gear = {{ teeth = {zg}, face_width_mm = {10 * m}, hand = "{hg}", material = "steel", '
                 f"inertia_kg_m2 = {jg} }}\n"
                 f"mesh = {{ stiffness = {law}, exponent = 1.5 }}\n")
        if k < 2:
            text += f"shaft = {{ stiffness_Nm_rad = {K_SHAFT[k]}, damping_Nms_rad = {C_SHAFT[k]} }}\n"
    return text + (f"[contact]\nexponent = 1.5\ndamping_Ns_mm = {C_IMPACT}\nfull_damping_penetration_mm = {D_IMPACT}\n"
                   f"[input]\nspeed_rpm = 1000\nramp_s = 0.1\ninertia_kg_m2 = {J_MOTOR}\n"
                   f"coupling_stiffness_Nm_rad = {K_IN}\ncoupling_damping_Nms_rad = {C_IN}\n"
                   f"[load]\ntorque_Nm = {T_LOAD}\nramp_s = 0.1\ninertia_kg_m2 = {J_DRUM}\n"
                   f"coupling_stiffness_Nm_rad = {K_OUT}\ncoupling_damping_Nms_rad = {C_OUT}\n"
                   "[simulation]\nduration_s = 0.3\n")


def _hand():
    """J, K, C over (motor, p1, g2, p3, g4, p5, g6, drum), the elements' levers and stiffnesses, the static approaches."""
    J = np.array([J_MOTOR] + [j for s in STAGES for j in s[4:6]] + [J_DRUM])
    n = len(J)
    K, C = np.zeros((n, n)), np.zeros((n, n))
    levers, springs, h0s = [], [], [0.0, 0.0, 0.0]
    torque = T_LOAD
    mesh = {}
    for s in (2, 1, 0):  # the gear torques from the drum back to the input
        m, beta, zp, zg, _, _, law = STAGES[s]
        rp, rg, cbb = _base_radius_m(zp, m, ALPHA_N, beta), _base_radius_m(zg, m, ALPHA_N, beta), _cos_beta_b(ALPHA_N, beta)
        f_n = torque / (rg * cbb)  # N
        h0s[s] = (f_n / law) ** (2 / 3)  # mm
        x = h0s[s] / D_IMPACT
        assert 0 < x < 1
        mesh[s] = ({1 + 2 * s: rp, 2 + 2 * s: -rg}, 1.5 * law * math.sqrt(h0s[s]) * 1e3 * cbb**2,
                   C_IMPACT * 1e3 * x * x * (3 - 2 * x) * cbb**2)
        torque *= zp / zg
    chain = [({0: 1.0, 1: -1.0}, K_IN, C_IN), mesh[0], ({2: 1.0, 3: -1.0}, K_SHAFT[0], C_SHAFT[0]), mesh[1],
             ({4: 1.0, 5: -1.0}, K_SHAFT[1], C_SHAFT[1]), mesh[2], ({6: 1.0, 7: -1.0}, K_OUT, C_OUT)]
    for lever, k, c in chain:
        _add(K, lever, k)
        _add(C, lever, c)
        v = np.zeros(n)
        for j, r in lever.items():
            v[j] = r
        levers.append(v)
        springs.append(k)
    return J, K, C, np.array(levers), np.array(springs), h0s


@pytest.fixture(scope="module")
def modes_json(tmp_path_factory):
    return _run(tmp_path_factory.mktemp("hertz3"), _scene(), "modes")


def test_static_approach_of_each_mesh_is_the_hand_one(modes_json):
    *_, h0s = _hand()
    assert_allclose([m["mesh_stiffness"]["static_approach_mm"] for m in modes_json["meshes"]], h0s, rtol=1e-9)
    assert modes_json["elements"] == ELEMENTS


@pytest.mark.parametrize("boundary", ["clamped_input", "free"])
def test_frequencies_damping_and_strain_energy_shares_by_hand(modes_json, boundary):
    J, K, C, levers, springs, _ = _hand()
    keep = list(range(1, len(J))) if boundary == "clamped_input" else list(range(len(J)))
    Jb, Kb, Cb = J[keep], K[np.ix_(keep, keep)], C[np.ix_(keep, keep)]
    w2, shapes = scipy.linalg.eigh(Kb, np.diag(Jb))
    modes = modes_json["boundaries"][boundary]
    elastic = _elastic(modes_json, boundary)
    n_rigid = len(modes) - len(elastic)
    assert n_rigid == (0 if boundary == "clamped_input" else 1)
    assert_allclose([m["frequency_Hz"] for m in elastic], np.sqrt(w2[n_rigid:]) / (2 * math.pi), rtol=1e-8)
    assert_allclose([m["damping_ratio"] for m in elastic], [-z.real / abs(z) for z in _damped(Jb, Kb, Cb)],
                    rtol=1e-6)
    for mode, j in zip(elastic, range(n_rigid, len(keep)), strict=True):
        full = np.zeros(len(J))
        full[keep] = shapes[:, j]
        strain = springs * (levers @ full) ** 2
        assert list(mode["energy_share"]) == ELEMENTS
        assert_allclose(list(mode["energy_share"].values()), strain / strain.sum(), atol=1e-9)
        assert sum(mode["energy_share"].values()) == pytest.approx(1.0, abs=1e-12)
    if n_rigid:
        assert all(v == 0.0 for v in modes[0]["energy_share"].values())
