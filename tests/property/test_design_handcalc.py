"""`gearcli design` against an independent textbook implementation, over random trains (hypothesis).

Everything the design prints per stage is recomputed here from the formulas of DESIGN.md §3/§7/§13 and
ISO 21771 / ISO 6336-1, written out without calling gearcli's own helpers: kinematics and torques down the
train (T_p = T_g / (i η) with power flowing to the load, T_p = T_g η / i when the load drives back), the
helical geometry with profile shift (working pressure angle by Newton on the involute, tip alteration,
tips and roots), ε_α, ε_β, the static tooth forces, Hertz K, ISO 6336-1 c′, c_γα, c_γβ, the calibrated
mesh law (e K h0^(e−1) = k_n = c_γα b / cos² β_b), the disc inertias, m_red and n_E1.

Two documented choices of gearcli are followed here (docs/iso6336.md): c_γα carries no 0.9 factor below
ε_α = 1.2, and the ISO stiffness is evaluated at |F_t|/b floored at 1 N/mm.
"""

from __future__ import annotations

import math
from math import atan, cos, pi, radians, sin, sqrt, tan

from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

SETTINGS = settings(max_examples=80, deadline=None)
RHO, E, NU = 7800.0, 2.07e5, 0.29  # the predefined steel
Q_C = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)


def shift(lo: float, hi: float):
    return st.floats(lo, hi).map(lambda x: x if abs(x) >= 1e-6 else 0.0)


@st.composite
def stage(draw):
    beta = draw(st.one_of(st.just(0.0), st.floats(0.5, 40.0)))
    m_n = draw(st.floats(1.0, 20.0))
    z1, z2 = draw(st.integers(12, 60)), draw(st.integers(12, 150))
    hands = draw(st.sampled_from([("left", "right"), ("right", "left")]))

    def member(z, x, hand):
        m = {"teeth": z, "face_width_mm": m_n * draw(st.floats(4.0, 15.0)), "profile_shift": x}
        return {**m, "hand": hand} if beta > 0 else m
    return {"normal_module_mm": m_n, "normal_pressure_angle_deg": draw(st.floats(14.5, 25.0)),
            "helix_angle_deg": beta, "efficiency": draw(st.one_of(st.just(1.0), st.floats(0.9, 1.0))),
            "pinion": member(z1, draw(shift(-0.2, 0.6)), hands[0]),
            "gear": member(z2, draw(shift(-0.2, 0.5)), hands[1])}


@st.composite
def train(draw):
    return {"stage": draw(st.lists(stage(), min_size=1, max_size=5)),
            "input": {"speed_rpm": draw(st.floats(50.0, 3000.0))},
            "load": {"torque_Nm": draw(st.floats(-2e4, 2e4).filter(lambda t: abs(t) > 1e-2)),
                     "application_factor": draw(st.one_of(st.just(1.0), st.floats(1.0, 2.0)))}}


def inv(a: float) -> float:
    return tan(a) - a


def inv_inverse(y: float) -> float:
    a = (3.0 * y) ** (1.0 / 3.0)  # series start, then Newton: d(inv)/da = tan² a
    for _ in range(50):
        a -= (tan(a) - a - y) / tan(a) ** 2
    return a


def hand_stage(s: dict, n_p_rpm: float, t_p_Nm: float, k_a: float) -> dict:
    m_n, beta, a_n = s["normal_module_mm"], radians(s["helix_angle_deg"]), radians(s["normal_pressure_angle_deg"])
    z1, z2 = s["pinion"]["teeth"], s["gear"]["teeth"]
    x1, x2 = s["pinion"]["profile_shift"], s["gear"]["profile_shift"]
    b1, b2 = s["pinion"]["face_width_mm"], s["gear"]["face_width_mm"]
    m_t = m_n / cos(beta)
    a_t = atan(tan(a_n) / cos(beta))
    d1, d2 = z1 * m_t, z2 * m_t
    db1, db2 = d1 * cos(a_t), d2 * cos(a_t)
    b_b = atan(tan(beta) * cos(a_t))
    a_d = (d1 + d2) / 2
    a_wt = inv_inverse(inv(a_t) + 2 * tan(a_n) * (x1 + x2) / (z1 + z2))
    a_w = a_d * cos(a_t) / cos(a_wt)
    k = (a_w - a_d) / m_n - (x1 + x2)
    da1, da2 = d1 + 2 * m_n * (1 + x1 + k), d2 + 2 * m_n * (1 + x2 + k)
    df1, df2 = d1 - 2 * m_n * (1.25 - x1), d2 - 2 * m_n * (1.25 - x2)
    p_bt = pi * m_t * cos(a_t)
    eps_a = (sqrt(da1 ** 2 - db1 ** 2) / 2 + sqrt(da2 ** 2 - db2 ** 2) / 2 - a_w * sin(a_wt)) / p_bt
    b = min(b1, b2)
    eps_b = b * sin(beta) / (pi * m_n)
    f_t = t_p_Nm * 1000.0 / (d1 / 2)
    f_n = f_t / (cos(a_n) * cos(beta))
    r_eq = (d1 / 2) * (d2 / 2) / (d1 / 2 + d2 / 2)
    e_star = 1.0 / (2 * (1 - NU ** 2) / E)
    # ISO 6336-1: index 1 the smaller wheel (equal counts: the smaller shift first)
    (zs, xs), (zl, xl) = sorted([(z1, x1), (z2, x2)])
    zn = [z / (cos(b_b) ** 2 * cos(beta)) for z in (zs, zl)]
    q = (Q_C[0] + Q_C[1] / zn[0] + Q_C[2] / zn[1] + Q_C[3] * xs + Q_C[4] * xs / zn[0] + Q_C[5] * xl
         + Q_C[6] * xl / zn[1] + Q_C[7] * xs ** 2 + Q_C[8] * xl ** 2)
    c_b = (1 + 0.5 * (1.2 - 1.25)) * (1 - 0.02 * (20 - s["normal_pressure_angle_deg"]))
    line_load = max(abs(f_t), b) * k_a / b  # floored at 1 N/mm
    c_p = (1 / q) * 0.8 * 1.0 * c_b * cos(beta) * min(line_load / 100, 1.0) ** 0.25
    c_ga = c_p * (0.75 * eps_a + 0.25)
    k_n = c_ga * b * 1000 / cos(b_b) ** 2  # N/mm along the normal
    f_n_ref = max(abs(f_t), b) / (cos(a_n) * cos(beta))
    h0 = 1.5 * f_n_ref / k_n  # e F / k_n for the default exponent e = 1.5
    # inertia: solid disc of the pitch diameter; ISO body (d_m = (d_a + d_f)/2) for m_red, per mm of face
    disc = [RHO * pi * (bw / 1e3) * (d / 1e3) ** 4 / 32 for d, bw in ((d1, b1), (d2, b2))]
    body_per_mm = [RHO * pi * 1e-3 * (((da + df) / 2) / 1e3) ** 4 / 32 for da, df in ((da1, df1), (da2, df2))]
    rb = (db1 / 2e3, db2 / 2e3)
    m_red = body_per_mm[0] * body_per_mm[1] / (body_per_mm[0] * rb[1] ** 2 + body_per_mm[1] * rb[0] ** 2)
    n_e1 = 30000 / (pi * zs) * sqrt(c_ga / m_red)
    return {"m_t": m_t, "a_t": math.degrees(a_t), "a_wt": math.degrees(a_wt), "b_b": math.degrees(b_b),
            "a_w": a_w, "d": (d1, d2), "db": (db1, db2), "da": (da1, da2), "df": (df1, df2), "eps_a": eps_a,
            "eps_b": eps_b, "f_t": f_t, "f_r": f_t * tan(a_t), "f_a": f_t * tan(beta), "f_n": f_n,
            "r_eq": r_eq, "e_star": e_star, "K_hertz": 4 / 3 * sqrt(r_eq) * e_star, "c_p": c_p, "c_ga": c_ga,
            "k_n": k_n, "K_iso": f_n_ref / h0 ** 1.5, "h0": h0, "J": disc, "m_red": m_red, "n_e1": n_e1,
            "f_z": z1 * n_p_rpm / 60}


def hand_train(doc: dict) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    speeds, n = [], doc["input"]["speed_rpm"]
    for s in doc["stage"]:
        i = s["gear"]["teeth"] / s["pinion"]["teeth"]
        speeds.append((n, n / i))
        n /= i
    torques, t = [], doc["load"]["torque_Nm"]
    for s in reversed(doc["stage"]):
        i, eta = s["gear"]["teeth"] / s["pinion"]["teeth"], s["efficiency"]
        t_p = t / (i * eta) if t >= 0 else t * eta / i
        torques.insert(0, (t_p, t))
        t = t_p
    return speeds, torques


@SETTINGS
@given(train())
def test_design_equals_the_textbook_formulas(doc):
    r = compute_design(DesignFile.model_validate(doc))
    speeds, torques = hand_train(doc)
    assert_allclose(r.output_speed_rpm, speeds[-1][1], rtol=1e-12)
    assert_allclose(r.input_torque_Nmm, torques[0][0] * 1e3, rtol=1e-12)
    for s, res, (n_p, n_g), (t_p, t_g) in zip(doc["stage"], r.stages, speeds, torques, strict=True):
        h = hand_stage(s, n_p, t_p, doc["load"]["application_factor"])
        # round-off only: the one iterative quantity (α_wt) converges to machine precision in both codes;
        # k = (a_w − a_d)/m_n − Σx is a difference of near-equal numbers, hence the absolute tolerance
        assert_allclose([res.pinion.speed_rpm, res.gear.speed_rpm], [n_p, n_g], rtol=1e-12)
        assert_allclose([res.pinion.torque_Nmm, res.gear.torque_Nmm], [t_p * 1e3, t_g * 1e3], rtol=1e-12)
        assert_allclose([res.transverse_module_mm, res.transverse_pressure_angle_deg, res.working_pressure_angle_deg,
                         res.base_helix_angle_deg, res.center_distance_mm],
                        [h["m_t"], h["a_t"], h["a_wt"], h["b_b"], h["a_w"]], rtol=1e-10)
        assert_allclose(res.tip_alteration_coefficient, (h["da"][0] - h["d"][0]) / (2 * s["normal_module_mm"])
                        - 1 - s["pinion"]["profile_shift"], atol=1e-9)
        for member, j in ((res.pinion, 0), (res.gear, 1)):
            assert_allclose([member.pitch_diameter_mm, member.base_diameter_mm, member.tip_diameter_mm,
                             member.root_diameter_mm, member.inertia_kg_m2],
                            [h["d"][j], h["db"][j], h["da"][j], h["df"][j], h["J"][j]], rtol=1e-10)
        assert_allclose([res.contact_ratio_transverse, res.overlap_ratio, res.contact_ratio_total],
                        [h["eps_a"], h["eps_b"], h["eps_a"] + h["eps_b"]], rtol=1e-9, atol=1e-12)
        f = res.static_force_N
        assert_allclose([f.tangential, f.radial, f.axial, f.normal], [h["f_t"], h["f_r"], h["f_a"], h["f_n"]],
                        rtol=1e-12, atol=1e-12 * abs(h["f_t"]))
        assert_allclose([res.equivalent_radius_mm, res.effective_modulus_MPa, res.hertz_stiffness_N_mm1_5,
                         res.mesh_frequency_Hz], [h["r_eq"], h["e_star"], h["K_hertz"], h["f_z"]], rtol=1e-12)
        assert_allclose([res.iso6336_single_pair_stiffness_N_mm_um, res.iso6336_mesh_stiffness_N_mm_um,
                         res.iso6336_mesh_stiffness_beta_N_mm_um],
                        [h["c_p"], h["c_ga"], 0.85 * h["c_ga"]], rtol=1e-9)
        ms = res.mesh_stiffness
        assert ms is not None
        assert_allclose([ms.iso_N_mm, ms.linearised_N_mm, ms.K], [h["k_n"], h["k_n"], h["K_iso"]], rtol=1e-9)
        assert_allclose([res.reduced_mass_kg_mm, res.resonance_speed_rpm], [h["m_red"], h["n_e1"]], rtol=1e-9)
