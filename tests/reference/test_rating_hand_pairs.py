"""The ISO 6336:2006 method B rating of gear pairs of our own, against the standard's formulas written out by hand.

``rating_hand`` types every formula again (ISO 6336-1/-2/-3/-5:2006 as docs/iso6336.md quotes them) without
importing gearcli's rating; each scene here goes from the design file to the safeties and is compared factor by
factor. The scenes cover what a single reference report cannot: spur and helical, case-carburized, nitrided,
nitrocarburized, induction/flame hardened, through-hardened, structural and cast steel, nodular and grey iron,
mixed hard/soft pairs (Z_W), a profile-shifted pinion, tip relief (B_k), m_n 1.5 and 22, all four K_v ranges of
method B (subcritical, main resonance, intermediate, supercritical), wide faces (K_Hβ > 2, K_Fβ), and life
factors from the static range through the finite life to beyond 1e10 cycles, "normal" and "optimum".

One scene (the mixed spur pair) is also worked out line by line with the printed intermediate figures, as a gear
engineer would check it on paper.
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from tests.reference.rating_hand import Member, Pair, rate, toml_doc

EH = {"treatment": "case_carburized", "hlim": 1500.0, "flim": 430.0}
NT = {"treatment": "nitrided", "hlim": 1250.0, "flim": 420.0}
V = {"treatment": "through_hardened", "hlim": 720.0, "flim": 300.0}

STAGE_KEYS = ("K_v", "K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha", "Z_eps", "Z_H", "Z_E", "Z_beta", "Z_L", "Z_V",
              "Z_R", "Z_W", "Y_beta")
STRESS_KEYS = {"sigma_H0": "sigma_H0_MPa", "sigma_H": "sigma_H_MPa"}
MEMBER_KEYS = {"load_cycles": "load_cycles", "Z_BD": "Z_BD", "sigma_H": "sigma_H_MPa", "Z_NT": "Z_NT",
               "sigma_HG": "sigma_HG_MPa", "S_H": "S_H", "Y_F": "Y_F", "Y_S": "Y_S", "sigma_F0": "sigma_F0_MPa",
               "sigma_F": "sigma_F_MPa", "Y_DT": "Y_DT", "Y_delta_rel_T": "Y_delta_rel_T", "Y_R_rel_T": "Y_R_rel_T", "Y_X": "Y_X",
               "Y_NT": "Y_NT", "sigma_FG": "sigma_FG_MPa", "S_F": "S_F"}


def _mixed_spur(**kw) -> Pair:
    """Spur 20/60, m 4, b 40: a case-carburized pinion (700 HV) on a through-hardened wheel (300 HV), grade 7."""
    args = {"mn": 4.0, "alpha_n_deg": 20.0, "beta_deg": 0.0, "grade": 7, "torque_pinion_Nm": 300.0, "n1_rpm": 1000.0,
            "k_a": 1.25, "nu40": 150.0, "life_h": 10000.0}
    args.update(kw)
    return Pair(Member(20, 40.0, rz_flank=4.0, rz_root=12.0, hv=700.0, **EH),
                Member(60, 40.0, "through_hardened", 750.0, 320.0, 6.0, 16.0, hv=300.0), **args)


def _small_module(n1: float) -> Pair:
    """Helical 23/41, m_n 1.5, β 20°, through-hardened, grade 5: a high-speed pair across method B's K_v ranges."""
    return Pair(Member(23, 18.0, rz_flank=2.0, rz_root=6.0, hv=280.0, **V),
                Member(41, 16.0, rz_flank=2.0, rz_root=6.0, hv=260.0, **V),
                mn=1.5, alpha_n_deg=20.0, beta_deg=20.0, grade=5, torque_pinion_Nm=12.0, n1_rpm=n1, k_a=1.0,
                nu40=68.0, life_h=5000.0)


def _materials(tp: str, tg: str) -> Pair:
    return Pair(Member(20, 40.0, tp, 600.0, 250.0, 4.0, 12.0, hv=200.0), Member(60, 40.0, tg, 500.0, 220.0, 6.0, 16.0,
                                                                                hv=180.0),
                mn=6.0, alpha_n_deg=20.0, beta_deg=10.0, grade=8, torque_pinion_Nm=300.0, n1_rpm=3000.0, k_a=1.25,
                nu40=150.0, life_h=10000.0)


def _deep_tooth(grade: int, rack: tuple[float, float, float]) -> Pair:
    """Helical 30/90, α_n 16°, β 25°: ε_αn = ε_α/cos² β_b = 2.08 on the standard rack, 2.53 with a 1.25 m_n
    addendum, where Y_DT (grade ≤ 4) is −0.666 ε_αn + 2.366 and 0.7; basic racks A, D and a long-addendum one."""
    return Pair(Member(30, 50.0, rz_flank=2.0, rz_root=5.0, **EH), Member(90, 50.0, rz_flank=2.0, rz_root=5.0, **EH),
                mn=3.0, alpha_n_deg=16.0, beta_deg=25.0, grade=grade, torque_pinion_Nm=400.0, n1_rpm=3000.0, k_a=1.0,
                nu40=100.0, life_h=20000.0, rack=rack)


SCENES = {
    "spur_mixed_hard_soft": _mixed_spur(),
    "helical_nitrided_shifted_tip_relief": Pair(
        Member(17, 60.0, rz_flank=3.0, rz_root=8.0, x=0.4, **NT), Member(71, 55.0, rz_flank=3.0, rz_root=8.0, x=-0.1, **NT),
        mn=3.0, alpha_n_deg=20.0, beta_deg=15.0, grade=6, torque_pinion_Nm=250.0, n1_rpm=2900.0, k_a=1.1, nu40=100.0,
        life_h=20000.0, c_a=15.0),
    "large_module_22_low_speed": Pair(
        Member(19, 400.0, rz_flank=6.0, rz_root=16.0, x=0.3, **EH), Member(97, 380.0, rz_flank=6.0, rz_root=16.0, x=0.1, **EH),
        mn=22.0, alpha_n_deg=20.0, beta_deg=8.0, grade=7, torque_pinion_Nm=4.0e5, n1_rpm=20.0, k_a=1.5, nu40=460.0,
        life_h=50000.0),
    "small_module_subcritical": _small_module(12000.0),
    "small_module_main_resonance": _small_module(26000.0),
    "small_module_intermediate": _small_module(33000.0),
    "small_module_supercritical": _small_module(60000.0),
    "spur_intermediate": _mixed_spur(n1_rpm=20000.0),
    "wide_face_khb_above_2": Pair(Member(20, 200.0, rz_flank=4.0, rz_root=12.0, **EH),
                                  Member(60, 200.0, rz_flank=4.0, rz_root=12.0, **EH), mn=4.0, alpha_n_deg=20.0,
                                  beta_deg=0.0, grade=9, torque_pinion_Nm=600.0, n1_rpm=1000.0, k_a=1.25, nu40=150.0,
                                  life_h=10000.0),
    "deep_tooth_grade_3": _deep_tooth(3, (1.0, 1.25, 0.38)),
    "deep_tooth_grade_4_long_addendum": _deep_tooth(4, (1.25, 1.5, 0.3)),
    "deep_tooth_grade_5_profile_d": _deep_tooth(5, (1.0, 1.4, 0.39)),
    "static_range": _mixed_spur(life_h=0.01),
    "finite_life_1h": _mixed_spur(life_h=1.0),
    "finite_life_20h": _mixed_spur(life_h=20.0),
    "finite_life_500h": _mixed_spur(life_h=500.0),
    "beyond_1e10_normal": _mixed_spur(life_h=1.0e6),
    "optimum_finite": _mixed_spur(life_h=20.0, quality="optimum"),
    "optimum_long": _mixed_spur(life_h=1.0e6, quality="optimum"),
    "grey_iron": _materials("grey_iron", "grey_iron"),
    "structural_steel": _materials("structural_steel", "structural_steel"),
    "nodular_on_cast_steel": _materials("nodular_iron", "cast_steel"),
    "nitrocarburized_on_through_hardened": _materials("nitrocarburized", "through_hardened"),
    "induction_on_flame_hardened": _materials("induction_hardened", "flame_hardened"),
}


def _tool(q: Pair):
    return compute_design(DesignFile.model_validate(toml_doc(q))).stages[0]


@pytest.mark.parametrize("name", sorted(SCENES))
def test_every_factor_against_the_hand_calculation(name):
    """Every stage factor, stress, limit and safety of the JSON equals the hand calculation (1e-9: both evaluate
    the same closed forms in double precision; the iterations (α_wt, θ) converge far below that)."""
    q = SCENES[name]
    hand, st = rate(q), _tool(q)
    r = st.rating
    assert_allclose(st.contact_ratio_transverse, hand["g"]["ea"], rtol=1e-9)
    assert_allclose(st.resonance_ratio, hand["res"]["N"], rtol=1e-9)
    for key in STAGE_KEYS:
        assert_allclose(getattr(r, key), hand[key], rtol=1e-9, err_msg=key)
    for mine, theirs in STRESS_KEYS.items():
        assert_allclose(getattr(r, theirs), hand[mine], rtol=1e-9, err_msg=mine)
    for part in ("pinion", "gear"):
        for mine, theirs in MEMBER_KEYS.items():
            assert_allclose(getattr(getattr(r, part), theirs), hand[part][mine], rtol=1e-9, err_msg=f"{part}.{mine}")


@pytest.mark.parametrize(("name", "expected"), [
    ("small_module_subcritical", "subcritical"), ("small_module_main_resonance", "main resonance"),
    ("small_module_intermediate", "intermediate"), ("small_module_supercritical", "supercritical"),
    ("spur_intermediate", "intermediate")])
def test_the_scenes_span_method_b_ranges(name, expected):
    """The K_v scenes really lie in the range they are named for (the design's own range label agrees)."""
    hand, st = rate(SCENES[name]), _tool(SCENES[name])
    assert st.resonance_range == expected
    assert hand["range"] == expected.split()[0]


@pytest.mark.parametrize(("name", "y_dt"), [("deep_tooth_grade_3", -0.666 * 2.0766051227 + 2.366),
                                            ("deep_tooth_grade_4_long_addendum", 0.7),
                                            ("deep_tooth_grade_5_profile_d", 1.0)])
def test_deep_tooth_factor(name, y_dt):
    """Y_DT where ISO 6336-3 applies it (grade ≤ 4, ε_αn > 2.05): ε_αn = 2.07661 gives 0.98298, ε_αn 2.528 > 2.5
    gives 0.7; grade 5 gives 1 whatever ε_αn."""
    r = _tool(SCENES[name]).rating
    assert_allclose([r.pinion.Y_DT, r.gear.Y_DT], [y_dt, y_dt], rtol=1e-9)


def test_mixed_pair_written_out():
    """The hard/soft spur pair, worked on paper (ISO 6336-1/-2:2006; ISO 1328-1:1995 grade 7 tables).

    F_t = 300 N·m / 40 mm = 7500 N; K_A F_t/b = 1.25 · 7500/40 = 234.375 N/mm; v = π 80 · 1000/60000 = 4.189 m/s.
    Tolerances (ISO 1328-1 table values, grade 7): f_pt 13/14 µm (d 50–125 / 125–280, m 3.5–6), f_fα 15/16 µm,
    f_Hβ 12 µm (d1 50–125, b 20–40); f_pb = 14 cos 20° = 13.156 µm.
    Running-in (ISO 6336-1, 8.3.5, the mean of the two members): y_α = (0.075 · 13.156 + 160/750 · 13.156)/2
    = (0.9867 + 2.8066)/2 = 1.8966 µm; y_f = (0.075 · 16 + 160/750 · 16)/2 = 2.3067 µm.
    c′ = 0.8 · 0.975/q′, q′ = 0.04723 + 0.15551/20 + 0.25791/60 = 0.059304 → c′ = 13.1526; ε_α = 1.67078;
    c_γα = c′ (0.75 ε_α + 0.25) = 19.7694, c_γβ = 16.8040 N/(mm·µm).
    K_v (subcritical, N = 0.06524): B_p = 13.1526 · 11.259/234.375 = 0.6318, B_f = 13.1526 · 13.693/234.375
    = 0.7684, B_k = 1; K_v = 1 + 0.06524 (0.32 · 0.6318 + 0.34 · 0.7684 + 0.23) = 1.04524.
    K_Hβ (method C): F_m/b = 234.375 · 1.04524 = 244.98 N/mm; f_sh = 0.023 · 244.98 · 0.5² = 1.4087 µm;
    F_βx = 1.33 · 1.4087 + 12 = 13.8735 µm; y_β = (0.15 · 13.8735 + 320/750 · 13.8735)/2 = (2.0810 + 5.9194)/2
    = 4.0002 µm (ISO 6336-1:2006, 7.6: where pinion and wheel materials differ, y_β1 and y_β2 separately and
    their mean; as for y_α); F_βy = 9.8733 µm; K_Hβ = 1 + 16.804 · 9.8733/(2 · 244.98) = 1.33862.
    (The pinion's y_β alone, 2.0810, gives 1.40444: what gearcli computed before the fix.)
    Z_W (ISO 6336-2, 13) on the wheel: HB = 0.95 · 300 = 285 → Z_W = 1.2 − (285 − 130)/1700 = 1.10882.
    """
    st = _tool(SCENES["spur_mixed_hard_soft"])
    r = st.rating
    assert_allclose(st.static_force_N.tangential, 7500.0, rtol=1e-12)
    assert_allclose(st.iso6336_single_pair_stiffness_N_mm_um, 0.8 * 0.975 / (0.04723 + 0.15551 / 20 + 0.25791 / 60),
                    rtol=1e-12)
    assert_allclose(r.K_v, 1.04524, atol=1e-5)
    f_m = 234.375 * r.K_v
    f_bx = 1.33 * 0.023 * f_m * 0.25 + 12.0
    y_b = 0.5 * (0.15 * f_bx + 320.0 / 750.0 * f_bx)
    assert_allclose(y_b, 4.0002, atol=1e-4)
    assert_allclose(r.K_Hbeta, 1.0 + st.iso6336_mesh_stiffness_beta_N_mm_um * (f_bx - y_b) / (2.0 * f_m), rtol=1e-12)
    assert_allclose(r.K_Hbeta, 1.33862, atol=1e-5)
    assert r.K_Hbeta_source == "estimated"
    assert_allclose(r.Z_W, 1.2 - (0.95 * 300 - 130) / 1700, rtol=1e-12)
    assert r.pinion.sigma_HG_MPa / r.pinion.Z_NT == pytest.approx(1500 * r.Z_L * r.Z_V * r.Z_R, rel=1e-12)  # no Z_W
    assert r.gear.sigma_HG_MPa / r.gear.Z_NT == pytest.approx(750 * r.Z_L * r.Z_V * r.Z_R * r.Z_W, rel=1e-12)


def test_mixed_pair_running_in_is_symmetric():
    """y_α, y_f and y_β are the mean of the two members, so swapping which member is hard (a through-hardened pinion
    on a case-carburized wheel) leaves K_v, K_Hβ and K_Hα unchanged; Z_W moves to the pinion."""
    q = _mixed_spur()
    swapped = Pair(Member(20, 40.0, "through_hardened", 750.0, 320.0, 6.0, 16.0, hv=300.0),
                   Member(60, 40.0, rz_flank=4.0, rz_root=12.0, hv=700.0, **EH), **{
                       k: getattr(q, k) for k in ("mn", "alpha_n_deg", "beta_deg", "grade", "torque_pinion_Nm",
                                                  "n1_rpm", "k_a", "nu40", "life_h")})
    a, b = _tool(q).rating, _tool(swapped).rating
    for key in ("K_v", "K_Hbeta", "K_Halpha", "Z_W"):
        assert_allclose(getattr(b, key), getattr(a, key), rtol=1e-12, err_msg=key)
    assert b.pinion.sigma_HG_MPa / b.pinion.Z_NT == pytest.approx(750 * b.Z_L * b.Z_V * b.Z_R * b.Z_W, rel=1e-12)
    assert math.isclose(b.gear.sigma_HG_MPa / b.gear.Z_NT, 1500 * b.Z_L * b.Z_V * b.Z_R, rel_tol=1e-12)


@pytest.mark.parametrize(("treatment", "rz", "expected"), [
    # 4.299 − 3.259 (R_z + 1)^0.0058: R_z 1 → 4.299 − 3.259 · 2^0.0058 = 4.299 − 3.259 · 1.0040283 = 1.02687;
    # R_z 10 → 4.299 − 3.259 · 11^0.0058 = 4.299 − 3.259 · 1.0140050 = 0.99436 (3.0 % below the smooth 1.025);
    # R_z 40 → 4.299 − 3.259 · 41^0.0058 = 4.299 − 3.259 · 1.0217716 = 0.96904
    ("nitrided", 1.0, 1.02687), ("nitrocarburized", 10.0, 0.99436), ("grey_iron", 40.0, 0.96904),
    ("nitrided", 0.5, 1.025),
    # the other two lines for contrast: 1.674 − 0.529 · 11^0.1 = 1.00165; 5.306 − 4.203 · 11^0.01 = 1.00100
    ("case_carburized", 10.0, 1.00165), ("structural_steel", 10.0, 1.00100),
])
def test_relative_surface_factor_lines(treatment, rz, expected):
    """Y_RrelT of ISO 6336-3:2006, 13.3 (method B), on a nitrided pair's root roughness: the GG/NT/NV line's exponent is
    0.0058 (ISO 6336-3; DIN 3990-3 the same; as reproduced in IACS UR M56.3 and coded in GEARpie,
    github.com/cfernandesFEUP/GEARpie, CLASSES/DIN3990.py at 329b03ce). gearcli had 0.005, which gives 1.00069 at
    R_z 10 (0.6 % too strong a root) and puts the reference roughness on the wrong side of 1."""
    q = Pair(Member(17, 60.0, rz_flank=3.0, rz_root=rz, treatment=treatment, hlim=1250.0, flim=420.0),
             Member(71, 55.0, rz_flank=3.0, rz_root=rz, treatment=treatment, hlim=1250.0, flim=420.0), mn=3.0,
             alpha_n_deg=20.0, beta_deg=15.0, grade=6, torque_pinion_Nm=250.0, n1_rpm=2900.0, k_a=1.1, nu40=100.0,
             life_h=20000.0)
    r = _tool(q).rating
    assert_allclose(r.pinion.Y_R_rel_T, expected, atol=6e-6)
    assert_allclose(r.gear.Y_R_rel_T, expected, atol=6e-6)


@pytest.mark.parametrize("torque", [0.0, 0.5])
def test_unloaded_stage_is_rated_at_the_floor_with_a_warning(torque):
    """An unloaded stage (zero torque, or below 1 N/mm) is rated at F_t = 1 N/mm · b = 40 N, as docs/iso6336.md says,
    and the design says so: a ``rating_out_of_range`` warning naming the stage and the nominal force. By hand:
    σ_H0 = Z_H Z_E Z_ε √(40/(80 · 40) · 4/3) = 2.49457 · 189.812 · 0.88114 · 0.129099 = 53.862 MPa."""
    q = _mixed_spur(torque_pinion_Nm=torque)
    design = compute_design(DesignFile.model_validate(toml_doc(q)))
    r = design.stages[0].rating
    assert_allclose(r.sigma_H0_MPa, 2.49457 * 189.812 * 0.88114 * math.sqrt(40.0 / 3200.0 * 4.0 / 3.0), rtol=2e-5)
    floor = [d for d in design.diagnostics if d.code == "rating_out_of_range" and
             d.data.get("quantity") == "tangential_force_N"]
    assert len(floor) == 1 and floor[0].data["stage"] == 1
    assert_allclose(floor[0].data["value"], torque * 1000.0 / 40.0, rtol=1e-12)
    assert "40 N" in floor[0].message


def test_loaded_stage_has_no_floor_warning():
    design = compute_design(DesignFile.model_validate(toml_doc(_mixed_spur())))
    assert not [d for d in design.diagnostics if d.data.get("quantity") == "tangential_force_N"]


def _static_warnings(q: Pair) -> dict[str, str]:
    design = compute_design(DesignFile.model_validate(toml_doc(q)))
    return {d.data["member"]: d.message for d in design.diagnostics
            if d.code == "rating_out_of_range" and d.data.get("quantity") == "load_cycles"}


def test_static_range_is_flagged():
    """N_L at or below the first node of a member's life curve (ISO 6336-2 Table 2: 1e5 for Eh and V; ISO 6336-3
    Table 3: 1e3 for Eh, 1e4 for V) is the static range, whose proof ISO 6336 makes with static values of Z_L Z_V Z_R
    and of Y_δrelT, Y_RrelT, Y_X that gearcli does not compute (docs/iso6336.md, "Not covered"): the design says so.
    0.01 h at 1000/333 rpm: N_L = 600 (pinion, Eh) and 200 (wheel, V): both curves static for both members;
    1 h: 6e4 and 2e4: Z_NT static only (Y_NT's nodes 1e3, 1e4 are passed); 20 h: 1.2e6, 4e5: none."""
    short = _static_warnings(_mixed_spur(life_h=0.01))
    assert set(short) == {"pinion", "gear"}
    assert "Z_NT (N_L ≤ 1e+05) and Y_NT (N_L ≤ 1e+03)" in short["pinion"]
    assert "Y_NT (N_L ≤ 1e+04)" in short["gear"]
    one_hour = _static_warnings(_mixed_spur(life_h=1.0))
    assert set(one_hour) == {"pinion", "gear"} and all("Y_NT" not in m for m in one_hour.values())
    assert _static_warnings(_mixed_spur(life_h=20.0)) == {}


def test_simulated_dynamic_factor_rating():
    """``dynamic_factor = "simulated"``: simulate's ``summary.stages[0].rating`` is the rating at K_v = max(1, the run's
    dynamic factor = steady-window max |F_t| / static F_t), with the estimated K_Hβ, K_Hα, K_Fα re-evaluated at that
    K_v: the hand calculation with K_v given reproduces every factor and safety. The mixed spur pair with a
    time-varying mesh (its stiffness between one and two tooth pairs excites it: K_v well above ISO's 1.045)."""
    from gearcli import api

    q = _mixed_spur()
    doc = toml_doc(q, extra_rating={"dynamic_factor": "simulated"})
    doc["input"]["ramp_s"] = 0.05
    doc["load"]["ramp_s"] = 0.05
    doc["contact"] = {"time_varying": True}
    doc["simulation"] = {"duration_s": 0.2, "steps": 400}
    cfg = DesignFile.model_validate(doc)
    design = compute_design(cfg)
    sd = api.simulate(cfg, design, want_series=False).stages[0]
    r = sd.rating
    assert r.K_v_source == "simulated"
    assert_allclose(r.K_v, max(1.0, sd.dynamic_factor), rtol=1e-12)
    assert_allclose(sd.dynamic_factor, sd.tangential_N.max / 7500.0, rtol=1e-9)  # static F_t = 7500 N, lossless
    assert r.K_v > 1.2  # the scene is dynamic: the check below is not ISO's K_v again
    hand = rate(q, k_v_given=r.K_v)
    for key in ("K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha", "Z_eps", "Z_H", "Z_L", "Z_V", "Z_R", "Z_W"):
        assert_allclose(getattr(r, key), hand[key], rtol=1e-9, err_msg=key)
    assert_allclose(r.sigma_H_MPa, hand["sigma_H"], rtol=1e-9)
    for part in ("pinion", "gear"):
        for mine, theirs in MEMBER_KEYS.items():
            assert_allclose(getattr(getattr(r, part), theirs), hand[part][mine], rtol=1e-9, err_msg=f"{part}.{mine}")


def test_notch_warning_reads_the_rated_root():
    """The q_s range warning (Y_S holds for 1 ≤ q_s < 8) looks at the root the rating rates: with a tooth-thickness
    allowance that is the generating shift x_E,i = x + A_sni/(2 m_n tan α_n) = −0.35 − 0.4/(8 tan 20°) = −0.48737
    (docs/iso6336.md, "Allowances in the strength rating"). A 14-tooth pinion at x = −0.35 has q_s = 1.03 but is
    rated at q_s = 0.875 (hand: method B's s_Fn/(2 ρ_F) at x_E,i): the warning fires with that value. It read the
    nominal x and stayed silent."""
    from dataclasses import replace as dc_replace

    from tests.reference.rating_hand import geometry, tooth_form

    q = _mixed_spur()
    q = dc_replace(q, p=dc_replace(q.p, z=14, x=-0.35))
    doc = toml_doc(q)
    doc["stage"][0]["pinion"]["tooth_thickness_allowance_mm"] = [-0.2, -0.4]
    design = compute_design(DesignFile.model_validate(doc))
    x_ei = -0.35 - 0.4 / (2 * 4.0 * math.tan(math.radians(20.0)))
    assert_allclose(design.stages[0].pinion.generating_profile_shift[1], x_ei, rtol=1e-12)
    g = geometry(q)
    nominal = tooth_form(q.p, q, g, 0)["q_s"]
    rated = tooth_form(dc_replace(q.p, x=x_ei), q, g, 0)["q_s"]
    assert nominal > 1.0 > rated
    warned = [d for d in design.diagnostics if d.code == "rating_out_of_range" and d.data.get("quantity") == "q_s"]
    assert [d.data["member"] for d in warned] == ["pinion"]
    assert_allclose(warned[0].data["value"], rated, rtol=1e-9)
