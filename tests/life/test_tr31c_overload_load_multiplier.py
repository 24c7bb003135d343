"""The spectrum safety of a gross overload: the load multiplier that makes D = 1 is found wherever it lies (docs/life.md,
"Damage"), and it keeps the relation a load spectrum's torque x k must give: the multiplier on the force / k.

The defect, in ``gearcli.life.miner.spectrum_safety``: the root find on ln s stopped at its first bracket [1e-3, 1e3]
and returned s = 1e-3 for a spectrum already past D = 1 there. The helical pair below (31/31, m_n 4, 60 mm) at 5e7 N m
over 20,000 h, 100 x a 5e5 N m point whose multiplier is 6.0e-3 on the flank and 1.08e-2 on the root, reported 0.001
for both modes: a stress safety of 0.032 where D = 1 needs 0.0078 on the flank, 1e-3 where the root's is 1.1e-4.

Reference (by hand): one load class of stress sigma and n cycles (the test's point: 0.01 h at 1500 rpm, 900 cycles,
below both static nodes) on the case-carburized curves of ISO 6336-2/-3:2006 (Z_NT 1.6 at 1e5, 1 at 5e7; Y_NT 2.5
at 1e3, 1 at 3e6), the finite-life slope extrapolated above the static node as docs/life.md says:
sigma_curve(n) = sigma_inf y0 (N0 / n)^(1/k), k = ln(N_knee / N0) / ln(y0); D = 1 at the bending multiplier
sigma_curve / sigma (sigma_F ∝ F) and the pitting one (sigma_curve / sigma)^2 (sigma_H ∝ sqrt(F)).
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from tests.life.engineer_duties import MATERIAL, YNT_CASE, ZNT_CASE, run_life

SCENE = MATERIAL + """
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
accuracy_grade = 6
pinion = { teeth = 31, face_width_mm = 60, hand = "left",  material = "st", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12 }
gear   = { teeth = 31, face_width_mm = 60, hand = "right", material = "st", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12 }

[input]
speed_rpm = 1500

[load]
torque_Nm = 900

[lubricant]
viscosity_40C_mm2_s = 220

[rating]
required_life_h = 0.01

[[duty]]
name = "overload"
hours = 0.01
torque_Nm = TORQUE
speed_rpm = 1500
"""

NODES = {"pitting": ZNT_CASE, "bending": YNT_CASE}


def _hand_multiplier(mode: str, stress: float, endurance: float, cycles: float) -> float:
    (n0, y0), (n1, y1), _ = NODES[mode]
    k = math.log(n1 / n0) / math.log(y0 / y1)
    curve = endurance * y0 * (n0 / cycles) ** (1.0 / k)  # the finite-life branch at n (extrapolated above N0)
    return (curve / stress) ** 2 if mode == "pitting" else curve / stress


def _life(tmp_path, torque: float) -> dict:
    return run_life(tmp_path, SCENE.replace("TORQUE", repr(torque)), "--static")["life"]["stages"][0]


def test_an_overload_multiplier_below_the_first_bracket(tmp_path) -> None:
    base, over = _life(tmp_path, 5e5), _life(tmp_path, 5e7)
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            got = over[member][mode]
            (b,) = got["bins"]
            hand = _hand_multiplier(mode, b["stress_MPa"], b["endurance_MPa"], b["cycles"])
            assert hand < 1e-3  # 6.0e-5 and 1.1e-4: past the first bracket's end
            assert_allclose(got["load_multiplier"], hand, rtol=1e-9)  # was 1e-3
            assert_allclose(got["stress_safety"], math.sqrt(hand) if mode == "pitting" else hand, rtol=1e-9)
            # the relation: torque x 100 -> the multiplier on the force / 100, to what ISO 6336-1's load-dependent
            # factors still move between the two loads (K_v's B_p, B_f, B_k fall with the line load: 3.2e-4 here)
            assert_allclose(got["load_multiplier"] * 100.0, base[member][mode]["load_multiplier"], rtol=1e-3)
