"""`gearcli design` at the edges of a parallel stage, against figures worked by hand (ISO 21771, ISO 53 profile A):
β = 0 exactly, a 1:1 stage, and 8-10 tooth pinions (undercut and interference).

Hand figures used below (α_n = 20°, ISO 53 profile A: h_aP* = 1, h_fP* = 1.25, ρ_fP* = 0.38):
- the rack's straight flank ends h_FfP* = 1.25 − 0.38 (1 − sin 20°) = 0.999968 m_n above the datum, so a spur pinion
  is undercut below x_min = h_FfP* − z sin² 20° / 2: 0.532057 (z = 8), 0.473568 (z = 9), 0.415079 (z = 10), and
  z_min = 2 h_FfP* / sin² 20° = 17.0967 at x = 0; helical, β = 30°: tan α_t = tan 20° / cos 30°, α_t = 22.7959°,
  sin² α_t = 0.150117, x_min = h_FfP* − 8 sin² α_t / (2 cos 30°) = 0.306607, z_min = 2 h_FfP* cos 30° / sin² α_t
  = 11.5376;
- spur 20/40, m = 3, x = 0: r_a = 33 / 63, r_b = 28.19078 / 56.38156, a = 90,
  ε_α = (√(33² − r_b1²) + √(63² − r_b2²) − 90 sin 20°) / (3π cos 20°) = 1.635186;
- spur 8/40, m = 2, x = 0: the pinion's involute would start q = 8 sin 20° − 2 h_FfP* / sin 20° = −3.1113 mm from its base
  tangent point T1 (undercut: no lower than T1); the gear's tip starts contact at 48 sin 20° − √(42² − (40 cos 20°)²)
  = −2.3224 mm, beyond T1: interference 2.3224 mm deep, usable path T1 → pinion tip = √(10² − (8 cos 20°)²) = 6.5945 mm,
  usable ε_α = 6.5945 / (2π cos 20°) = 1.116894.
"""

from __future__ import annotations

import math

import pytest
import tomli_w
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.io import serialize


def design(tmp_path, stage: dict, torque_Nm: float = 100.0) -> dict:
    doc = {"title": "edge", "stage": [stage], "input": {"speed_rpm": 1000.0}, "load": {"torque_Nm": torque_Nm}}
    path = tmp_path / "edge.toml"
    path.write_bytes(tomli_w.dumps(doc).encode())
    return serialize.design_dict(api.design(api.load(str(path))))


def spur(z1: int, z2: int, m: float, x1: float = 0.0, x2: float = 0.0, **extra) -> dict:
    return {"normal_module_mm": m, "normal_pressure_angle_deg": 20.0, "helix_angle_deg": 0.0,
            "pinion": {"teeth": z1, "face_width_mm": 10 * m, "profile_shift": x1, **extra},
            "gear": {"teeth": z2, "face_width_mm": 10 * m, "profile_shift": x2, **extra}}


def checks(js: dict, check: str) -> list[dict]:
    return [w for w in js["warnings"] if w.get("check") == check]


@pytest.mark.parametrize("hand", [None, "spur"])
def test_beta_zero_exactly_is_a_spur_pair(tmp_path, hand):
    extra = {} if hand is None else {"hand": hand}
    js = design(tmp_path, spur(20, 40, 3.0, **extra))
    s = js["stages"][0]
    assert s["helix_angle_deg"] == 0.0 and s["base_helix_angle_deg"] == 0.0 and s["overlap_ratio"] == 0.0
    assert s["transverse_module_mm"] == 3.0 and s["transverse_pressure_angle_deg"] == pytest.approx(20.0, abs=1e-13)
    assert_allclose([s["center_distance_mm"], s["contact_ratio_transverse"], s["contact_ratio_total"]],
                    [90.0, 1.635186, 1.635186], rtol=1e-6)
    f = s["static_force_N"]  # T_1 = 100 N·m / 2 on r_1 = 30 mm
    assert_allclose([f["tangential"], f["radial"], f["normal"]],
                    [50e3 / 30, 50e3 / 30 * math.tan(math.radians(20)), 50e3 / 30 / math.cos(math.radians(20))],
                    rtol=1e-12)
    assert f["axial"] == 0.0
    assert not checks(js, "spur_hand") and not checks(js, "axial_forces_add")


def test_a_hand_on_a_spur_pair_is_a_warning(tmp_path):
    js = design(tmp_path, spur(20, 40, 3.0) | {"pinion": {"teeth": 20, "face_width_mm": 30.0, "hand": "left"},
                                               "gear": {"teeth": 40, "face_width_mm": 30.0, "hand": "right"}})
    assert [w["stage"] for w in checks(js, "spur_hand")] == [1]
    assert js["stages"][0]["static_force_N"]["axial"] == 0.0


def test_a_one_to_one_stage(tmp_path):
    """z 20/20: ratio 1, the same speed and (lossless) torque on both members, and ISO's c′ independent of which
    member carries which shift (equal counts: the smaller shift is index 1 either way)."""
    a = design(tmp_path, spur(20, 20, 4.0, 0.3, 0.1))["stages"][0]
    b = design(tmp_path, spur(20, 20, 4.0, 0.1, 0.3))["stages"][0]
    assert a["ratio"] == 1.0
    assert a["pinion"]["speed_rpm"] == a["gear"]["speed_rpm"] == 1000.0
    assert_allclose(a["pinion"]["torque_Nmm"], a["gear"]["torque_Nmm"], rtol=1e-15)
    for key in ("iso6336_single_pair_stiffness_N_mm_um", "iso6336_mesh_stiffness_N_mm_um", "center_distance_mm",
                "contact_ratio_transverse", "working_pressure_angle_deg"):
        assert_allclose(a[key], b[key], rtol=1e-13, err_msg=key)
    # q′ by hand, index 1 = x 0.1 (z_n = 20): 0.04723 + 0.15551/20 + 0.25791/20 − 0.00635·0.1 − 0.11654·0.1/20
    # − 0.00193·0.3 − 0.24188·0.3/20 + 0.00529·0.01 + 0.00182·0.09
    q = (0.04723 + 0.15551 / 20 + 0.25791 / 20 - 0.00635 * 0.1 - 0.11654 * 0.1 / 20 - 0.00193 * 0.3
         - 0.24188 * 0.3 / 20 + 0.00529 * 0.01 + 0.00182 * 0.09)
    load = 100e3 / 40.0 / 40.0  # F_t / b = (100 N·m on r = 40 mm) / 40 mm = 62.5 N/mm < 100: ISO's correction
    assert_allclose(a["iso6336_single_pair_stiffness_N_mm_um"], 0.8 * 0.975 / q * (load / 100) ** 0.25, rtol=1e-12)


@pytest.mark.parametrize(("z", "x_min"), [(8, 0.532057), (9, 0.473568), (10, 0.415079)])
def test_small_spur_pinions_warn_undercut_below_the_hand_limit(tmp_path, z, x_min):
    cut = checks(design(tmp_path, spur(z, 40, 2.0)), "undercut")
    assert [w["member"] for w in cut] == ["pinion"]
    assert_allclose([cut[0]["min_profile_shift"], cut[0]["min_teeth"]], [x_min, 17.0967], atol=1e-6, rtol=1e-5)
    assert not checks(design(tmp_path, spur(z, 40, 2.0, x_min + 0.005)), "undercut")
    assert checks(design(tmp_path, spur(z, 40, 2.0, x_min - 0.005)), "undercut")


def test_a_helical_eight_tooth_pinion_has_the_helical_limit(tmp_path):
    stage = spur(8, 40, 2.0) | {"helix_angle_deg": 30.0}
    stage["pinion"] |= {"hand": "left"}
    stage["gear"] |= {"hand": "right"}
    cut = checks(design(tmp_path, stage), "undercut")
    assert_allclose([cut[0]["min_profile_shift"], cut[0]["min_teeth"]], [0.306607, 11.5376], atol=1e-6, rtol=1e-5)


def test_an_eight_tooth_pinion_meets_the_gear_tip_in_its_undercut(tmp_path):
    hit = checks(design(tmp_path, spur(8, 40, 2.0)), "interference")
    assert [w["member"] for w in hit] == ["pinion"]
    assert hit[0]["form_diameter_mm"] is None  # undercut: no involute form circle above the base circle
    assert_allclose([hit[0]["depth_mm"], hit[0]["contact_ratio_transverse_usable"]], [2.32242, 1.116894], rtol=1e-5)


def test_the_design_table_shows_both_members_diameters(tmp_path):
    """Spur 20/40, m = 3, x = 0: the gear's d_b2 = 120 cos 20° = 112.76, d_a2 = 120 + 2·3 = 126, d_f2 = 120 − 2.5·3 =
    112.5 beside the pinion's 56.382, 66, 52.5 (the table printed the pinion's alone)."""
    from gearcli.io.tables import design_tables

    path = tmp_path / "edge.toml"
    path.write_bytes(tomli_w.dumps({"title": "edge", "stage": [spur(20, 40, 3.0)], "input": {"speed_rpm": 1000.0},
                                    "load": {"torque_Nm": 100.0}}).encode())
    geometry = design_tables(api.design(api.load(str(path))))[0]
    rows = {label.strip(): cells[0] for label, cells in geometry.rows}
    assert [float(rows[k]) for k in ("pinion base d_b1 [mm]", "gear base d_b2 [mm]", "pinion tip d_a1 [mm]",
                                     "gear tip d_a2 [mm]", "pinion root d_f1 [mm]", "gear root d_f2 [mm]")] \
        == pytest.approx([56.382, 112.76, 66.0, 126.0, 52.5, 112.5], rel=1e-4)
