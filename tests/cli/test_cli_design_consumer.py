"""A downstream program reading `gearcli design`: `-o x.json`, `--format json` and `--format csv` on stdout, for
designs of our own, every key DESIGN §3/§5/§7/§12 names checked for presence, unit and sign, and every number against
a hand calculation written out here (ISO 21771 geometry, statics with stage efficiencies, Hertz, ISO 6336-1 c′).

The hand calculation never calls gearcli's formula modules: inverse involute by bisection, the train by hand.

Scenes:
- FOUR: four stages, 1480 rpm, 25 kN·m on the output (N·m key): helical β = 15° (right/left), an 1/8-DP module
  3.175 mm at α_n = 22.5° with x = +0.3/−0.1 (working centre distance, tip alteration) and a cast-iron gear, a spur
  stage, and a 25° β = 20° stage with x = +0.4/+0.2; η = 0.985, 0.98, 0.99, 1.
- INCREASER: two stages with the big wheel driving (i = 23/97 and 21/88 < 1), 20 rpm in, 1.5 kN·m on the fast
  output; the same reversed (−1.5 kN·m: the output drives back, losses taken on the gear side).
- INCH: two stages in inch modules (6 DP = 4.2333 mm at 14.5°, 10 DP = 2.54 mm at 20°), input in °/s, load in N·mm,
  target in °/s.
- SPUR: one 8-DP spur pair 24/72 (d1 = 3 in, a = 6 in): a clean design, no warning.
- POWER: FOUR with the load as 34.74 kW at the output speed instead of a torque.
"""

from __future__ import annotations

import csv
import io
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

RTOL = 1e-11  # the same closed-form formulas in another order: round-off only

MATERIALS = """
[materials.st]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.1e5
poisson_ratio = 0.3
[materials.ci]
density_kg_m3 = 7200
youngs_modulus_MPa = 1.7e5
poisson_ratio = 0.26
"""
MAT = {"st": (7850.0, 2.1e5, 0.3), "ci": (7200.0, 1.7e5, 0.26)}

# (m_n, alpha_n, beta, eta, (z1, z2), (x1, x2), (b1, b2), (hand1, hand2), (mat1, mat2))
FOUR_STAGES = [
    (2.5, 20, 15, 0.985, (23, 67), (0.0, 0.0), (32, 30), ("right", "left"), ("st", "st")),
    (3.175, 22.5, 10, 0.98, (19, 71), (0.3, -0.1), (45, 42), ("left", "right"), ("st", "ci")),
    (5, 20, 0, 0.99, (21, 62), (0.0, 0.0), (70, 65), (None, None), ("st", "st")),
    (8, 25, 20, 1.0, (17, 59), (0.4, 0.2), (120, 110), ("right", "left"), ("st", "st")),
]
INCREASER_STAGES = [
    (6, 20, 8, 0.97, (97, 23), (0.0, 0.25), (120, 125), ("left", "right"), ("st", "st")),
    (4, 20, 12, 0.98, (88, 21), (0.0, 0.0), (80, 85), ("right", "left"), ("st", "st")),
]
INCH_STAGES = [
    (25.4 / 6, 14.5, 0, 1.0, (36, 90), (0.0, 0.0), (40, 38), (None, None), ("st", "st")),
    (2.54, 20, 18, 0.985, (31, 113), (0.1, 0.0), (60, 56), ("left", "right"), ("st", "st")),
]
SPUR_STAGES = [(3.175, 20, 0, 1.0, (24, 72), (0.0, 0.0), (38.1, 38.1), (None, None), ("st", "st"))]


def scene_text(title: str, stages, speed: str, load: str, extra: str = "") -> str:
    lines = [f'title = "{title}"', MATERIALS]
    for m_n, a_n, beta, eta, z, x, b, hand, mat in stages:
        lines += ["[[stage]]", f"normal_module_mm = {m_n!r}", f"normal_pressure_angle_deg = {a_n!r}",
                  f"helix_angle_deg = {beta!r}", f"efficiency = {eta!r}"]
        for part, i in (("pinion", 0), ("gear", 1)):
            h = f'hand = "{hand[i]}", ' if hand[i] else ""
            lines.append(f'{part} = {{ teeth = {z[i]}, face_width_mm = {b[i]!r}, {h}material = "{mat[i]}", '
                         f"profile_shift = {x[i]!r} }}")
    lines += ["[input]", speed, "[load]", load, extra]
    return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------------------- hand calculation
def inv(a: float) -> float:
    return math.tan(a) - a


def inv_inverse(v: float) -> float:
    lo, hi = 1e-6, 1.5  # bisection, independent of the code's Newton iteration
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if inv(mid) < v else (lo, mid)
    return 0.5 * (lo + hi)


C_ISO = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)  # ISO 6336-1 cl. 9


def hand_stage(m_n, a_n_deg, beta_deg, z, x, b, mats, t_pinion_Nmm):
    """ISO 21771 geometry, the forces on the pinion's reference circle (DESIGN §3), Hertz, ISO 6336-1 c′."""
    a_n, beta = math.radians(a_n_deg), math.radians(beta_deg)
    m_t = m_n / math.cos(beta)
    a_t = math.atan(math.tan(a_n) / math.cos(beta))
    b_b = math.atan(math.tan(beta) * math.cos(a_t))
    d = [zi * m_t for zi in z]
    d_b = [di * math.cos(a_t) for di in d]
    shift = x[0] + x[1]
    a_wt = inv_inverse(inv(a_t) + 2 * math.tan(a_n) * shift / (z[0] + z[1])) if shift else a_t
    a = (d[0] + d[1]) / 2
    a_w = a * math.cos(a_t) / math.cos(a_wt)
    k = (a_w - a) / m_n - shift
    d_a = [di + 2 * m_n * (1 + xi + k) for di, xi in zip(d, x, strict=True)]
    d_f = [di - 2 * m_n * (1.25 - xi) for di, xi in zip(d, x, strict=True)]
    p_bt = math.pi * m_t * math.cos(a_t)
    eps_a = (math.sqrt((d_a[0] / 2) ** 2 - (d_b[0] / 2) ** 2) + math.sqrt((d_a[1] / 2) ** 2 - (d_b[1] / 2) ** 2)
             - a_w * math.sin(a_wt)) / p_bt
    bw = min(b)
    eps_b = bw * math.sin(beta) / (math.pi * m_n)
    f_t = 2 * t_pinion_Nmm / d[0]
    f_n = f_t / (math.cos(a_n) * math.cos(beta))
    r1, r2 = d[0] / 2, d[1] / 2
    (_, e1, nu1), (_, e2, nu2) = MAT[mats[0]], MAT[mats[1]]
    e_star = 1 / ((1 - nu1 ** 2) / e1 + (1 - nu2 ** 2) / e2)
    radius = r1 * r2 / (r1 + r2)
    order = (0, 1) if z[0] <= z[1] else (1, 0)  # ISO's wheel 1 is the smaller one, whichever drives
    zn = [z[i] / (math.cos(b_b) ** 2 * math.cos(beta)) for i in order]
    xs = [x[i] for i in order]
    c = C_ISO
    q = (c[0] + c[1] / zn[0] + c[2] / zn[1] + c[3] * xs[0] + c[4] * xs[0] / zn[0] + c[5] * xs[1]
         + c[6] * xs[1] / zn[1] + c[7] * xs[0] ** 2 + c[8] * xs[1] ** 2)
    c_b = (1 + 0.5 * (1.2 - 1.25)) * (1 - 0.02 * (20 - a_n_deg))
    line_load = max(abs(f_t), bw) / bw  # K_A = 1; ISO's c′ evaluated at ≥ 1 N/mm (docs/physics.md)
    c_single = 0.8 * c_b * math.cos(beta) / q * min(line_load / 100, 1) ** 0.25
    return dict(m_t=m_t, a_t=math.degrees(a_t), b_b=math.degrees(b_b), a_wt=math.degrees(a_wt), a_w=a_w, k=k, d=d,
                d_b=d_b, d_a=d_a, d_f=d_f, p_bt=p_bt, eps_a=eps_a, eps_b=eps_b, b=bw,
                F_t=f_t, F_r=f_t * math.tan(a_t), F_a=f_t * math.tan(beta), F_n=f_n,
                R=radius, E=e_star, K=4 / 3 * math.sqrt(radius) * e_star,
                c_single=c_single, c_mesh=c_single * (0.75 * eps_a + 0.25))


def hand_train(stages, n_in_rpm: float, t_out_Nmm: float):
    """Speeds down the train (n_{k+1} = n_k z1/z2), torques up it: T_p = T_g/(i η) while the pinion drives,
    T_g η / i when the load drives back (the loss on the driving side)."""
    ratios = [z[1] / z[0] for _, _, _, _, z, *_ in stages]
    speeds = [n_in_rpm]
    for i in ratios:
        speeds.append(speeds[-1] / i)
    torques = []
    t_g = t_out_Nmm
    for (_, _, _, eta, *_), i in zip(reversed(stages), reversed(ratios), strict=True):
        t_p = t_g / (i * eta) if t_g >= 0 else t_g * eta / i
        torques.append((t_p, t_g))
        t_g = t_p
    return ratios, speeds, torques[::-1]


def disc_inertia(rho, b_mm, d_mm):
    return rho * math.pi * (b_mm / 1000) * (d_mm / 1000) ** 4 / 32  # solid disc of pitch diameter (DESIGN §2)


# ------------------------------------------------------------------------------------------ the consumer
def run(args, **kw):
    return CliRunner().invoke(cli, args, catch_exceptions=False, **kw)


def consume(tmp_path: Path, name: str, text: str):
    """Reads the design as a script would: -o x.json, --format json and --format csv on stdout."""
    path = tmp_path / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    out = tmp_path / f"{name}.json"
    res_file = run(["design", str(path), "-o", str(out)])
    assert res_file.exit_code == 0, res_file.stderr
    res_json = run(["design", str(path), "--format", "json"])
    res_csv = run(["design", str(path), "--format", "csv"])
    assert res_json.exit_code == 0 and res_csv.exit_code == 0, res_json.stderr
    from_file = json.loads(out.read_text(encoding="utf-8"))
    doc = json.loads(res_json.stdout)
    assert from_file == doc  # the file and stdout carry the same document
    rows = list(csv.DictReader(io.StringIO(res_csv.stdout)))
    # warnings: one "warning: <message>" line on stderr each, in the JSON's order, in every format
    for res in (res_file, res_json, res_csv):
        said = [line[len("warning: "):] for line in res.stderr.splitlines() if line.startswith("warning: ")]
        assert said == [w["message"] for w in doc["warnings"]]
    return doc, rows


TOP_KEYS = {"gearcli_version", "input_sha256", "title", "total_ratio", "input_speed_deg_s", "output_speed_deg_s",
            "output_speed_rpm", "input_torque_Nmm", "output_torque_Nmm", "input_power_kW", "output_power_kW", "units",
            "warnings", "shafts", "stages"}
STAGE_KEYS = {"index", "ratio", "efficiency", "normal_module_mm", "transverse_module_mm", "normal_pressure_angle_deg",
              "transverse_pressure_angle_deg", "working_pressure_angle_deg", "helix_angle_deg",
              "base_helix_angle_deg", "center_distance_mm", "transverse_base_pitch_mm", "face_width_mm",
              "contact_ratio_transverse", "overlap_ratio", "contact_ratio_total", "mesh_frequency_Hz",
              "equivalent_radius_mm", "effective_modulus_MPa", "hertz_stiffness_N_mm1_5", "static_approach_mm",
              "linearised_stiffness_N_mm", "static_force_N", "iso6336_single_pair_stiffness_N_mm_um",
              "iso6336_mesh_stiffness_N_mm_um", "iso6336_mesh_stiffness_beta_N_mm_um", "iso6336_factors",
              "reduced_mass_kg_mm", "resonance_speed_rpm", "resonance_ratio", "backlash_mm", "tip_alteration_coefficient",
              "mesh_stiffness", "rating", "pinion", "gear"}
MEMBER_KEYS = {"teeth", "hand", "profile_shift", "face_width_mm", "pitch_diameter_mm", "base_diameter_mm",
               "tip_diameter_mm", "root_diameter_mm", "speed_deg_s", "speed_rpm", "torque_Nmm", "torque_Nm",
               "power_kW", "inertia_kg_m2", "inertia_given"}
SHAFT_KEYS = {"index", "speed_deg_s", "speed_rpm", "torque_Nmm", "torque_Nm", "power_kW", "inertia_kg_m2"}


def check_contract_keys(doc, rows, speed_unit: str, torque_unit: str):
    """Every key DESIGN §5, §7, §12 and docs/output.md name, in the JSON and (flattened) in the CSV."""
    assert TOP_KEYS <= set(doc), TOP_KEYS - set(doc)
    assert doc["units"] == {"speed": speed_unit, "torque": torque_unit}
    assert len(doc["input_sha256"]) == 64 and doc["gearcli_version"]
    # §12: a file's own units beside the fixed keys, and no other unit's keys
    assert ("input_speed_rad_s" in doc) == ("output_speed_rad_s" in doc) == (speed_unit == "rad_s")
    assert ("input_torque_Nm" in doc) == ("output_torque_Nm" in doc) == (torque_unit == "Nm")
    for w in doc["warnings"]:
        assert isinstance(w, dict) and {"code", "message"} <= set(w), w
    assert len(rows) == len(doc["stages"])
    for st, row in zip(doc["stages"], rows, strict=True):
        assert STAGE_KEYS <= set(st), STAGE_KEYS - set(st)
        assert set(st["static_force_N"]) == {"tangential", "radial", "axial", "normal"}
        assert set(st["iso6336_factors"]) == {"C_M", "C_R", "C_B"}
        assert {"law", "K", "exponent", "linearised_N_mm", "iso_N_mm"} <= set(st["mesh_stiffness"])
        for part in ("pinion", "gear"):
            assert MEMBER_KEYS <= set(st[part]), MEMBER_KEYS - set(st[part])
            assert ("speed_rad_s" in st[part]) == (speed_unit == "rad_s")
        # the CSV: one row per stage, nested keys flattened with "_", the same numbers as the JSON
        flat = {}
        for key, value in st.items():
            if isinstance(value, dict):
                flat.update({f"{key}_{k}": v for k, v in value.items()})
            elif key != "rating":  # no rating columns without [rating] (docs/output.md)
                flat[key] = value
        assert set(flat) <= set(row), set(flat) - set(row)
        for key, value in flat.items():
            if isinstance(value, bool) or value is None or isinstance(value, str):
                assert row[key] == ("" if value is None else str(value)), key
            else:
                assert float(row[key]) == value, key  # repr round-trips: the same float
    for sh in doc["shafts"]:
        assert SHAFT_KEYS <= set(sh), SHAFT_KEYS - set(sh)


def check_against_hand(doc, stages, n_in_rpm: float, t_out_Nmm: float):
    ratios, speeds, torques = hand_train(stages, n_in_rpm, t_out_Nmm)
    assert_allclose(doc["total_ratio"], math.prod(ratios), rtol=RTOL)
    assert_allclose(doc["output_speed_rpm"], speeds[-1], rtol=RTOL)
    assert_allclose(doc["output_speed_deg_s"], 6 * speeds[-1], rtol=RTOL)
    assert_allclose(doc["input_speed_deg_s"], 6 * n_in_rpm, rtol=RTOL)
    assert_allclose(doc["input_torque_Nmm"], torques[0][0], rtol=RTOL)
    assert_allclose(doc["output_torque_Nmm"], t_out_Nmm, rtol=RTOL)
    w = [n * math.pi / 30 for n in speeds]
    p_in, p_out = torques[0][0] * w[0] * 1e-6, t_out_Nmm * w[-1] * 1e-6  # N·mm · rad/s = mW
    assert_allclose([doc["input_power_kW"], doc["output_power_kW"]], [p_in, p_out], rtol=RTOL)
    # the efficiency chain: the power lost on the way is Π η of the driving side's power
    eta = math.prod(s[3] for s in stages)
    if t_out_Nmm >= 0:
        assert_allclose(p_out, p_in * eta, rtol=1e-12)
    else:  # the load drives back: the input receives Π η of the output's power, all signs negative
        assert_allclose(p_in, p_out * eta, rtol=1e-12)
    sign = math.copysign(1.0, t_out_Nmm)
    for k, (spec, st) in enumerate(zip(stages, doc["stages"], strict=True)):
        m_n, a_n, beta, eta_k, z, x, b, hand, mats = spec
        h = hand_stage(m_n, a_n, beta, z, x, b, mats, torques[k][0])
        assert st["index"] == k + 1
        assert_allclose(st["ratio"], z[1] / z[0], rtol=RTOL)
        assert st["efficiency"] == eta_k
        assert_allclose([st["transverse_module_mm"], st["transverse_pressure_angle_deg"], st["base_helix_angle_deg"],
                         st["working_pressure_angle_deg"], st["center_distance_mm"], st["tip_alteration_coefficient"],
                         st["transverse_base_pitch_mm"], st["face_width_mm"]],
                        [h["m_t"], h["a_t"], h["b_b"], h["a_wt"], h["a_w"], h["k"], h["p_bt"], h["b"]],
                        rtol=1e-10, atol=1e-12)  # bisection to 1e-15 rad: a_wt to ~1e-13
        for i, part in enumerate(("pinion", "gear")):
            g = st[part]
            assert g["teeth"] == z[i] and g["profile_shift"] == x[i]
            assert g["hand"] == (hand[i] if beta else "spur")
            assert_allclose([g["pitch_diameter_mm"], g["base_diameter_mm"], g["tip_diameter_mm"],
                             g["root_diameter_mm"]], [h["d"][i], h["d_b"][i], h["d_a"][i], h["d_f"][i]], rtol=1e-10)
            assert_allclose(g["speed_rpm"], speeds[k + i], rtol=RTOL)
            assert_allclose(g["speed_deg_s"], 6 * speeds[k + i], rtol=RTOL)
            assert g["speed_rpm"] > 0  # every shaft turns in its own running direction
            assert_allclose(g["torque_Nmm"], torques[k][i], rtol=RTOL)
            assert_allclose(g["torque_Nm"], torques[k][i] / 1000, rtol=RTOL)
            assert math.copysign(1.0, g["torque_Nmm"]) == sign
            assert_allclose(g["power_kW"], torques[k][i] * speeds[k + i] * math.pi / 30 * 1e-6, rtol=RTOL)
            assert_allclose(g["inertia_kg_m2"], disc_inertia(MAT[mats[i]][0], b[i], h["d"][i]), rtol=RTOL)
        assert_allclose([st["contact_ratio_transverse"], st["overlap_ratio"], st["contact_ratio_total"]],
                        [h["eps_a"], h["eps_b"], h["eps_a"] + h["eps_b"]], rtol=1e-10)
        assert_allclose(st["mesh_frequency_Hz"], z[0] * speeds[k] / 60, rtol=RTOL)  # = z2 n2 / 60 too
        assert_allclose(st["mesh_frequency_Hz"], z[1] * speeds[k + 1] / 60, rtol=RTOL)
        f = st["static_force_N"]
        assert_allclose([f["tangential"], f["radial"], f["axial"], f["normal"]],
                        [h["F_t"], h["F_r"], h["F_a"], h["F_n"]], rtol=RTOL, atol=1e-9)
        # the sign of the load, and F_n along the line of action: T / (r_b cos β_b), whichever circle F_t is on
        assert math.copysign(1.0, f["tangential"]) == sign
        assert_allclose(f["normal"], 2 * torques[k][0] / (h["d_b"][0] * math.cos(math.radians(h["b_b"]))), rtol=1e-12)
        assert_allclose([st["equivalent_radius_mm"], st["effective_modulus_MPa"], st["hertz_stiffness_N_mm1_5"]],
                        [h["R"], h["E"], h["K"]], rtol=RTOL)
        assert_allclose([st["iso6336_single_pair_stiffness_N_mm_um"], st["iso6336_mesh_stiffness_N_mm_um"],
                         st["iso6336_mesh_stiffness_beta_N_mm_um"]],
                        [h["c_single"], h["c_mesh"], 0.85 * h["c_mesh"]], rtol=1e-10)
        # ISO 6336-1 resonance: solid bodies of d_m = (d_a + d_f)/2, m* = J/(b r_b²) = ρ π d_m⁴ / (32 r_b²) (kg/mm),
        # m_red = m1* m2* / (m1* + m2*), n_E1 = 30000/(π z1) √(c_γα / m_red) of the smaller wheel, N = n1 / n_E1
        m_star = [MAT[mats[i]][0] * 1e-9 * math.pi * ((h["d_a"][i] + h["d_f"][i]) / 2) ** 4 / 32 / (h["d_b"][i] / 2) ** 2
                  for i in range(2)]
        m_red = m_star[0] * m_star[1] / (m_star[0] + m_star[1])
        small = 0 if (z[0], x[0]) <= (z[1], x[1]) else 1
        n_e1 = 30000 / (math.pi * z[small]) * math.sqrt(h["c_mesh"] / m_red)
        assert_allclose([st["reduced_mass_kg_mm"], st["resonance_speed_rpm"], st["resonance_ratio"]],
                        [m_red, n_e1, speeds[k + small] / n_e1], rtol=1e-10)
        # the default law (DESIGN §13): its tangent at the static load is ISO's k_n = c_γα b / cos² β_b
        k_n = h["c_mesh"] * h["b"] * 1000 / math.cos(math.radians(h["b_b"])) ** 2
        assert st["mesh_stiffness"]["law"] == "iso6336"
        assert_allclose([st["mesh_stiffness"]["iso_N_mm"], st["linearised_stiffness_N_mm"]], [k_n, k_n], rtol=1e-10)
        e = st["mesh_stiffness"]["exponent"]
        law_force = abs(h["F_n"]) / (eta_k if t_out_Nmm < 0 and eta_k < 1 else 1.0)  # reversed: the gear drives
        assert_allclose(st["static_approach_mm"], e * law_force / k_n, rtol=1e-10)  # h0 = e F_n0 / k_n
    for j, sh in enumerate(doc["shafts"]):
        assert sh["index"] == j + 1
        assert_allclose(sh["speed_rpm"], speeds[j], rtol=RTOL)
        assert_allclose(sh["torque_Nmm"], torques[j][0] if j < len(stages) else t_out_Nmm, rtol=RTOL)
        on_shaft = ([doc["stages"][j - 1]["gear"]] if j else []) + ([doc["stages"][j]["pinion"]] if j < len(stages)
                                                                      else [])
        assert_allclose(sh["inertia_kg_m2"], sum(g["inertia_kg_m2"] for g in on_shaft), rtol=1e-12)


FOUR = scene_text("FOUR", FOUR_STAGES, "speed_rpm = 1480", "torque_Nm = 25000")


def test_four_stage_reducer(tmp_path):
    doc, rows = consume(tmp_path, "four", FOUR)
    check_contract_keys(doc, rows, "rpm", "Nm")
    check_against_hand(doc, FOUR_STAGES, 1480.0, 25e6)
    assert_allclose(doc["output_torque_Nm"], 25000.0, rtol=RTOL)
    assert_allclose(doc["input_torque_Nm"], doc["input_torque_Nmm"] / 1000, rtol=RTOL)
    # 1480 rpm / (67/23 · 71/19 · 62/21 · 59/17) = 13.2689 rpm; T_in = 25 kN·m / (111.539 · 0.955647) = 234.54 N·m
    assert_allclose(doc["output_speed_rpm"], 13.2689, rtol=5e-6)
    assert_allclose(doc["input_torque_Nm"], 234.539, rtol=5e-6)


@pytest.mark.parametrize("reverse", [False, True])
def test_speed_increaser_forward_and_reversed(tmp_path, reverse):
    t_nm = -1500.0 if reverse else 1500.0
    text = scene_text("INC", INCREASER_STAGES, "speed_rpm = 20", f"torque_Nm = {t_nm!r}",
                      "[target]\noutput_speed_rpm = 350\ntolerance_percent = 1\n")
    doc, rows = consume(tmp_path, "inc", text)
    check_contract_keys(doc, rows, "rpm", "Nm")
    check_against_hand(doc, INCREASER_STAGES, 20.0, t_nm * 1000)
    assert doc["total_ratio"] < 1 and all(st["ratio"] < 1 for st in doc["stages"])
    # 20 rpm · 97/23 · 88/21 = 353.458 rpm: within 1 % of 350, so no target warning
    assert_allclose(doc["output_speed_rpm"], 353.458, rtol=5e-6)
    assert doc["warnings"] == []
    if reverse:  # the fast output drives back: T_in = −1500 · 0.98 · 0.97 / (23/97 · 21/88) N·m = −25199.8 N·m
        assert_allclose(doc["input_torque_Nm"], -25199.76, rtol=5e-7)
        assert all(st["static_force_N"][k] < 0 for st in doc["stages"] for k in ("tangential", "radial", "axial"))
    else:  # T_in = 1500 / (0.98 · 0.97 · 23/97 · 21/88) N·m = 27886.9 N·m
        assert_allclose(doc["input_torque_Nm"], 27886.93, rtol=5e-7)


def test_inch_modules_in_deg_s_and_n_mm(tmp_path):
    text = scene_text("INCH", INCH_STAGES, "speed_deg_s = 6900", "torque_Nmm = 1.8e6",
                      "[target]\noutput_speed_deg_s = 345\n")
    doc, rows = consume(tmp_path, "inch", text)
    check_contract_keys(doc, rows, "deg_s", "Nmm")
    check_against_hand(doc, INCH_STAGES, 6900 / 6, 1.8e6)
    # 6 DP, 36 teeth: d1 = 6 in = 152.4 mm; 10 DP β = 18°: d1 = 31 · 2.54 / cos 18° = 78.74 / 0.951057 = 82.7921 mm
    assert_allclose(doc["stages"][0]["pinion"]["pitch_diameter_mm"], 152.4, rtol=1e-12)
    assert_allclose(doc["stages"][1]["pinion"]["pitch_diameter_mm"], 82.7921, rtol=2e-6)
    # 6900 °/s · 36/90 · 31/113 = 757.17 °/s misses 345 °/s by +119 %; 14.5°, 36 teeth: z_min = 2 · 0.965 / sin² 14.5°
    # = 30.8 (h_FfP* = 1.25 − 0.38 (1 − sin 14.5°) = 0.965): no undercut
    checks = [(w["code"], w.get("check")) for w in doc["warnings"]]
    assert ("design", "target_speed") in checks
    target = next(w for w in doc["warnings"] if w.get("check") == "target_speed")
    assert_allclose(target["target_rpm"], 345 / 6, rtol=1e-12)
    assert_allclose(target["output_speed_rpm"], 6900 / 6 * 36 / 90 * 31 / 113, rtol=1e-12)
    # the message speaks the target's own unit (it said "126.2 rpm misses the target 57.5 rpm" for a target in °/s)
    assert "output speed 757.2 °/s misses the target 345 °/s by +119.5 %" in target["message"], target["message"]
    assert not [c for c in checks if c[1] == "undercut"]


def test_single_spur_pair_is_clean(tmp_path):
    text = scene_text("SPUR", SPUR_STAGES, "speed_rpm = 1750", "torque_Nm = 300")
    doc, rows = consume(tmp_path, "spur", text)
    check_contract_keys(doc, rows, "rpm", "Nm")
    check_against_hand(doc, SPUR_STAGES, 1750.0, 3e5)
    st = doc["stages"][0]
    # 8 DP: d1 = 24/8 in = 76.2 mm, a = 96/16 in = 152.4 mm; F_t = 2 · 100 N·m / 76.2 mm = 2624.67 N, F_a = 0
    assert_allclose([st["pinion"]["pitch_diameter_mm"], st["center_distance_mm"]], [76.2, 152.4], rtol=1e-12)
    assert_allclose(st["static_force_N"]["tangential"], 2624.67, rtol=2e-6)
    assert st["static_force_N"]["axial"] == 0.0 and st["overlap_ratio"] == 0.0
    assert doc["warnings"] == []


SPELLINGS = {  # the FOUR scene's speed and load in every spelling the schema allows
    "rpm_Nm": ("speed_rpm = 1480", "torque_Nm = 25000", ("rpm", "Nm")),
    "deg_s_Nmm": ("speed_deg_s = 8880", "torque_Nmm = 2.5e7", ("deg_s", "Nmm")),
    "rad_s_Nm": (f"speed_rad_s = {1480 * math.pi / 30!r}", "torque_Nm = 25000", ("rad_s", "Nm")),
    # P = T ω_out = 25 kN·m · (1480 rpm / 111.539) · π/30 = 34.738 kW: the power at the nominal output speed
    "rpm_kW": ("speed_rpm = 1480", f"power_kW = {25000 * 1480 / (67 / 23 * 71 / 19 * 62 / 21 * 59 / 17) * math.pi / 30000!r}",
               ("rpm", "Nm")),
}


def _flat(obj, prefix=""):
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield from _flat(v, f"{prefix}.{k}")
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _flat(v, f"{prefix}[{i}]")
    else:
        yield prefix, obj


def test_the_same_design_in_every_unit_spelling_gives_the_same_numbers(tmp_path):
    docs = {}
    for name, (speed, load, units) in SPELLINGS.items():
        doc, rows = consume(tmp_path, name, scene_text("FOUR", FOUR_STAGES, speed, load))
        check_contract_keys(doc, rows, *units)
        check_against_hand(doc, FOUR_STAGES, 1480.0, 25e6)
        docs[name] = dict(_flat({k: v for k, v in doc.items() if k not in ("input_sha256", "units")}))
    ref = docs["rpm_Nm"]
    for name, flat in docs.items():
        common = set(ref) & set(flat)
        assert {k for k in set(ref) ^ set(flat) if not k.endswith(("_rad_s", "_torque_Nm"))} == set(), name
        for key in common:
            if isinstance(ref[key], float):
                assert_allclose(flat[key], ref[key], rtol=1e-9, err_msg=f"{name} {key}")  # unit conversions only
            else:
                assert flat[key] == ref[key], (name, key)


# --------------------------------------------------------------------------------------------- warnings
SPUR = scene_text("SPUR", SPUR_STAGES, "speed_rpm = 1750", "torque_Nm = 300")
SIN2_20 = math.sin(math.radians(20)) ** 2
H_FF = 1.25 - 0.38 * (1 - math.sin(math.radians(20)))  # ISO 53 profile A's straight flank: 0.99997 m_n


def design_with(tmp_path, *sets, text=SPUR):
    path = tmp_path / "w.toml"
    path.write_text(text, encoding="utf-8")
    args = ["design", str(path), "--format", "json"]
    for s in sets:
        args += ["--set", s]
    res = run(args)
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    said = [line[len("warning: "):] for line in res.stderr.splitlines() if line.startswith("warning: ")]
    assert said == [w["message"] for w in doc["warnings"]]  # stderr says each JSON warning, in order
    return doc


def checks_of(doc):
    return [(w["code"], w.get("check"), w.get("stage"), w.get("member")) for w in doc["warnings"]]


def test_target_speed_fires_only_outside_its_tolerance(tmp_path):
    # 1750 rpm / 3 = 583.33 rpm: −16.7 % from 700 rpm (fires), −2.8 % from 600 rpm (inside the default 5 %)
    doc = design_with(tmp_path, "target.output_speed_rpm=700")
    assert checks_of(doc) == [("design", "target_speed", None, None)]
    w = doc["warnings"][0]
    assert_allclose([w["output_speed_rpm"], w["target_rpm"], w["tolerance_percent"]], [1750 / 3, 700, 5], rtol=1e-12)
    assert "-16.7 %" in w["message"]
    assert design_with(tmp_path, "target.output_speed_rpm=600")["warnings"] == []
    assert design_with(tmp_path, "target.output_speed_deg_s=3600")["warnings"] == []  # 600 rpm in °/s
    doc = design_with(tmp_path, "target.output_speed_rpm=600", "target.tolerance_percent=2")  # −2.78 % > 2 %
    assert checks_of(doc) == [("design", "target_speed", None, None)]


def test_spur_hand_warns_that_the_hands_are_ignored(tmp_path):
    doc = design_with(tmp_path, 'stage.0.pinion.hand="left"')
    assert checks_of(doc) == [("design", "spur_hand", 1, None)]
    assert doc["stages"][0]["pinion"]["hand"] == "spur"


@pytest.mark.parametrize(("teeth", "shift", "fires"), [(14, 0.0, True), (17, 0.0, True), (18, 0.0, False),
                                                       (14, 0.19, False), (14, 0.18, True),
                                                       (14, 0.17, True)])
def test_undercut_at_the_rack_limit(tmp_path, teeth, shift, fires):
    """z_min = 2 (h_FfP* − x) / sin² α for a spur pinion: 17.097 at x = 0; x_min = h_FfP* − z sin² α / 2 = 0.1810 for
    z = 14 (ISO 21771 / DIN 3960, the rack's straight flank)."""
    assert_allclose(2 * H_FF / SIN2_20, 17.097, rtol=1e-4)
    doc = design_with(tmp_path, f"stage.0.pinion.teeth={teeth}", f"stage.0.pinion.profile_shift={shift}")
    cut = [w for w in doc["warnings"] if w.get("check") == "undercut"]
    assert bool(cut) == fires, doc["warnings"]
    if fires:
        assert (cut[0]["stage"], cut[0]["member"], cut[0]["teeth"]) == (1, "pinion", teeth)
        # the shift that avoids it, rounded up: +0.18 (x_min = 0.1810 to the nearest) still warns, the case above
        assert f"≥ {math.ceil(100 * (H_FF - teeth * SIN2_20 / 2)) / 100:+.2f}" in cut[0]["message"]
        # and the numbers in the data, so that a script need not parse the message (they were only in the text)
        assert_allclose([cut[0]["min_teeth"], cut[0]["min_profile_shift"]],
                        [2 * (H_FF - shift) / SIN2_20, H_FF - teeth * SIN2_20 / 2], rtol=1e-12)


def test_contact_ratio_warnings_below_1_2_and_below_1(tmp_path):
    # α_n = 35°, z = 10/11, x = 0: ε_α = 1.184 (hand: hand_stage) < 1.2
    h = hand_stage(3.175, 35, 0, (10, 11), (0.0, 0.0), (38.1, 38.1), ("st", "st"), 1e5)
    assert 1.0 < h["eps_a"] < 1.2
    doc = design_with(tmp_path, "stage.0.normal_pressure_angle_deg=35", "stage.0.pinion.teeth=10",
                      "stage.0.gear.teeth=11")
    w = next(w for w in doc["warnings"] if w.get("check") == "contact_ratio")
    assert_allclose(w["contact_ratio_transverse"], h["eps_a"], rtol=1e-10)
    assert "< 1.2" in w["message"] and "< 1:" not in w["message"]
    # α_n = 25°, z = 12/13, x = +0.8/+0.8: the working pressure angle grows, ε_α = 0.962 < 1
    h = hand_stage(3.175, 25, 0, (12, 13), (0.8, 0.8), (38.1, 38.1), ("st", "st"), 1e5)
    assert h["eps_a"] < 1.0
    doc = design_with(tmp_path, "stage.0.normal_pressure_angle_deg=25", "stage.0.pinion.teeth=12",
                      "stage.0.gear.teeth=13", "stage.0.pinion.profile_shift=0.8", "stage.0.gear.profile_shift=0.8")
    w = next(w for w in doc["warnings"] if w.get("check") == "contact_ratio")
    assert_allclose(w["contact_ratio_transverse"], h["eps_a"], rtol=1e-10)
    assert "< 1:" in w["message"]


@pytest.mark.parametrize(("width", "fires"), [(130, True), (114, False), (15.0, True), (15.3, False)])
def test_face_width_ratio_outside_0_2_to_1_5(tmp_path, width, fires):
    # b/d1 with d1 = 76.2 mm: 130 → 1.706, 114 → 1.496, 15 → 0.1969, 15.3 → 0.2008
    ratio = width / 76.2
    doc = design_with(tmp_path, f"stage.0.pinion.face_width_mm={width}", f"stage.0.gear.face_width_mm={width}")
    found = [w for w in doc["warnings"] if w.get("check") == "face_width"]
    assert (not 0.2 <= ratio <= 1.5) == fires
    assert bool(found) == fires, (ratio, found)
    if found:
        assert_allclose(found[0]["face_width_ratio"], ratio, rtol=1e-12)


def test_pointed_tip_warns(tmp_path):
    """z = 12, x = +1.0 at 20°: s_an = d_a (π/(2z) + 2 x tan α / z + inv α − inv α_a) with d_a = d + 2 m (1 + x + k)
    is below 0.2 m_n (hand: ISO 21771 5.4)."""
    h = hand_stage(3.175, 20, 0, (12, 72), (1.0, 0.0), (38.1, 38.1), ("st", "st"), 1e5)
    d, d_a = h["d"][0], h["d_a"][0]
    a = math.radians(20)
    a_a = math.acos(d * math.cos(a) / d_a)
    s_an = d_a * (math.pi / 24 + 2 * math.tan(a) / 12 + inv(a) - inv(a_a))
    assert s_an < 0.2 * 3.175
    doc = design_with(tmp_path, "stage.0.pinion.teeth=12", "stage.0.pinion.profile_shift=1.0")
    w = next(w for w in doc["warnings"] if w.get("check") == "tip_thickness")
    assert (w["stage"], w["member"]) == (1, "pinion")
    assert f"{s_an:.3g} mm" in w["message"]
    assert_allclose([w["tip_thickness_mm"], w["min_tip_thickness_mm"]], [s_an, 0.2 * 3.175], rtol=1e-10)


@pytest.mark.parametrize(("rpm", "verdict"), [(13000, "main resonance"), (6500, "1/2"), (3000, None)])
def test_iso6336_resonance_ranges(tmp_path, rpm, verdict):
    """N = n1/n_E1 against ISO 6336-1's ranges: the main resonance N_S < N ≤ 1.15 with N_S = 0.5 + 0.35 √(F_t/b / 100)
    below 100 N/mm (here F_t/b = 2624.67/38.1 = 68.89 N/mm: N_S = 0.7905), and N near 1/2 (N_S/2 < N ≤ 0.575)."""
    doc = design_with(tmp_path, f"input.speed_rpm={rpm}")
    st = doc["stages"][0]
    assert_allclose(st["resonance_lower_limit"], 0.5 + 0.35 * math.sqrt(2624.6719 / 38.1 / 100), rtol=1e-6)
    assert_allclose(st["resonance_ratio"], rpm / st["resonance_speed_rpm"], rtol=1e-12)
    iso = [w for w in doc["warnings"] if w.get("check") == "iso6336_resonance"]
    if verdict is None:
        assert not iso
    else:
        assert len(iso) == 1 and verdict in iso[0]["message"] and iso[0]["stage"] == 1
        assert_allclose([iso[0]["resonance_ratio"], iso[0]["resonance_lower_limit"]],
                        [st["resonance_ratio"], st["resonance_lower_limit"]], rtol=0)
        assert iso[0]["resonance_range"] == st["resonance_range"]
        # the range's bound printed to N's own three decimals (was two: "N = 0.710 lies in 0.71 < N" for N_S = 0.706)
        n_s = 0.5 + 0.35 * math.sqrt(2624.6719 / 38.1 / 100)
        assert verdict != "main resonance" or f"{n_s:.3f} < N ≤ 1.15" in iso[0]["message"], iso[0]["message"]


def test_stiffness_not_iso_for_the_seed_hertz_law(tmp_path):
    """K = 4/3 √R E* at the static load: k_lin = 1.5 K h0^0.5, h0 = (F_n/K)^(2/3); far from ISO's k_n, so it warns
    with departure = k_lin/k_n − 1."""
    doc = design_with(tmp_path, 'contact.stiffness="hertz"')
    st = doc["stages"][0]
    h = hand_stage(3.175, 20, 0, (24, 72), (0.0, 0.0), (38.1, 38.1), ("st", "st"), 1e5)
    h0 = (h["F_n"] / h["K"]) ** (2 / 3)
    k_lin = 1.5 * h["K"] * h0 ** 0.5
    k_n = h["c_mesh"] * 38.1 * 1000
    assert_allclose([st["static_approach_mm"], st["linearised_stiffness_N_mm"]], [h0, k_lin], rtol=1e-10)
    (w,) = [w for w in doc["warnings"] if w["code"] == "stiffness_not_iso"]
    assert_allclose([w["linearised_N_mm"], w["iso_N_mm"], w["departure"]], [k_lin, k_n, k_lin / k_n - 1], rtol=1e-10)
    assert abs(k_lin / k_n - 1) > 0.25


# ------------------------------------------------------------------------------------ exit codes and files
def test_bad_and_infeasible_files_exit_2_and_leave_no_file(tmp_path):
    """A same-hand helical pair, a helical pair without hands and a key out of range: exit 2, one line naming the
    file and the key path, no traceback; -o creates nothing, and an existing -o file keeps its bytes."""
    helical = SPUR.replace("helix_angle_deg = 0", "helix_angle_deg = 12")
    cases = {
        "same_hand": (helical.replace('material = "st", profile_shift = 0.0 }', 'hand = "left", material = "st", '
                                      'profile_shift = 0.0 }'), "stage[0].gear.hand"),
        "no_hand": (helical, "stage[0].pinion.hand"),
        "teeth": (SPUR.replace("teeth = 24", "teeth = 4"), "stage[0].pinion.teeth"),
        "both_speeds": (SPUR.replace("speed_rpm = 1750", "speed_rpm = 1750\nspeed_deg_s = 10500"), "input"),
    }
    for name, (text, key) in cases.items():
        path = tmp_path / f"{name}.toml"
        path.write_text(text, encoding="utf-8")
        new, old = tmp_path / f"{name}_new.json", tmp_path / f"{name}_old.json"
        old.write_bytes(b"previous run\n")
        for target in (new, old):
            res = run(["design", str(path), "-o", str(target)])
            assert res.exit_code == 2, (name, res.stderr)
            assert res.stdout == "" and "Traceback" not in res.stderr
            assert res.stderr.startswith(f"gearcli: {path}: ") and key in res.stderr, res.stderr
        assert not new.exists() and old.read_bytes() == b"previous run\n"
        assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(name)) == sorted(
            [f"{name}.toml", f"{name}_old.json"])  # no temporary file left beside


def test_piped_stdout_is_clean_csv_with_the_warnings_on_stderr(tmp_path):
    """A real process with stdout a pipe: the default format is CSV, parseable whole; warnings only on stderr."""
    path = tmp_path / "spur.toml"
    path.write_text(SPUR, encoding="utf-8")
    res = subprocess.run([sys.executable, "-m", "gearcli", "design", str(path), "--set", "target.output_speed_rpm=700",
                          "--set", 'stage.0.pinion.hand="right"'], capture_output=True, text=True, check=False)
    assert res.returncode == 0, res.stderr
    rows = list(csv.DictReader(io.StringIO(res.stdout)))
    assert len(rows) == 1 and float(rows[0]["ratio"]) == 3.0
    assert "warning" not in res.stdout
    lines = res.stderr.splitlines()
    assert len(lines) == 2 and all(line.startswith("warning: ") for line in lines), res.stderr
    assert "misses the target 700 rpm" in lines[0] and "hand given" in lines[1]


# ------------------------------------------------------------------------------------------ the table's units
@pytest.mark.parametrize(("speed", "load", "present", "absent"), [
    ("speed_rpm = 1480", "torque_Nm = 25000", ["speed [rpm]", "torque [N·m]", "output 13.269 rpm",
                                               "input torque 234.54 N·m"], ["°/s", "N·mm", "rad/s"]),
    ("speed_deg_s = 8880", "torque_Nmm = 2.5e7", ["speed [°/s]", "speed [rpm]", "torque [N·mm]", "torque [N·m]",
                                                  "output 79.613 °/s = 13.27 rpm",
                                                  "input torque 2.3454e+05 N·mm = 234.54 N·m"], ["rad/s"]),
    (f"speed_rad_s = {1480 * math.pi / 30!r}", "power_kW = 34.73787", ["speed [rad/s]", "torque [N·m]",
                                                                        "output 1.3895 rad/s = 13.27 rpm"],
     ["°/s", "N·mm"]),
])
def test_design_table_speaks_the_files_units(tmp_path, speed, load, present, absent):
    """DESIGN §12: speeds in the input speed key's unit, torques in the load torque key's (torque_Nm or power_kW →
    N·m everywhere); °/s files also in rpm, N·mm files also in N·m, as the simulate and report footers give them.
    The design table printed °/s and N·mm rows and footer for every file. FOUR: 1480 rpm / 111.539 = 13.269 rpm
    = 79.613 °/s = 1.3895 rad/s; T_in = 234.54 N·m."""
    path = tmp_path / "t.toml"
    path.write_text(scene_text("FOUR", FOUR_STAGES, speed, load), encoding="utf-8")
    res = run(["design", str(path), "--format", "table", "-q"], env={"COLUMNS": "200"})
    assert res.exit_code == 0, res.stderr
    for s in present:
        assert s in res.stdout, s
    for s in absent:
        assert s not in res.stdout, s


def test_planetary_design_table_speaks_the_files_units(tmp_path):
    """configs/planetary_stage.toml (carrier driven at 12.127 rpm, ring held, sun out) written in °/s and N·mm: the
    planetary table's member rows were in rpm and N·m whatever the file. The sun turns at 12.127 (1 + 56/19) =
    47.870 rpm = 287.22 °/s; the carrier's 72.762 °/s; the load 999650.9 N·m = 9.9965e+08 N·mm on the sun."""
    root = Path(__file__).resolve().parents[2]
    res = run(["design", str(root / "configs" / "planetary_stage.toml"), "--format", "table", "-q",
               "--set", "input.speed_deg_s=72.762", "--set", "load.torque_Nmm=999650900"], env={"COLUMNS": "200"})
    assert res.exit_code == 0, res.stderr
    out = res.stdout
    assert_allclose(72.762 * (1 + 56 / 19), 287.22, rtol=2e-5)
    for s in ("sun: speed [°/s] / torque [N·mm] / power [kW]", "287.22 / 9.9965e+08 /", "carrier: speed [°/s]",
              "72.762 /", "moment balance T_sun + T_carrier + T_ring [N·mm]",
              "per planet, carrier frame: sun-side / planet torque [N·mm]",
              "planet speed relative to the carrier [°/s]"):
        assert s in out, s
    assert "[N·m]" not in out.split("planetary stages", 1)[1].split("shafts", 1)[0]
