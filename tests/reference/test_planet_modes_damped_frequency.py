"""A planetary stage's repeated planet modes each ring at their damped frequency (trial tr24c). A spur stage
40/20/80 with five planets, ring held, on a linear mesh law with viscous damping: the N - 1 = 4 planet modes
share one frequency, w^2 = (k_sp + k_rp) r_bp^2 / J_p, with the sun and the carrier at rest, and since the
meshes' damping has the stiffness's pattern (c_sp, c_rp on the same levers) that space is invariant under it too:
each planet mode is a damped oscillator, lambda = -zeta w +- i w sqrt(1 - zeta^2), zeta = (c_sp + c_rp) r_bp^2 /
(2 J_p w), c = 2 zeta_mesh sqrt(k m_e), m_e = 1 / (r_bp^2 / J_p + (r_c cos a_w)^2 / J_c) (docs/physics.md: the
speed drive and the held ring count as infinitely heavy; J_c with the planets' N m_p r_c^2).

The undamped solver's basis of that eigenspace and the damped eigenvectors are two arbitrary bases of the same
space: matched vector by vector, three of the four planet modes found no eigenvalue and were reported with a null
`damped_frequency_Hz` (the contract keeps null for rigid and overdamped modes), their ratio the modal projection's."""

from __future__ import annotations

import json
import math

import pytest
import tomli_w
from click.testing import CliRunner

from gearcli.cli import cli

K, ZETA, J_S, J_P, M_P, J_C, N = 6e8, 0.05, 0.0064, 0.00038, 0.84, 0.02, 5
M, ZS, ZP, ZR = 3.0, 40, 20, 80
STAGE = {"type": "planetary", "normal_module_mm": M, "normal_pressure_angle_deg": 20, "fixed": "ring", "input": "sun",
         "sun": {"teeth": ZS, "face_width_mm": 40, "inertia_kg_m2": J_S},
         "planet": {"teeth": ZP, "face_width_mm": 38, "count": N, "inertia_kg_m2": J_P, "mass_kg": M_P},
         "ring": {"teeth": ZR, "face_width_mm": 38}, "carrier": {"inertia_kg_m2": J_C}}
SCENE = tomli_w.dumps({"stage": [STAGE], "contact": {"stiffness": K / 1000, "exponent": 1, "damping_ratio": ZETA},
                       "input": {"speed_rpm": 1500}, "load": {"torque_Nm": 1500}})


def _planet_mode():
    """The planet modes' undamped frequency, damping ratio and damped frequency (Hz), by hand."""
    cos_a = math.cos(math.radians(20))
    r_bp = ZP * M / 2 * cos_a / 1e3
    r_c = (ZS + ZP) * M / 2 / 1e3  # zero shifts: both working angles 20 deg, r_c cos a_w on both meshes
    j_c = J_C + N * M_P * r_c**2
    m_e = 1.0 / (r_bp**2 / J_P + (r_c * cos_a) ** 2 / j_c)  # the same for the sun and the ring mesh
    w = math.sqrt(2.0 * K * r_bp**2 / J_P)
    c = 2.0 * ZETA * math.sqrt(K * m_e)
    zeta = 2.0 * c * r_bp**2 / (2.0 * J_P * w)
    return w / (2 * math.pi), zeta, w * math.sqrt(1.0 - zeta**2) / (2 * math.pi)


@pytest.mark.parametrize("boundary", ["clamped_input", "free"])
def test_every_repeated_planet_mode_rings_at_its_damped_frequency(tmp_path, boundary):
    f, zeta, f_d = _planet_mode()  # 8.48 kHz, 6.8 %
    path = tmp_path / "five_planets.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["-q", "modes", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    modes = json.loads(res.stdout)["boundaries"][boundary]
    planet = [m for m in modes if m["frequency_Hz"] == pytest.approx(f, rel=1e-9)]
    # the N - 1 planet modes; with the sun clamped also the planets' in-phase swing, which zero shifts and equal k
    # decouple from the carrier (k r_bp (r_br - r_bs - 2 r_bp) = 0): the same oscillator
    assert len(planet) == (N if boundary == "clamped_input" else N - 1)
    for m in planet:
        assert abs(m["shape"]["shaft 1"]) < 1e-9 and abs(m["shape"]["shaft 2"]) < 1e-9  # sun and carrier still
        assert m["damping_ratio"] == pytest.approx(zeta, rel=1e-9)
        assert m["damped_frequency_Hz"] is not None
        assert m["damped_frequency_Hz"] == pytest.approx(f_d, rel=1e-9)


# Sequentially phased (39/21/81, five planets: h z_s / N = 7.8 at h = 1), the mesh order drives only the planet modes.
SEQUENTIAL = dict(STAGE, sun=dict(STAGE["sun"], teeth=39), planet=dict(STAGE["planet"], teeth=21),
                  ring=dict(STAGE["ring"], teeth=81))


def test_a_repeated_planet_modes_resonance_names_every_planet_alike(tmp_path):
    """The resonance warning of the planet modes' eigenspace names what holds its strain energy over the whole
    space: with the same k on both meshes and every planet alike (cyclic symmetry), each of the 10 planet meshes holds
    1/10 (k r_bp^2 theta_j^2 on either mesh of planet j, the planets equal over the space). One basis vector's shares
    named whichever planet the eigensolver's basis favoured ("stage 1 planet 1 sun and ring meshes (50 % of its
    strain energy)": a basis vector in which planet 1 alone swings)."""
    cos_a = math.cos(math.radians(20))
    r_bp = 21 * M / 2 * cos_a / 1e3
    f_planet = math.sqrt(2.0 * K * r_bp**2 / J_P) / (2 * math.pi)
    # the 1x mesh order (z_s |n_s - n_c|, n_c = n_s z_s / (z_s + z_r)) 2 % below the planet modes
    n_s = 60.0 * f_planet / 1.02 / (39 * 81 / 120)
    scene = tomli_w.dumps({"stage": [SEQUENTIAL], "input": {"speed_rpm": n_s}, "load": {"torque_Nm": 1500},
                           "contact": {"stiffness": K / 1000, "exponent": 1, "damping_ratio": ZETA}})
    path = tmp_path / "sequential.toml"
    path.write_text(scene)
    res = CliRunner().invoke(cli, ["-q", "modes", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    found = [w for w in json.loads(res.stdout)["warnings"] if w["code"] == "resonance"
             and w["frequency_Hz"] == pytest.approx(f_planet, rel=1e-9)]
    assert found  # the planet modes, once per boundary
    for w in found:
        assert "(repeated)" in w["message"]
        assert w["element"] == "stage 1 planets 1, 2, 3, 4, 5 sun and ring meshes"
        assert "(10 % of its strain energy)" in w["message"]
