"""The first mesh cycle of a span is a whole tooth engagement and is counted (tr11a): a DOL start meets its
largest tooth force within the first tooth pitch of the pinion's turn (the motor's locked-rotor torque winds the
coupling before the train has turned 1/z of a revolution), and the start's spectrum dropped that cycle: its top
class stood at 8724 N where the start peaked at 9367 N."""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose

from gearcli.life.spectra import mesh_cycle_peaks
from tests.life.engineer_duties import MATERIAL, run_life

# a 15 kW four-pole DOL motor (rotor on an elastic coupling) on one helical stage 21/83, a drum on its coupling
SCENE = """
input = { speed_rpm = 1460, drive = "motor", inertia_kg_m2 = 0.09, coupling_stiffness_Nm_rad = 2.0e4, coupling_damping_Nms_rad = 5, motor = { rated_power_kW = 15, rated_speed_rpm = 1460, synchronous_speed_rpm = 1500, breakdown_torque_ratio = 2.8, locked_rotor_torque_ratio = 2.3 } }
load = { torque_Nm = 300, inertia_kg_m2 = 2.0, coupling_stiffness_Nm_rad = 5e4, coupling_damping_Nms_rad = 20 }
lubricant = { viscosity_40C_mm2_s = 220 }
rating = { required_life_h = 6000 }
simulation = { duration_s = 1.0 }
""" + MATERIAL + """
[[stage]]
normal_module_mm = 3
helix_angle_deg = 15
accuracy_grade = 6
pinion = { teeth = 21, face_width_mm = 40, hand = "left", material = "st", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12 }
gear = { teeth = 83, face_width_mm = 38, hand = "right", material = "st", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12 }
[[duty]]
name = "full"
hours = 6000
torque_Nm = 300
speed_rpm = 1460
starts = 20000
"""


def test_cycle_peaks_by_hand_count_the_first_cycle_and_drop_the_cut_last_one():
    # 3 teeth, the angle rising linearly through 2.5 mesh cycles: cycles [0, 1) and [1, 2) are whole, [2, 2.5) is cut
    t = np.linspace(0.0, 1.0, 101)
    angle = 2.5 * (2.0 * math.pi / 3) * t
    ft = np.zeros_like(t)
    ft[10], ft[50], ft[90] = 7.0, -5.0, 9.0  # phase 0.25 (cycle 0), 1.25 (cycle 1; |F_t| counts), 2.25 (cut off)
    assert_allclose(mesh_cycle_peaks(t, ft, angle, 3), [7.0, 5.0])
    # one whole cycle and a cut one: the whole one counts
    assert_allclose(mesh_cycle_peaks(t[:61], ft[:61], angle[:61], 3), [7.0])
    # no whole cycle: nothing
    assert mesh_cycle_peaks(t[:30], ft[:30], angle[:30], 3).size == 0


def test_a_dol_start_counts_its_largest_tooth_force(tmp_path):
    life = run_life(tmp_path, SCENE)["life"]
    start = life["points"][0]["start"]
    peak = start["peak_tangential_N"][0]
    # the locked-rotor torque 2.3 x 98.1 N m over the pinion's pitch radius alone is 6.9 kN; the coupling's wind-up
    # overshoots it: the peak lies far above the static 2.33 kN, within the first tooth pitch of the pinion
    assert peak > 2.3 * 15e3 / (1460 * math.pi / 30) / (0.5 * 21 * 3 / math.cos(math.radians(15)) * 1e-3)
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            own = [b["force_N"] for b in life["stages"][0][member][mode]["bins"] if b["point"] == "full (start)"]
            # each class stands at its largest force: the top class is the start's largest engagement, its peak
            assert_allclose(max(own), peak, rtol=1e-12)
