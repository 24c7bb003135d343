"""A hoist reducer of the tr10c trial (one helical stage 23/71, m_n 3, case-carburized; bearings with ISO 281 catalogue
data) over a duty with a reversing step (lowering, -700 N m), a light step whose stress lies below the S-N curve's
endurance limit, and an idle step (0 N m). Every figure is checked by hand:

- cycles per class: hours x 60 x the member's speed (one contact per turn);
- N_i from the ISO 6336-2:2006 Z_NT curve of case-carburized steel written out below (1.6 at 1e5, 1.0 at 5e7,
  0.85 at 1e10), through sigma_inf = sigma_HG / Z_NT of ``gearcli design`` at the point (K_A = 1), in the three
  Miner variants of ISO 6336-6 (iso: the 0.85-at-1e10 slope continued; elementary: the finite slope k continued;
  modified: 2k - 1 below the knee);
- the shaft reactions of the lowering step from F_t, F_r, F_a by the lever rule (the separating force keeps its
  sense when the torque reverses, F_t and F_a reverse: the two bearings of the symmetric input shaft swap loads);
- kappa (ASTM D341, nu_1 of ISO 281 6.5.2.4), e_C (ISO 281 Table 13, lower end, by d_m), a_ISO (ISO 281 eq. for
  radial ball and roller bearings), a_1 (Table 12), L_nm combined by Palmgren-Miner over the points.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

HOIST = """
title = "tr10c hoist reducer"

[materials.case]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1450
bending_fatigue_limit_MPa = 420

[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 12
accuracy_grade = 6
pinion = { teeth = 23, face_width_mm = 35, hand = "right", material = "case", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 12, axial_position_mm = 80 }
gear = { teeth = 71, face_width_mm = 35, hand = "left", material = "case", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 12, axial_position_mm = 80 }

[input]
speed_rpm = 1200
ramp_s = 0.05

[load]
torque_Nm = 1000
ramp_s = 0.05

[lubricant]
viscosity_40C_mm2_s = 150
viscosity_100C_mm2_s = 15
temperature_C = 65
contamination = "normal"

[rating]
required_life_h = 10000

[simulation]
duration_s = 0.3
steps = 600

[[duty]]
name = "lift"
hours = 4000
torque_Nm = 1000
speed_rpm = 1200

[[duty]]
name = "lower"
hours = 3000
torque_Nm = -700
speed_rpm = 1200

[[duty]]
name = "creep"
hours = 3000
torque_Nm = 150
speed_rpm = 600

[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 30
static_load_rating_kN = 16
kind = "ball"
locating = true
factors = { e = 0.3, X = 0.56, Y = 1.5 }
fatigue_load_limit_kN = 0.7
pitch_diameter_mm = 45

[[bearing]]
shaft = 1
position_mm = 160
dynamic_load_rating_kN = 30
kind = "ball"
fatigue_load_limit_kN = 0.7
pitch_diameter_mm = 45
reliability_percent = 99

[[bearing]]
shaft = 2
position_mm = 0
dynamic_load_rating_kN = 90
static_load_rating_kN = 100
kind = "roller"
locating = true
factors = { e = 0.4, X = 0.4, Y = 1.5 }
fatigue_load_limit_kN = 11
pitch_diameter_mm = 110
reliability_percent = 95

[[bearing]]
shaft = 2
position_mm = 160
dynamic_load_rating_kN = 90
kind = "roller"
fatigue_load_limit_kN = 11
pitch_diameter_mm = 110
"""

POINTS = (("lift", 4000.0, 1000.0, 1200.0), ("lower", 3000.0, -700.0, 1200.0), ("creep", 3000.0, 150.0, 600.0))
RATIO = 23 / 71  # gear turns per pinion turn
ZNT = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))  # ISO 6336-2:2006 Table 2, case-carburized, normal quality


def _run(*args: str, code: int = 0):
    res = CliRunner().invoke(cli, ["-q", *args])
    assert res.exit_code == code, res.output
    return res


@pytest.fixture(scope="module")
def hoist(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("hoist") / "hoist.toml"
    path.write_text(HOIST, encoding="utf-8")
    return path


def _design(path: Path, torque: float, speed: float) -> dict:
    return json.loads(_run("design", str(path), "--format", "json", "--set", f"load.torque_Nm={torque!r}",
                           "--set", f"input.speed_rpm={speed!r}", "--set", "load.application_factor=1").stdout)


def _cycles_to_failure(stress: float, knee: float, variant: str) -> float:
    """N at ``stress`` on sigma_inf Z_NT(N), ``knee`` = sigma_inf, by the variant's branch below the knee."""
    (n0, y0), (n1, y1), (n2, y2) = ZNT
    k_fin = math.log(n1 / n0) / math.log(y0 / y1)  # 13.22
    y = stress / knee
    if y >= y1:
        return n1 * (y1 / y) ** k_fin
    if variant == "elementary":
        return n1 * (y1 / y) ** k_fin
    if variant == "modified":
        return n1 * (y1 / y) ** (2 * k_fin - 1)
    k_long = math.log(n2 / n1) / math.log(y1 / y2)  # 32.6, continued beyond 1e10
    return n1 * (y1 / y) ** k_long


@pytest.mark.parametrize("variant", ["iso", "elementary", "modified"])
def test_static_miner_variants_by_hand(hoist, variant):
    life = json.loads(_run("life", str(hoist), "--static", "--miner", variant, "--format", "json").stdout)["life"]
    for member, ratio in (("pinion", 1.0), ("gear", RATIO)):
        damage = 0.0
        entry = life["stages"][0][member]["pitting"]
        for (name, hours, torque, speed), b in zip(POINTS, entry["bins"], strict=True):
            rating = _design(hoist, torque, speed)["stages"][0]["rating"][member]
            knee = rating["sigma_HG_MPa"] / rating["Z_NT"]
            n = hours * 60.0 * speed * ratio
            big_n = _cycles_to_failure(abs(rating["sigma_H_MPa"]), knee, variant)
            assert b["point"] == name
            assert_allclose(b["cycles"], n, rtol=1e-12)
            assert_allclose(b["stress_MPa"], rating["sigma_H_MPa"], rtol=1e-12)  # the reversed step: |sigma|
            assert_allclose(b["cycles_to_failure"], big_n, rtol=1e-9)  # the curve's power law, exponent 13-33
            damage += n / big_n
        assert_allclose(entry["damage"], damage, rtol=1e-9)
        # every step lies below 0.85 sigma_inf (the iso curve's last node): an infinite life on that curve; Miner
        # elementary and modified have no endurance limit: their life is the duty's hours over their damage (tr17c)
        if variant == "iso":
            assert entry["below_endurance"] is True and entry["life_h"] is None
        else:
            assert entry["below_endurance"] is False
            assert_allclose(entry["life_h"], sum(h for _, h, _, _ in POINTS) / damage, rtol=1e-9)


def _statics(ft: float, fr: float, fa: float, r_w: float, x_gear: float, span: float) -> tuple[float, float]:
    """|R| of the bearings at 0 and ``span`` of a shaft carrying F_t, F_r, F_a at x_gear (moment F_a r_w)."""
    m = fa * r_w
    ra_r = fr * (span - x_gear) / span - m / span
    rb_r = fr * x_gear / span + m / span
    ra_t, rb_t = ft * (span - x_gear) / span, ft * x_gear / span
    return math.hypot(ra_r, ra_t), math.hypot(rb_r, rb_t)


def test_reversed_step_swaps_the_input_bearings(hoist):
    """Lowering (-700 N m): F_t and F_a reverse, the separating force F_r does not; the axial force's moment now
    loads the other bearing. Hand statics of the input shaft (pinion at 80 mm between bearings at 0 and 160 mm)."""
    life = json.loads(_run("life", str(hoist), "--static", "--format", "json").stdout)["life"]
    d = _design(hoist, 1000.0, 1200.0)
    st = d["stages"][0]
    ft, fr, fa = (st["static_force_N"][k] for k in ("tangential", "radial", "axial"))
    r_w = st["pinion"]["pitch_diameter_mm"] / 2  # no profile shift: working = reference circle
    up = _statics(ft, fr, fa, r_w, 80.0, 160.0)
    down = _statics(-0.7 * ft, fr * 0.7, -0.7 * fa, r_w, 80.0, 160.0)
    assert_allclose(down, (0.7 * up[1], 0.7 * up[0]), rtol=1e-12)  # the symmetric shaft swaps them
    b1, b2 = life["bearings"][0], life["bearings"][1]
    # bearing 2 (floating, no factors): P = F_r
    assert_allclose([b2["loads_N"][0], b2["loads_N"][1]], [up[1], down[1]], rtol=1e-9)
    # bearing 1 (locating, e 0.3, X 0.56, Y 1.5): F_a / F_r > e at both points
    for k, rad in ((0, up[0]), (1, down[0])):
        axial = abs(fa) * (1.0 if k == 0 else 0.7)
        assert axial / rad > 0.3
        assert_allclose(b1["loads_N"][k], 0.56 * rad + 1.5 * axial, rtol=1e-9)


def _nu(t_c: float, nu40: float = 150.0, nu100: float = 15.0) -> float:
    """ASTM D341: log10 log10(nu + 0.7) linear in log10 T (K)."""
    y1, y2 = (math.log10(math.log10(v + 0.7)) for v in (nu40, nu100))
    b = (y1 - y2) / (math.log10(373.15) - math.log10(313.15))
    a = y1 + b * math.log10(313.15)
    return 10 ** (10 ** (a - b * math.log10(t_c + 273.15))) - 0.7


def _nu1(n: float, dm: float) -> float:
    return 45000 * n ** -0.83 * dm ** -0.5 if n < 1000 else 4500 * n ** -0.5 * dm ** -0.5


def _a_iso(kind: str, kappa: float, x: float) -> float:
    """ISO 281:2007 a_ISO of radial bearings (x = e_C C_u / P), kappa held at 4, a_ISO at most 50."""
    kappa = min(kappa, 4.0)
    e = 0.054381 if kappa < 0.4 else (0.19087 if kappa < 1 else 0.071739)
    if kind == "ball":
        c = 2.2649 if kappa < 0.4 else 1.9987
        br = 1 - (2.5671 - c / kappa ** e) ** 0.83 * x ** (1 / 3)
        return 50.0 if br <= 0 else min(50.0, 0.1 * br ** -9.3)
    c = 1.3993 if kappa < 0.4 else 1.2348
    br = 1 - (1.5859 - c / kappa ** e) * x ** 0.4
    return 50.0 if br <= 0 else min(50.0, 0.1 * br ** -9.185)


def test_modified_bearing_life_by_hand(hoist):
    """Ball bearings (d_m 45 mm: e_C 0.5 'normal' below 100 mm) and roller bearings (d_m 110 mm: e_C 0.6), a_1 1,
    0.25 (99 %) and 0.64 (95 %); the creep step turns at 600 rpm (nu_1's n < 1000 branch; the output shaft's
    194 rpm puts its kappa below 1, the 0.4 <= kappa < 1 branch)."""
    life = json.loads(_run("life", str(hoist), "--static", "--format", "json").stdout)["life"]
    nu = _nu(65.0)
    assert_allclose(nu, 46.6055, rtol=1e-5)  # the oil at 65 C
    specs = (("ball", 30e3, 700.0, 45.0, 1.0, 1.0), ("ball", 30e3, 700.0, 45.0, 0.25, 1.0),
             ("roller", 90e3, 11e3, 110.0, 0.64, RATIO), ("roller", 90e3, 11e3, 110.0, 1.0, RATIO))
    branches = set()
    for (kind, c, cu, dm, a1, ratio), b in zip(specs, life["bearings"], strict=True):
        p = 3.0 if kind == "ball" else 10 / 3
        e_c = 0.5 if dm < 100 else 0.6
        revs = [h * 60 * n * ratio for _, h, _, n in POINTS]
        loads = b["loads_N"]
        kappas = [nu / _nu1(n * ratio, dm) for _, _, _, n in POINTS]
        a_iso = [_a_iso(kind, k, e_c * cu / load) for k, load in zip(kappas, loads, strict=True)]
        branches |= {(kind, 0 if k < 0.4 else 1 if k < 1 else 2) for k in kappas}
        l_nm = [a1 * a * (c / load) ** p for a, load in zip(a_iso, loads, strict=True)]
        total = sum(revs) / 1e6 / sum(r / 1e6 / lv for r, lv in zip(revs, l_nm, strict=True))  # 10^6 rev
        p_eq = (sum(load ** p * r for load, r in zip(loads, revs, strict=True)) / sum(revs)) ** (1 / p)
        assert_allclose(b["kappa_points"], kappas, rtol=1e-12)
        assert_allclose(b["a_ISO_points"], a_iso, rtol=1e-12)
        assert_allclose(b["a_1"], a1, rtol=1e-12)
        assert_allclose(b["equivalent_load_N"], p_eq, rtol=1e-12)
        assert_allclose(b["L10_Mrev"], (c / p_eq) ** p, rtol=1e-12)  # (C/P)^p in 10^6 revolutions
        assert_allclose(b["L_nm_Mrev"], total, rtol=1e-12)
        assert_allclose(b["a_ISO"], total / (a1 * (c / p_eq) ** p), rtol=1e-12)
        assert_allclose(b["kappa"], min(kappas), rtol=1e-12)
    assert ("ball", 2) in branches and ("roller", 1) in branches and ("roller", 2) in branches


def test_idle_step_is_not_warned_as_unresolved_peaks(hoist):
    """An idle step (0 N m) on the dynamic route: its stage carries 1e-8 N of round-off after the ramps, whose
    every-second-sample peak estimate was 4e-3 of itself: a `peaks_unresolved` warning asking for 35,328 steps, which
    no sampling resolves. The peaks' error is referred to the force the run resolves (at least its mean peak), so
    the idle step is quiet; it does no damage and adds its revolutions to the bearings. The loaded steps' estimates
    are unchanged (their mean peak is the larger reference)."""
    idle = HOIST.replace("torque_Nm = 150", "torque_Nm = 0")
    path = hoist.with_name("idle.toml")
    path.write_text(idle, encoding="utf-8")
    doc = json.loads(_run("life", str(path), "--format", "json").stdout)
    codes = [(w["code"], w.get("point")) for w in doc["warnings"]]
    assert ("peaks_unresolved", "creep") not in codes, codes
    points = {p["name"]: p for p in doc["life"]["points"]}
    assert points["creep"]["peak_error"][0] < 1e-3
    pinion = doc["life"]["stages"][0]["pinion"]["pitting"]
    creep = [b for b in pinion["bins"] if b["point"] == "creep"]
    assert sum(b["cycles"] for b in creep) == pytest.approx(3000 * 60 * 600, rel=1e-9)
    assert sum(b["damage"] for b in creep) < 1e-30 * pinion["damage"]
    b = doc["life"]["bearings"][0]
    assert_allclose(b["revolutions"], sum(h * 60 * n for _, h, _, n in POINTS), rtol=1e-12)
    assert b["loads_N"][2] < 1e-3  # the idle step's equivalent load: round-off


@pytest.mark.parametrize(("set_line", "named"), [
    ('set = { "stage.0.pinion.teeth" = 25 }', "stage.0.pinion.teeth"),  # was: a 25/71 pair's damage summed with 23/71's
    ('set = { "stage[0].normal_module_mm" = 4 }', "stage[0].normal_module_mm"),
    ('set = { "materials.case.contact_fatigue_limit_MPa" = 1000 }', "materials.case.contact_fatigue_limit_MPa"),
    ('set = { rating = { material_quality = "optimum" } }', "rating.material_quality"),  # another S-N curve
    ('set = { "stage.0" = { backlash_mm = 0.1 } }', "stage.0"),  # the whole stage table
])
def test_a_point_may_not_set_another_gear(tmp_path, set_line, named):
    """The Miner sum adds one member's damage over the duty's points: a point whose `set` gives the member another
    tooth count, module, material or S-N curve was accepted and its damage added to the file's gear (the creep step's
    gear at 25 teeth: 3.80e7 cycles at 602.6 MPa summed into the 23-tooth pinion's gear). Exit 2 naming the point and
    the key, as a bearing's key is; nothing written."""
    path = tmp_path / "hoist.toml"
    path.write_text(HOIST.replace('name = "creep"\n', 'name = "creep"\n' + set_line + "\n"), encoding="utf-8")
    out = tmp_path / "life.json"
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "json", "-o", str(out)])
    assert res.exit_code == 2, res.output
    assert str(path) in res.output and "duty[2]" in res.output and named in res.output
    assert "Traceback" not in res.output and not out.exists()


def test_a_point_may_still_set_its_operating_conditions(hoist, tmp_path):
    """What a point runs under may differ (the oil's temperature, the backlash as it warms, the mesh's excitation, the
    stage efficiency): accepted; the creep step's ball bearings' kappa follows its oil by hand."""
    path = tmp_path / "hoist.toml"
    path.write_text(HOIST.replace('name = "creep"\n', 'name = "creep"\nset = { "lubricant.temperature_C" = 80, '
                                  '"stage.0.backlash_mm" = 0.12, "stage.0.efficiency" = 0.98 }\n'), encoding="utf-8")
    life = json.loads(_run("life", str(path), "--static", "--format", "json").stdout)["life"]
    assert_allclose(life["bearings"][0]["kappa_points"][2], _nu(80.0) / _nu1(600.0, 45.0), rtol=1e-12)


def test_dynamic_factors_without_static_factors_warn_that_p0_ignores_the_axial_force(hoist, tmp_path):
    """Bearing 1 (locating ball, C_0 16 kN) has the catalogue's dynamic factors but no static_factors: its ISO 76 P_0
    was F_r alone (4766.9 N, s_0 3.357) with no word, though it carries F_a = F_t tan(beta) = 1952.2 N. Now the
    `bearing_axial_not_rated` warning names static_factors (design; once over the duty in life). With them, P_0 =
    max(F_r, X0 F_r + Y0 F_a) by hand, and no warning."""
    design = json.loads(_run("design", str(hoist), "--format", "json").stdout)
    said = [w for w in design["warnings"] if w["code"] == "bearing_axial_not_rated"]
    assert [w["bearing"] for w in said] == [1, 3] and all("static_factors" in w["message"] for w in said)
    life = json.loads(_run("life", str(hoist), "--static", "--format", "json").stdout)
    assert [w["bearing"] for w in life["warnings"] if w["code"] == "bearing_axial_not_rated"] == [1, 3]
    st = design["stages"][0]
    fa = st["static_force_N"]["axial"]
    assert_allclose(fa, st["static_force_N"]["tangential"] * math.tan(math.radians(12.0)), rtol=1e-12)
    b = design["bearings"][0]
    assert_allclose(b["static_equivalent_load_N"], b["radial_N"], rtol=1e-12)  # X0 = 1, Y0 = 0: F_r alone
    path = tmp_path / "hoist.toml"
    text = HOIST.replace('factors = { e = 0.3, X = 0.56, Y = 1.5 }',
                         'factors = { e = 0.3, X = 0.56, Y = 1.5 }\nstatic_factors = { X0 = 0.5, Y0 = 2.0 }', 1)
    text = text.replace('factors = { e = 0.4, X = 0.4, Y = 1.5 }',
                        'factors = { e = 0.4, X = 0.4, Y = 1.5 }\nstatic_factors = { X0 = 0.5, Y0 = 0.9 }', 1)
    path.write_text(text, encoding="utf-8")
    design = json.loads(_run("design", str(path), "--format", "json").stdout)
    assert not [w for w in design["warnings"] if w["code"] == "bearing_axial_not_rated"]
    for j, (x0, y0, c0) in ((0, (0.5, 2.0, 16e3)), (2, (0.5, 0.9, 100e3))):
        b = design["bearings"][j]
        p0 = max(b["radial_N"], x0 * b["radial_N"] + y0 * abs(b["axial_N"]))
        assert_allclose(b["static_equivalent_load_N"], p0, rtol=1e-12)
        assert_allclose(b["static_safety"], c0 / p0, rtol=1e-12)
    assert design["bearings"][0]["static_equivalent_load_N"] > design["bearings"][0]["radial_N"]  # F_a now counts
