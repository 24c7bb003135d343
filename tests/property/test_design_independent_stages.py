"""`gearcli design`'s JSON against an independent implementation (tests/property/helical_stage_reference.py) on random
parallel helical trains: 1-4 stages, z 12-120 (either member the larger: speed increasers too), m_n 1-20 mm,
β 0 or 0.5-35°, α_n 14.5-25°, profile shifts -0.5 … 0.8 kept clear of undercut and of a tip thinner than 0.25 m_n,
both hands, a basic rack of its own, two materials, webbed bodies, efficiencies, K_A, a load of either sign, and
tooth-thickness, tip and centre-distance allowances (which may thin a tooth into undercut or a pointed tip).

Every stage, member and shaft figure of the JSON is compared at 1e-9 relative; the differences of near-equal numbers
(the tip alteration k, the backlash as a pitch less two tooth thicknesses, the opposed axial forces) get an absolute
tolerance instead. The design checks the reference can decide (undercut, tip thickness, ε_α < 1.2, interference,
tip clearance, negative backlash, ε_α with allowances, axial forces adding on a shaft, ISO 6336-1's resonance
ranges) must fire exactly when the
reference says, outside a 1e-9 band (1e-3 m_n for interference, gearcli's stated tolerance) around their limits.
The same test at the contract's limits (z 5-250, β to 44.9°, α_n 10-35°, x -1 … 1.5, 800-1,500 examples) passed too;
40 examples here keep it in the fast tier (about 1.5 s).
"""

from __future__ import annotations

from math import atan, cos, degrees, pi, radians, tan

import tomli_w
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.io import serialize
from tests.property.helical_stage_reference import Member, Stage, inv, stage_figures, train, undercut_min_shift

MATERIALS = {"a": {"density_kg_m3": 7850.0, "youngs_modulus_MPa": 2.06e5, "poisson_ratio": 0.3},
             "b": {"density_kg_m3": 7200.0, "youngs_modulus_MPa": 1.7e5, "poisson_ratio": 0.27}}
RTOL = 1e-9
MIN_TIP = 0.25  # × m_n, above gearcli's 0.2 m_n warning threshold


def clean(x: float) -> float:
    """0 for a value below gearcli's 1e-6 floor (a tiny nonzero value is refused as a typo)."""
    return x if abs(x) >= 1e-6 else 0.0


@st.composite
def stage(draw):
    beta = draw(st.one_of(st.just(0.0), st.floats(0.5, 35.0)))
    m_n = draw(st.floats(1.0, 20.0))
    alpha_n = draw(st.floats(14.5, 25.0))
    rack = draw(st.one_of(st.none(), st.tuples(st.floats(0.8, 1.1), st.floats(0.15, 0.35), st.floats(0.2, 0.35))))
    z1, z2 = draw(st.integers(12, 120)), draw(st.integers(12, 120))
    hand = draw(st.sampled_from(["left", "right"]))
    ref_rack = (1.0, 1.25, 0.38) if rack is None else (rack[0], rack[0] + rack[1], rack[2])
    probe = Stage(m_n, alpha_n, beta, Member(z1, 1.0), Member(z2, 1.0), rack=ref_rack)
    xs = []
    for z in (z1, z2):
        x_min = max(-0.5, undercut_min_shift(probe, z) + 0.02)
        assume(x_min < 0.8)
        xs.append(clean(draw(st.floats(x_min, 0.8))))
    a_t = probe_alpha_t(alpha_n, beta)
    assume(inv(a_t) + 2 * tan(radians(alpha_n)) * (xs[0] + xs[1]) / (z1 + z2) > 0.002)  # the pair meshes

    def member(z, x, h):
        mat = draw(st.sampled_from(["a", "b"]))
        m = {"teeth": z, "face_width_mm": m_n * draw(st.floats(3.0, 20.0)), "profile_shift": x, "material": mat}
        if beta > 0:
            m["hand"] = h
        if draw(st.booleans()):
            upper = clean(m_n * draw(st.floats(-0.03, 0.02)))  # thinned or thickened
            m["tooth_thickness_allowance_mm"] = [upper, clean(upper - m_n * draw(st.floats(0.001, 0.02)))]
        if draw(st.booleans()):
            upper = clean(m_n * draw(st.floats(-0.02, 0.6)))
            m["tip_diameter_allowance_mm"] = [upper, clean(upper - m_n * draw(st.floats(0.001, 0.05)))]
        if draw(st.booleans()):  # a webbed body: rim s_R, web b_s (C_R clamps b_s/b to 0.2 … 1.2, s_R to ≥ m_n)
            d_f = m_n * z / cos(radians(beta)) - 2 * m_n * (ref_rack[1] - x)
            rim = m_n * draw(st.floats(0.5, 6.0))
            inside = d_f - 2 * rim  # the rim's inner diameter: the bore lies within it
            if inside > 1.0:
                m["bore_diameter_mm"] = draw(st.floats(0.1, 0.9)) * inside
                m["rim_thickness_mm"] = rim
                m["web_thickness_mm"] = m["face_width_mm"] * draw(st.floats(0.1, 1.3))
        return m
    s = {"normal_module_mm": m_n, "normal_pressure_angle_deg": alpha_n, "helix_angle_deg": beta,
         "efficiency": draw(st.one_of(st.just(1.0), st.floats(0.9, 1.0))),
         "pinion": member(z1, xs[0], hand),
         "gear": member(z2, xs[1], "right" if hand == "left" else "left")}
    if rack is not None:
        s["basic_rack"] = {"addendum": ref_rack[0], "dedendum": ref_rack[1], "root_radius": ref_rack[2]}
    if draw(st.booleans()):
        s["center_distance_allowance_mm"] = [m_n * 0.01, -m_n * 0.01]
    return s


def probe_alpha_t(alpha_n: float, beta: float) -> float:
    return atan(tan(radians(alpha_n)) / cos(radians(beta)))


def reference_stage(s: dict) -> Stage:
    def member(m: dict) -> Member:
        mat = MATERIALS[m["material"]]
        return Member(m["teeth"], m["face_width_mm"], m["profile_shift"], mat["youngs_modulus_MPa"],
                      mat["poisson_ratio"], mat["density_kg_m3"],
                      tuple(m["tooth_thickness_allowance_mm"]) if "tooth_thickness_allowance_mm" in m else None,
                      tuple(m.get("tip_diameter_allowance_mm", (0.0, 0.0))), m.get("bore_diameter_mm"),
                      (m["rim_thickness_mm"], m["web_thickness_mm"]) if "rim_thickness_mm" in m else None)
    rack = s.get("basic_rack")
    return Stage(s["normal_module_mm"], s["normal_pressure_angle_deg"], s["helix_angle_deg"], member(s["pinion"]),
                 member(s["gear"]), s["efficiency"],
                 (1.0, 1.25, 0.38) if rack is None else (rack["addendum"], rack["dedendum"], rack["root_radius"]),
                 tuple(s.get("center_distance_allowance_mm", (0.0, 0.0))))


def thick_enough(s: dict) -> bool:
    """Tips no thinner than MIN_TIP m_n (the reference's s_an on the nominal tips)."""
    ref = reference_stage(s)
    out = stage_figures(ref, 1.0, 1.0, 1.0, 1.0, 1.0, 1.5)
    return min(out["tip_thickness"]) >= MIN_TIP * s["normal_module_mm"]


@st.composite
def design(draw):
    stages = draw(st.lists(stage().filter(thick_enough), min_size=1, max_size=4))
    return {"title": "random train", "materials": MATERIALS, "stage": stages,
            "input": {"speed_rpm": draw(st.floats(10.0, 20000.0))},  # to the mesh resonances
            "load": {"torque_Nm": draw(st.sampled_from([1.0, -1.0])) * draw(st.floats(1.0, 5e4)),
                     "application_factor": draw(st.one_of(st.just(1.0), st.floats(1.0, 2.0)))}}


def run_design(doc: dict, tmp_path_factory) -> dict:
    path = tmp_path_factory.mktemp("d") / "train.toml"
    path.write_bytes(tomli_w.dumps(doc).encode())
    loaded = api.load(str(path))
    return serialize.design_dict(api.design(loaded))


def close(actual, expected, what: str, rtol: float = RTOL, atol: float = 0.0) -> None:
    assert_allclose(actual, expected, rtol=rtol, atol=atol, err_msg=what)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.filter_too_much,
                                                                  HealthCheck.too_slow,
                                                                  HealthCheck.function_scoped_fixture])
@given(doc=design())
def test_design_json_equals_the_independent_reference(doc, tmp_path_factory):
    js = run_design(doc, tmp_path_factory)
    stages = train([reference_stage(s) for s in doc["stage"]], doc["input"]["speed_rpm"], doc["load"]["torque_Nm"],
                   doc["load"]["application_factor"])
    close(js["total_ratio"], stages_ratio(stages), "total_ratio")
    close(js["output_speed_rpm"], stages[-1].out["speeds"][1], "output_speed_rpm")
    close(js["input_torque_Nmm"], stages[0].out["torques"][0], "input_torque_Nmm")
    for k, (s, res, src) in enumerate(zip(stages, js["stages"], doc["stage"], strict=True)):
        compare_stage(k, s, res, src)
        compare_checks(k, s, js["warnings"])
    compare_shafts(doc, stages, js)


def compare_shafts(doc: dict, stages: list[Stage], js: dict) -> None:
    """Shaft speeds, torques, inertias (gear k + pinion k+1) and powers; the axial forces on an intermediate shaft of
    two helical stages. A helical tooth's axial force is F_x = −h F_θ tan β (h = +1 right, −1 left, F_θ along the
    rotation): on one shaft the driven gear's F_θ is along the rotation and the driving pinion's against it, so
    opposite hands add |F_a,k| + |F_a,k+1| and one hand leaves their difference."""
    n = len(stages)
    speeds = [stages[0].out["speeds"][0]] + [s.out["speeds"][1] for s in stages]
    torques = [stages[0].out["torques"][0]] + [s.out["torques"][1] for s in stages]
    inertias = ([stages[0].out["J_model"][0]] + [stages[k].out["J_model"][1] + stages[k + 1].out["J_model"][0]
                                                 for k in range(n - 1)] + [stages[-1].out["J_model"][1]])
    for i, shaft in enumerate(js["shafts"]):
        close([shaft["speed_rpm"], shaft["torque_Nmm"], shaft["inertia_kg_m2"], shaft["power_kW"]],
              [speeds[i], torques[i], inertias[i], torques[i] * 1e-3 * speeds[i] * 2 * pi / 60 * 1e-3], f"shaft {i + 1}")
    close([js["input_power_kW"], js["output_power_kW"], js["output_torque_Nmm"]],
          [js["shafts"][0]["power_kW"], js["shafts"][-1]["power_kW"], torques[-1]], "train powers")
    adds = {w["shaft"]: w for w in js["warnings"] if w.get("check") == "axial_forces_add"}
    for k in range(n - 1):
        gear, pinion = doc["stage"][k]["gear"], doc["stage"][k + 1]["pinion"]
        if "hand" not in gear or "hand" not in pinion:
            assert k + 2 not in adds
            continue
        assert (k + 2 in adds) == (gear["hand"] != pinion["hand"]), f"shaft {k + 2}: axial_forces_add"
        if k + 2 in adds:
            a, b = abs(stages[k].out["forces"]["axial"]), abs(stages[k + 1].out["forces"]["axial"])
            close([adds[k + 2]["net_axial_N"], adds[k + 2]["opposed_axial_N"]], [a + b, abs(a - b)],
                  f"shaft {k + 2}: axial forces", atol=1e-9 * (a + b))  # a difference: round-off of the sum


def compare_checks(k: int, s: Stage, warnings: list[dict]) -> None:
    """The design checks the reference can decide: undercut (x_E,i below x_min), a tip thinner than 0.2 m_n (x_E,i
    on the largest tip), ε_α < 1.2."""
    o = s.out
    found = {(w.get("check"), w.get("member")) for w in warnings if w.get("stage") == k + 1}
    for j, name in enumerate(("pinion", "gear")):
        assert (("undercut", name) in found) == (o["x_E_i"][j] < o["undercut_x_min"][j]), (k, name, "undercut")
        assert (("tip_thickness", name) in found) == (o["tip_thickness_cut"][j] < 0.2 * s.m_n), (k, name, "tip")
    assert any(c == "contact_ratio" for c, _ in found) == (o["geometry"]["eps_a"] < 1.2), (k, "contact_ratio")
    n, n_s = o["N"], o["N_S"]  # ISO 6336-1's speed ranges; warned: the main range, and its 1/2 and 1/3 (subcritical)
    bands = [n_s < n <= 1.15] + [n <= n_s and n_s / j < n <= 1.15 / j for j in (2, 3)]
    if min(abs(n - edge) for edge in (n_s, 1.15, n_s / 2, 0.575, n_s / 3, 1.15 / 3)) > 1e-9 * n:
        assert any(c == "iso6336_resonance" for c, _ in found) == any(bands), (k, "iso6336_resonance", n, n_s)
    inter = o["interference"]
    for j, name in enumerate(("pinion", "gear")):
        hit = [w for w in warnings if w.get("stage") == k + 1 and w.get("check") == "interference"
               and w.get("member") == name]
        if abs(inter[name]) > 1e-3 * s.m_n:  # gearcli calls contact within 1e-3 m_n of the form point a touch
            assert bool(hit) == (inter[name] > 0), (k, name, "interference", inter[name])
        if hit:
            close([hit[0]["depth_mm"], hit[0]["contact_ratio_transverse_usable"]], [inter[name], inter["usable"]],
                  f"stage {k + 1} {name} interference")
            if inter["form_diameter"][j] is None:
                assert hit[0]["form_diameter_mm"] is None
            else:
                close(hit[0]["form_diameter_mm"], inter["form_diameter"][j], f"stage {k + 1} {name} d_Ff")
    if s.center_allowance != (0.0, 0.0) or any(m.thickness_allowance or m.tip_allowance != (0.0, 0.0)
                                                for m in (s.pinion, s.gear)):
        a = o["allow"]
        if abs(a["j_n"][1]) > 1e-9:  # zero backlash (no thickness allowance) is round-off either side
            assert any(c == "backlash_negative" for c, _ in found) == (a["j_n"][1] < 0), (k, "backlash_negative")
        for j, name in enumerate(("pinion", "gear")):  # tip clearance: highest tip against the mate's highest root
            c = (o["geometry"]["a_w"] + s.center_allowance[1] - (o["geometry"]["d_a"][j] + (s.pinion, s.gear)[j]
                 .tip_allowance[0]) / 2 - a["d_f_cut"][1 - j][0] / 2)
            if abs(c) > 1e-9:
                assert (("tip_clearance", name) in found) == (c < 0), (k, name, "tip_clearance", c)
        assert any(c == "contact_ratio_allowances" for c, _ in found) == (
            a["eps_allow"][2] < 1 <= o["geometry"]["eps_a"]), (k, "contact_ratio_allowances")


def stages_ratio(stages) -> float:
    r = 1.0
    for s in stages:
        r *= s.out["ratio"]
    return r


def compare_stage(k: int, s: Stage, res: dict, src: dict) -> None:
    o, g = s.out, s.out["geometry"]
    tag = f"stage {k + 1}: "
    pairs = {
        "ratio": o["ratio"], "transverse_module_mm": g["m_t"],
        "transverse_pressure_angle_deg": degrees(g["a_t"]), "working_pressure_angle_deg": degrees(g["a_wt"]),
        "base_helix_angle_deg": degrees(g["b_b"]), "center_distance_mm": g["a_w"],
        "transverse_base_pitch_mm": g["p_bt"], "face_width_mm": g["b"],
        "contact_ratio_transverse": g["eps_a"], "overlap_ratio": g["eps_b"],
        "contact_ratio_total": g["eps_a"] + g["eps_b"], "mesh_frequency_Hz": o["f_z"],
        "equivalent_radius_mm": o["r_eq"], "effective_modulus_MPa": o["e_star"],
        "hertz_stiffness_N_mm1_5": o["K_hertz"], "static_approach_mm": o["h0"],
        "linearised_stiffness_N_mm": o["k_lin"],
        "iso6336_single_pair_stiffness_N_mm_um": o["iso"]["c_p"], "iso6336_mesh_stiffness_N_mm_um": o["iso"]["c_ga"],
        "iso6336_mesh_stiffness_beta_N_mm_um": o["iso"]["c_gb"], "reduced_mass_kg_mm": o["m_red"],
        "resonance_speed_rpm": o["n_E1"], "resonance_ratio": o["N"], "resonance_lower_limit": o["N_S"],
    }
    for key, want in pairs.items():
        close(res[key], want, tag + key)
    n, n_s = o["N"], o["N_S"]
    if min(abs(n - edge) for edge in (n_s, 1.15, 1.5)) > 1e-9 * n:
        assert res["resonance_range"] == ("subcritical" if n <= n_s else "main resonance" if n <= 1.15
                                          else "intermediate" if n < 1.5 else "supercritical"), tag + "range"
    close(res["tip_alteration_coefficient"], g["k"], tag + "k", rtol=0.0, atol=1e-9)
    close([res["iso6336_factors"][f] for f in ("C_M", "C_R", "C_B")],
          [o["iso"]["C_M"], o["iso"]["C_R"], o["iso"]["C_B"]], tag + "iso6336_factors")
    close([res["static_force_N"][f] for f in ("tangential", "radial", "axial", "normal")],
          [o["forces"][f] for f in ("tangential", "radial", "axial", "normal")], tag + "static_force_N")
    ms = res["mesh_stiffness"]
    close([ms["iso_N_mm"], ms["linearised_N_mm"], ms["K"], ms["exponent"], ms["static_approach_mm"]],
          [o["k_n"], o["k_n"], o["law_K"], 1.5, o["h_cal"]], tag + "mesh_stiffness")
    for j, name in enumerate(("pinion", "gear")):
        m, t = res[name], tag + name + "."
        want = {"pitch_diameter_mm": g["d"][j], "base_diameter_mm": g["d_b"][j], "tip_diameter_mm": g["d_a"][j],
                "root_diameter_mm": g["d_f"][j], "speed_rpm": o["speeds"][j], "speed_deg_s": 6 * o["speeds"][j],
                "torque_Nmm": o["torques"][j], "inertia_kg_m2": o["J_model"][j],
                "body_inertia_kg_m2": o["J_body"][j]}
        want["gear_blank_factor"] = o["iso"]["C_R_each"][j]
        for key, value in want.items():
            close(m[key], value, t + key)
        assert m["teeth"] == src[name]["teeth"], t + "teeth"
        if s.beta_deg > 0:
            assert m["hand"] == src[name]["hand"], t + "hand"
    allow = o["allow"]
    has = any(key in src[n] for n in ("pinion", "gear")
              for key in ("tooth_thickness_allowance_mm", "tip_diameter_allowance_mm")) \
        or "center_distance_allowance_mm" in src
    assert ("backlash_normal_mm" in res) == has, tag + "allowance keys present exactly with allowances"
    if has:
        close(res["backlash_circumferential_mm"], allow["j_t"], tag + "backlash_circumferential_mm", atol=1e-9)
        close(res["backlash_normal_mm"], allow["j_n"], tag + "backlash_normal_mm", atol=1e-9)
        close(res["contact_ratio_transverse_with_allowances"], allow["eps_allow"], tag + "ε_α with allowances")
        for j, name in enumerate(("pinion", "gear")):
            close(res[name]["generating_profile_shift"], allow["x_E"][j], tag + name + " x_E", atol=1e-12)
            close(res[name]["manufactured_root_diameter_mm"], allow["d_f_cut"][j], tag + name + " d_f cut")
