"""The dynamic route's load spectrum against a closed form (round-4 trial tr17c).

A spur pair 20/60 driven at a prescribed speed, a linear ISO mesh (exponent 1, k = c_γα b), viscous mesh damping
ζ = 0.05 on the dynamic transmission error, one harmonic of static transmission error e(φ) = E cos φ and the load
torque on the wheel alone: a single-degree-of-freedom forced response. With x the wheel's base-circle coordinate and
q = δ − e, m_e ẍ = F − T/r_b2, m_e = J_2 / r_b2², F = k q + c q̇, c = 2 ζ √(k m_e), so at the mesh frequency ω

    F_dyn = E (k + iωc) m_e ω² / (k − m_e ω² + iωc),   K_v = 1 + |F_dyn| / (T / r_b2).

Each mesh cycle meets the static force plus that amplitude once, so every engagement counted in the window sits at
K_v times the static force: the life's ``points[i].K_v`` is this K_v, and the damage is the rating's at K_v = 1 at
the torque K_v T (``--static --set rating.dynamic_factor=1``). c_γα by ISO 6336-1, typed again in
tests/reference/rating_hand.py; the rest written out here.
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.engineer_duties import MATERIAL  # case-carburized steel, 1500 / 500 N/mm², named st
from tests.reference.rating_hand import Member, Pair, geometry, stiffness

J_GEAR = 0.4  # kg m²: the wheel's natural frequency with the mesh about 800 Hz, above both mesh frequencies
E_UM, ZETA = 4.0, 0.05
POINTS = (("a", 6000.0, 1500.0, 1500.0), ("b", 4000.0, 900.0, 1000.0))  # name, hours, output N·m, input rpm
SCENE = f"""
title = "spur 20/60, one harmonic of transmission error on a linear ISO mesh: a 1-DOF forced response"
contact = {{ stiffness = "iso6336", exponent = 1.0, damping_ratio = {ZETA}, transmission_error_um = [{E_UM}] }}
input = {{ speed_rpm = 1500, ramp_s = 0.05 }}
load = {{ torque_Nm = 1500, ramp_s = 0.05 }}
lubricant = {{ viscosity_40C_mm2_s = 220 }}
rating = {{ required_life_h = 10000 }}
simulation = {{ duration_s = 0.3, steps = 4000 }}
{MATERIAL}
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 0
accuracy_grade = 6
pinion = {{ teeth = 20, face_width_mm = 40, material = "st", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }}
gear   = {{ teeth = 60, face_width_mm = 40, material = "st", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10, inertia_kg_m2 = {J_GEAR} }}
""" + "".join(f'[[duty]]\nname = "{n}"\nhours = {h}\ntorque_Nm = {t}\nspeed_rpm = {s}\n' for n, h, t, s in POINTS)


def closed_form_k_v(torque_Nm: float, speed_rpm: float) -> float:
    member = Member(20, 40.0, "case_carburized", 1500.0, 500.0, 3.0, 10.0)
    q = Pair(p=member, g=Member(60, 40.0, "case_carburized", 1500.0, 500.0, 3.0, 10.0), mn=4.0, alpha_n_deg=20.0,
             beta_deg=0.0, grade=6, torque_pinion_Nm=torque_Nm / 3.0, n1_rpm=speed_rpm, k_a=1.0, nu40=220.0,
             life_h=1e4)
    g = geometry(q)
    line_load = torque_Nm / 3.0 * 1000.0 / (0.5 * g["d"][0]) / g["b"]  # F_t / b, above 100 N/mm: no low-load factor
    assert line_load > 100.0
    k = stiffness(q, g, line_load)["cga"] * g["b"] * 1e6  # N/m along the line of action (spur: β_b = 0)
    r_b2 = 0.5e-3 * g["db"][1]
    m_e = J_GEAR / r_b2 ** 2
    c = 2.0 * ZETA * math.sqrt(k * m_e)
    w = 2.0 * math.pi * 20 * speed_rpm / 60.0
    f_dyn = E_UM * 1e-6 * (k + 1j * w * c) * m_e * w ** 2 / (k - m_e * w ** 2 + 1j * w * c)
    return 1.0 + abs(f_dyn) / (torque_Nm / r_b2)


def _life(path, *args: str) -> dict:
    res = CliRunner().invoke(cli, ["-q", "life", str(path), "--format", "json", *args])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)["life"]


def test_dynamic_spectrum_is_the_one_dof_forced_response(tmp_path):
    path = tmp_path / "te.toml"
    path.write_text(SCENE)
    dynamic = _life(path)
    k_v = [closed_form_k_v(t, s) for _, _, t, s in POINTS]
    assert k_v[0] > 1.1 and k_v[1] > 1.05  # a dynamic increment worth counting
    # rtol 1e-5: the peaks of 128 output samples per mesh cycle miss the crest by at most (1 - cos(π/128)) of the
    # 15 % amplitude, 4e-5 of K_v, and the steady window still carries ringing below 1 %·e^(-ζωt)
    assert_allclose([p["K_v"][0] for p in dynamic["points"]], k_v, rtol=1e-5)
    sets = ["--set", "rating.dynamic_factor=1"]
    for i, (_, _, torque, _) in enumerate(POINTS):
        sets += ["--set", f"duty.{i}.torque_Nm={torque * k_v[i]!r}"]
    static = _life(path, "--static", *sets)
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            got, want = dynamic["stages"][0][member][mode], static["stages"][0][member][mode]
            assert_allclose(sum(b["cycles"] for b in got["bins"]), sum(b["cycles"] for b in want["bins"]), rtol=1e-12)
            # damage ∝ F^(k e) with k up to 50: K_v's 1e-5 moves it by up to 1e-3
            assert_allclose(got["damage"], want["damage"], rtol=2e-3)
