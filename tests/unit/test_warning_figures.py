"""A warning's figures read against the limit it names: never rounded onto the limit or across it, and a suggested
fix that clears the warning. References are hand calculations (ISO 21771 undercut limit, ISO 6336-1 c_γα), not the
code's output."""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

import pytest

from gearcli.config.schema import DesignFile
from gearcli.core.text import beside
from gearcli.design import compute_design

SIN20 = math.sin(math.radians(20.0))
H_FFP = 1.25 - 0.38 * (1.0 - SIN20)  # ISO 53 profile A's straight flank, 0.99997 m_n

# a spur pair z = 20 / 60, m_n = 4 mm, b = 40 mm, x = 0: d1 = 80 mm, speed drive 1000 rpm, 500 N·m on the output
BASE = {
    "title": "warning figures",
    "materials": {"steel": {"density_kg_m3": 7850, "youngs_modulus_MPa": 206000, "poisson_ratio": 0.3}},
    "stage": [{"normal_module_mm": 4, "normal_pressure_angle_deg": 20, "helix_angle_deg": 0,
               "pinion": {"teeth": 20, "face_width_mm": 40, "material": "steel"},
               "gear": {"teeth": 60, "face_width_mm": 40, "material": "steel"}}],
    "input": {"speed_rpm": 1000},
    "load": {"torque_Nm": 500},
    "simulation": {"duration_s": 0.1, "steps": 100},
}


def warnings_of(edit, check: str) -> list[str]:
    doc = copy.deepcopy(BASE)
    edit(doc)
    result = compute_design(DesignFile.model_validate(doc))
    return [d.message for d in result.diagnostics if d.data.get("check", d.code) == check]


def _pinion(**keys):
    return lambda d: d["stage"][0]["pinion"].update(keys)


# ------------------------------------------------------------------------------------------ the helper
@pytest.mark.parametrize(("x", "limit", "spec", "shown"), [
    (1.5004, 1.5, ".3g", "1.5004"),     # b/d1 just above 1.5: not "1.5 > 1.5"
    (14.018, 14, ".1f", "14.02"),       # an undercut limit just above z = 14: not "14 < 14.0"
    (0.79, 0.8, ".3g", "0.79"),         # far enough from the limit: the spec as given
    (2.03, 2.0, "+.1f", "+2.03"),       # a deviation beyond a ±2 % tolerance: not "+2.0 %"
    (-2.03, -2.0, "+.1f", "-2.03"),
    (1.2496, 1.25, ".3g", "1.2496"),    # a safety just below its minimum: not "1.25 below 1.25"
    (25.04, 25.0, "+.0f", "+25.04"),
])
def test_beside_keeps_the_figure_on_its_side_of_the_limit(x, limit, spec, shown):
    assert beside(x, limit, spec) == shown
    assert (float(shown) > limit) == (x > limit) and float(shown) != limit


# --------------------------------------------------------------------------------------------- design
def test_undercut_limit_and_suggested_shift_clear_the_warning():
    # z = 14 at x = 0.18: z_min = 2 (h_FfP* − x) / sin² 20° = 14.018; x_min = h_FfP* − 14 sin² 20° / 2 = 0.1811
    z_min = 2.0 * (H_FFP - 0.18) / SIN20 ** 2
    x_min = H_FFP - 14 * SIN20 ** 2 / 2.0
    assert 14.0 < z_min < 14.05 and 0.18 < x_min < 0.19
    (message,) = warnings_of(_pinion(teeth=14, profile_shift=0.18), "undercut")
    assert f"z_min = {z_min:.2f}" in message  # 14.02, not 14.0 beside z = 14
    assert "profile shift ≥ +0.19" in message  # x_min rounded up: +0.18 would leave the warning standing
    assert warnings_of(_pinion(teeth=14, profile_shift=0.19), "undercut") == []


def test_face_width_ratio_just_over_the_limit_is_written_over_it():
    def edit(d):
        d["stage"][0]["pinion"]["face_width_mm"] = d["stage"][0]["gear"]["face_width_mm"] = 120.1
    (message,) = warnings_of(edit, "face_width")
    assert f"b/d1 = 120.1/80 = {120.1 / 80:.4g} > 1.5" in message  # 1.501


def test_target_deviation_just_beyond_the_tolerance_is_written_beyond_it():
    # output 1000 / 3 = 333.33 rpm against 326.7 rpm: +2.03 %, tolerance ±2 %
    deviation = 100.0 * (1000.0 / 3.0 - 326.7) / 326.7
    (message,) = warnings_of(lambda d: d.update(target={"output_speed_rpm": 326.7, "tolerance_percent": 2}),
                             "target_speed")
    assert f"by {deviation:+.2f} % (tolerance ±2 %)" in message


def test_stiffness_departure_just_over_25_percent_is_written_over_it():
    # ISO 6336-1 by hand: q′ = C1 + C2/20 + C3/60, c′ = 0.8 C_B / q′ (C_B = 0.975 for h_fP = 1.25 m_n, 20°),
    # F_t/b = 104 N/mm (no low-load factor); ε_α = 1.6708 (x = 0, z 20/60); c_γα = c′ (0.75 ε_α + 0.25)
    eps = ((math.sqrt(44.0 ** 2 - (40.0 * math.cos(math.radians(20))) ** 2)
            + math.sqrt(124.0 ** 2 - (120.0 * math.cos(math.radians(20))) ** 2) - 160.0 * SIN20)
           / (4.0 * math.pi * math.cos(math.radians(20))))
    c_prime = 0.8 * 0.975 / (0.04723 + 0.15551 / 20 + 0.25791 / 60)
    k_n = c_prime * (0.75 * eps + 0.25) * 40 * 1000.0  # N/mm
    assert k_n == pytest.approx(7.9078e5, rel=1e-4)
    (message,) = warnings_of(lambda d: d.update(contact={"stiffness": 1.2502 * k_n, "exponent": 1}),
                             "stiffness_not_iso")
    assert "+25.02 % from ISO" in message
    assert warnings_of(lambda d: d.update(contact={"stiffness": 1.2498 * k_n, "exponent": 1}),
                       "stiffness_not_iso") == []


def _figure_after(message: str, lead: str) -> float:
    return float(message.split(lead, 1)[1].split()[0])


def test_a_safety_a_hair_below_its_minimum_is_written_below_it():
    # a property of the message, whatever S_F is: with the minimum 1e-5 above it, a 3-digit S_F reads as the minimum
    path = Path(__file__).resolve().parents[2] / "configs" / "industrial_two_stage_rated.toml"
    doc = tomllib.loads(path.read_text())
    s_f = compute_design(DesignFile.model_validate(doc)).stages[0].rating.pinion.S_F
    doc["rating"]["min_safety_bending"] = minimum = round(s_f * (1.0 + 1e-5), 9)
    (message,) = [d.message for d in compute_design(DesignFile.model_validate(doc)).diagnostics
                  if d.data.get("mode") == "bending" and d.data.get("stage") == 1 and d.data.get("member") == "pinion"]
    shown = _figure_after(message, "S_F = ")
    assert shown < minimum and f"{shown:.3g}" == f"{minimum:.3g}"  # the 3-digit figure would have sat on it


def test_a_pointed_tooth_names_where_its_flanks_meet_and_the_contact_ratio_there():
    # z = 10, x = +1.3 against z = 60, x = −1.3 (a_w = a = 140 mm, α_w = 20°): the flanks meet where
    # inv α_p = (π/2 + 2 x tan α)/z + inv α (ISO 21771 tooth thickness = 0), d_p = d_b / cos α_p = 55.86 mm, below
    # d_a = 58.4 mm; contact ends there, so ε_α = (√(r_p² − r_b1²) + √(r_a2² − r_b2²) − a sin α) / p_b = 0.861, not the
    # 1.004 the tip circle gives
    def inv(a):
        return math.tan(a) - a
    alpha, target = math.radians(20.0), (math.pi / 2 + 2 * 1.3 * math.tan(math.radians(20.0))) / 10 + inv(math.radians(20.0))
    lo, hi = 0.1, 1.5
    for _ in range(200):  # bisection on the increasing inv α
        lo, hi = (0.5 * (lo + hi), hi) if inv(0.5 * (lo + hi)) < target else (lo, 0.5 * (lo + hi))
    d_p = 40.0 * math.cos(alpha) / math.cos(lo)
    r_b1, r_b2, r_a2 = 20.0 * math.cos(alpha), 120.0 * math.cos(alpha), 0.5 * (240.0 + 2 * 4 * (1 - 1.3))
    eps = ((math.sqrt((d_p / 2) ** 2 - r_b1 ** 2) + math.sqrt(r_a2 ** 2 - r_b2 ** 2) - 140.0 * math.sin(alpha))
           / (4 * math.pi * math.cos(alpha)))
    assert d_p == pytest.approx(55.86, abs=0.01) and eps == pytest.approx(0.861, abs=1e-3)

    def edit(d):
        d["stage"][0]["pinion"].update(teeth=10, profile_shift=1.3)
        d["stage"][0]["gear"]["profile_shift"] = -1.3
    (message,) = warnings_of(edit, "tip_thickness")
    assert f"the flanks meet at d = {d_p:.4g} mm" in message
    assert f"the transverse contact ratio is {eps:.3f} (< 1" in message
