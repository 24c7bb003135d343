"""ISO 21771 geometry formulas one by one, against table values and hand calculations."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.design import geometry as g


def test_involute_table_values():
    # classical involute tables: inv 20° = 0.014904, inv 25° = 0.029975, inv 14.5° = 0.0055448
    assert_allclose([g.involute(math.radians(a)) for a in (20.0, 25.0, 14.5)], [0.014904, 0.029975, 0.0055448],
                    rtol=5e-5)  # 5 significant digits in the tables


@pytest.mark.parametrize("alpha_deg", [0.5, 5.0, 14.5, 20.0, 23.1126, 35.0, 50.0, 70.0, 85.0])
def test_inverse_involute_round_trip(alpha_deg):
    alpha = math.radians(alpha_deg)
    # Newton converges to machine precision; tan α − α itself loses digits to cancellation at small α
    # (inv 0.5° ≈ 1.3e-8 from terms of 8.7e-3), which bounds the round trip near 1e-11 there
    assert_allclose(g.inverse_involute(g.involute(alpha)), alpha, rtol=1e-10)


def test_inverse_involute_of_the_table_value():
    # inv α = 0.014904 -> α = 20.000° to the table's 5 digits
    assert_allclose(math.degrees(g.inverse_involute(0.014904)), 20.0, rtol=5e-5)


def test_inverse_involute_refuses_non_positive_values():
    for bad in (0.0, -1e-3, float("nan")):
        with pytest.raises(ValueError):
            g.inverse_involute(bad)


def test_spur_gear_reduces_to_the_spur_formulas():
    # β = 0: m_t = m_n, α_t = α_n, β_b = 0, ε_β = 0
    assert_allclose(g.transverse_module_mm(4.0, 0.0), 4.0, rtol=1e-15)
    assert_allclose(g.transverse_pressure_angle_rad(math.radians(20.0), 0.0), math.radians(20.0), rtol=1e-15)
    assert g.base_helix_angle_rad(0.0, math.radians(20.0)) == 0.0  # tan 0 = 0 exactly, not a float comparison
    assert g.overlap_ratio(50.0, 0.0, 4.0) == 0.0  # sin 0 = 0 exactly


def test_spur_pair_by_hand():
    # m = 5, α = 20°, z = 20/40, x = 0: d = 100/200, d_b = 93.9693/187.9385, d_a = 110/210, d_f = 87.5/187.5
    p = g.pair_geometry(5.0, 20.0, 0.0, (20, 40), (0.0, 0.0), (40.0, 40.0))
    assert_allclose(p.pitch_diameter_mm, (100.0, 200.0), rtol=1e-14)
    assert_allclose(p.base_diameter_mm, (93.9693, 187.9385), rtol=1e-6)
    assert_allclose(p.tip_diameter_mm, (110.0, 210.0), rtol=1e-14)
    assert_allclose(p.root_diameter_mm, (87.5, 187.5), rtol=1e-14)
    assert_allclose(p.center_distance_mm, 150.0, rtol=1e-14)  # x1 + x2 = 0: a_w = a
    # √(55² − 46.98463²) = √(3025 − 2207.556) = √817.444 = 28.59099
    # √(105² − 93.96926²) = √(11025 − 8830.220) = √2194.780 = 46.84846
    # a sin α = 150 · 0.342020 = 51.30302; p_b = 5 π cos 20° = 14.76066
    # ε_α = (28.59099 + 46.84846 − 51.30302) / 14.76066 = 24.13643 / 14.76066 = 1.63519
    assert_allclose(p.contact_ratio_transverse, 1.63519, rtol=5e-6)
    assert_allclose(p.transverse_base_pitch_mm, 14.76066, rtol=5e-7)


def test_profile_shift_changes_tip_and_root_by_2xm():
    # x = +0.5, m_n = 4: d_a = d + 2·4·1.5 = d + 12, d_f = d − 10 + 4 = d − 6
    d = 80.0
    assert_allclose(g.tip_diameter_mm(d, 4.0, 0.5), 92.0, rtol=1e-15)
    assert_allclose(g.root_diameter_mm(d, 4.0, 0.5), 74.0, rtol=1e-15)


def test_zero_shift_sum_keeps_the_reference_centre_distance():
    # x1 = −x2 (V-zero): inv α_wt = inv α_t, so a_w = a = m_n (z1+z2)/(2 cos β) = 270 / 1.931852 = 139.7623
    p = g.pair_geometry(3.0, 20.0, 15.0, (25, 65), (0.4, -0.4), (30.0, 30.0))
    assert_allclose(p.center_distance_mm, 139.7623, rtol=5e-7)
    assert_allclose(p.working_pressure_rad, p.transverse_pressure_rad, rtol=1e-12)


def test_undercut_limit_spur_20_deg_is_17_1():
    # z_min = 2 / sin² 20° = 2 / 0.116978 = 17.097 (the textbook 17 teeth)
    assert_allclose(g.undercut_limit_teeth(0.0, 0.0, math.radians(20.0)), 17.097, rtol=5e-5)
    # x = 0.5 halves it: 2 · 0.5 / 0.116978 = 8.549
    assert_allclose(g.undercut_limit_teeth(0.5, 0.0, math.radians(20.0)), 8.549, rtol=5e-5)


def test_tip_thickness_of_a_standard_spur_tooth_by_hand():
    # z = 20, m = 5, x = 0: s = π m / 2 = 7.85398, d = 100, d_a = 110, cos α_a = 93.9693/110 = 0.854266,
    # α_a = 31.3213°, inv α_a = tan 31.3213° − 0.546659 = 0.608518 − 0.546659 = 0.0618587
    # s_a = 110 (0.0785398 + 0.0149044 − 0.0618587) = 110 · 0.0315855 = 3.47440 mm
    s_a = g.normal_tip_thickness_mm(20, 5.0, 0.0, 0.0, math.radians(20.0), 110.0)
    assert_allclose(s_a, 3.47440, rtol=5e-5)


@pytest.mark.parametrize("shifts, part", [((-1.5, -1.5), "pinion"), ((-1.2, 0.0), "pinion")])
def test_infeasible_pairs_are_refused_with_the_key_to_blame(shifts, part):
    with pytest.raises(g.InfeasibleGeometry) as err:
        g.pair_geometry(5.0, 20.0, 0.0, (6, 6), shifts, (30.0, 30.0))
    assert err.value.part == part and err.value.field == "profile_shift"


def test_root_below_zero_is_refused():
    # z = 5, m = 5, β = 0, x = −1.3: d_f = 25 − 12.5 − 13 = −0.5 ≤ 0 (the partner's x = +1.3 keeps
    # inv α_wt positive, so the root is what fails)
    with pytest.raises(g.InfeasibleGeometry, match="root diameter"):
        g.pair_geometry(5.0, 20.0, 0.0, (5, 200), (-1.3, 1.3), (30.0, 30.0))
