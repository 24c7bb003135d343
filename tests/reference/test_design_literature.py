"""Worked examples from the literature, each with its published numbers and tolerances set by the
digits published (and, where noted, by a documented difference of convention).

1. SDP/SI, "Elements of Metric Gear Technology" (the KHK gear technical reference in its SDP/SI
   edition), section 11.1, Table 11-1, "An example of helical gear" (page T-109,
   http://www.sdp-si.com/D785/HTML1/D785T108_2.html): m_n = 3, α_n = 20°, β = 30°, z = 12/60,
   x = +0.09809/0, a_x = 125, α_t = 22.79588°, α_wt = 23.1126°, m_t = 3.46410, d_a = 48.153/213.842,
   d_b = 38.322/191.611, ε_α = 1.2939.
2. An ISO 21771:2007 profile-shift calculation ("Gear Generating Profile Shift Calculations", scribd
   document 376176518): m_n = 3.5, α_n = 20°, z = 31/30, reference a = 114.3447280708 mm (so β = 21°),
   working a_w = 116.5 mm, α_t = 21.2990642859°, α_wt = 23.8707609654°, x1 + x2 = 0.651877131252
   (ISO 21771 eq. 62), x1 = 0.291.
3. D-Soft CylGear geometry output example (http://dsoftcon.be/CylGear/en/GeometryOutputHtml.htm):
   m_n = 4, z = 21/66, b = 60, β = 14° right/left, x = 0.494/0.487, a = 183.000, m_t = 4.1224,
   d = 86.572/272.082, d_b = 81.057/254.749, α_t = 20.56171°, α_wt = 23.43655°, ε_β = 1.155,
   F_a/F_t = 0.249.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design


def one_stage(m_n, beta_deg, teeth, shifts, widths=(30.0, 30.0), hands=("right", "left"), alpha_n=20.0):
    doc = {
        "stage": [{
            "normal_module_mm": m_n, "normal_pressure_angle_deg": alpha_n, "helix_angle_deg": beta_deg,
            "pinion": {"teeth": teeth[0], "face_width_mm": widths[0], "hand": hands[0], "profile_shift": shifts[0]},
            "gear": {"teeth": teeth[1], "face_width_mm": widths[1], "hand": hands[1], "profile_shift": shifts[1]},
        }],
        "input": {"speed_rpm": 1000.0},
        "load": {"torque_Nm": 100.0},
    }
    return compute_design(DesignFile.model_validate(doc)).stages[0]


def test_sdp_si_table_11_1_helical_example():
    s = one_stage(3.0, 30.0, (12, 60), (0.09809, 0.0))
    assert_allclose(s.transverse_pressure_angle_deg, 22.79588, rtol=5e-7)  # 7 digits published
    assert_allclose(s.working_pressure_angle_deg, 23.1126, rtol=5e-6)  # 6 digits published
    assert_allclose(s.transverse_module_mm, 3.46410, rtol=5e-6)
    # a_x = 125: x1 = 0.09809 is itself rounded to 4 significant digits, hence 1e-6
    assert_allclose(s.center_distance_mm, 125.0, rtol=1e-6)
    assert_allclose([s.pinion.base_diameter_mm, s.gear.base_diameter_mm], [38.322, 191.611], rtol=2e-5)
    # SDP/SI shortens the tips (h_a1 = (1 + y − x2) m_n with y = 0.09744), as gearcli does (ISO 21771 tip
    # alteration k = y − Σx): 48.1539 and 213.8422 printed as 48.153 and 213.842 (3 decimals, truncated)
    assert_allclose([s.pinion.tip_diameter_mm, s.gear.tip_diameter_mm], [48.153, 213.842], atol=1e-3)
    assert_allclose(s.contact_ratio_transverse, 1.2939, rtol=4e-5)  # 4 decimals printed


def test_iso21771_profile_shift_sum_gives_the_working_centre_distance():
    x_sum = 0.651877131252
    s = one_stage(3.5, 21.0, (31, 30), (0.291, x_sum - 0.291))
    assert_allclose(s.transverse_pressure_angle_deg, 21.2990642859, rtol=1e-10)  # 12 digits published
    # inverse of ISO 21771 eq. 62: our Newton solve of inv α_wt must land on their α_wt and a_w
    assert_allclose(s.working_pressure_angle_deg, 23.8707609654, rtol=1e-10)
    assert_allclose(s.center_distance_mm, 116.5, rtol=1e-10)
    # reference a = (d1 + d2)/2 = 3.5 · 61 / (2 cos 21°) = 114.3447280708, recovered from a_w
    a_ref = s.center_distance_mm * math.cos(math.radians(23.8707609654)) / math.cos(math.radians(21.2990642859))
    assert_allclose(a_ref, 114.3447280708, rtol=1e-10)


def test_dsoft_cylgear_example():
    s = one_stage(4.0, 14.0, (21, 66), (0.494, 0.487), widths=(60.0, 60.0))
    assert_allclose(s.transverse_module_mm, 4.1224, rtol=2e-5)
    assert_allclose([s.pinion.pitch_diameter_mm, s.gear.pitch_diameter_mm], [86.572, 272.082], rtol=1e-5)
    assert_allclose([s.pinion.base_diameter_mm, s.gear.base_diameter_mm], [81.057, 254.749], rtol=1e-5)
    assert_allclose(s.transverse_pressure_angle_deg, 20.56171, rtol=1e-6)
    # α_wt and a: the published shifts are rounded to 3 decimals (x1 + x2 = 0.981 ± 0.001)
    assert_allclose(s.working_pressure_angle_deg, 23.43655, rtol=5e-6)
    assert_allclose(s.center_distance_mm, 183.000, rtol=1e-6)
    assert_allclose(s.overlap_ratio, 1.155, rtol=5e-4)
    assert_allclose(s.static_force_N.axial / s.static_force_N.tangential, 0.249, rtol=2e-3)  # 3 digits
    # their ε_α = 1.397 with the tips truncated by k = −0.063 m_n: see tests/reference/test_design_iso6336.py
