"""docs/life.md, "Dynamic route": the run is lengthened until its steady window holds 40 whole mesh cycles of the
slowest mesh. A window exactly 40 periods long held 39 (the cycle its end cuts off is not counted: mesh_cycle_peaks),
as `gearcli life` on a two-stage reducer showed (`points[i].mesh_cycles` [157, 39]).

By hand, for the two stages below at 1450 rpm: stage 1 meshes at 19 · 1450/60 = 459.17 Hz, stage 2 (its pinion at
1450 · 19/75 = 367.33 rpm) at 19 · 367.33/60 = 116.32 Hz, the slowest: 40 whole cycles need a window of at least
40/116.32 = 0.344 s, in which stage 1 turns 40 · 459.17/116.32 = 157.9 of its cycles.
"""

from __future__ import annotations

from tests.life.engineer_duties import MATERIAL, run_life

ROUGH = 'material = "st", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10'
STAGES = [(3, ("left", 19, 50, 0.3), ("right", 75, 45, 0.0)), (5, ("right", 19, 80, 0.35), ("left", 68, 75, 0.2))]


def _member(hand: str, teeth: int, width: float, shift: float) -> str:
    return f'{{ teeth = {teeth}, face_width_mm = {width}, hand = "{hand}", profile_shift = {shift}, {ROUGH} }}'


SCENE = "stage = [\n" + "".join(
    f"  {{ normal_module_mm = {m}, helix_angle_deg = 12, accuracy_grade = 6, pinion = {_member(*p)}, "
    f"gear = {_member(*g)} }},\n" for m, p, g in STAGES) + """]
input = { speed_rpm = 1450, ramp_s = 0.05 }
load = { torque_Nm = 1340, ramp_s = 0.05 }
contact = { stiffness = "iso6336", exponent = 1.0, damping_ratio = 0.05 }
lubricant = { viscosity_40C_mm2_s = 220 }
rating = { required_life_h = 1000 }
simulation = { duration_s = 0.1 }
duty = [{ name = "rated", hours = 1000, torque_Nm = 1340, speed_rpm = 1450 }]
""" + MATERIAL


def test_the_slowest_mesh_gets_forty_whole_cycles(tmp_path):
    f1, f2 = 19 * 1450 / 60.0, 19 * (1450 * 19 / 75) / 60.0
    assert abs(f2 - 116.32) < 0.01
    (point,) = run_life(tmp_path, SCENE)["life"]["points"]
    c1, c2 = point["mesh_cycles"]
    assert c2 >= 40, point["mesh_cycles"]
    assert c1 >= int(40 * f1 / f2), point["mesh_cycles"]  # 157 whole cycles of stage 1 in 40 of stage 2
    lo, hi = point["solver"]["window_s"]
    assert hi - lo >= 40 / f2
