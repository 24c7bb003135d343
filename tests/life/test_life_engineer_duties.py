"""``gearcli life --static`` on an engineer's own duties, every figure by hand (round-4 trial, branch t9d).

Scene PAR: one spur stage 20/60, m 4, b 40, on two shafts with ISO 281 bearings (two ball bearings with the
modified life at 95 % and 99.5 % reliability, two roller bearings, one with a_ISO), over four duty steps: full
load, part load at a lower speed, a peak 56 % above the file's rated torque, and an idle step at zero load.
Scene PLANET: a sun-driven planetary stage 21/24/69 with three planets, the ring held, the carrier the output,
and the planet pins' roller bearings (K_γ 1.15, 99 % reliability), over two steps.

Written out here, independent of the code: the load cycles per member and hour (a planetary stage's from the
speeds relative to the carrier and the number of planets), the ISO 6336-2 Z_NT / ISO 6336-3 Y_NT curves of
case-carburized and through-hardened steel (nodes, log-log, the last slope continued), Miner's sum, the load
multiplier that makes D = 1 (by bisection), the shafts' reactions by the lever rule, the spectrum's equivalent
load (cubic mean for ball bearings, exponent 10/3 for roller bearings, weighted by revolutions), L10 and L10h,
the oil's viscosity by ASTM D341, ν_1 and κ, e_C, a_ISO by ISO 281:2007 eq. (8)-(13), a_1 (Table 12 and its
Weibull law) and L_nm by Palmgren–Miner over the steps. Inputs taken from gearcli are the rating's limit stress
σ_HG, σ_FG and its stresses at each point (ISO 6336-2/-3, checked elsewhere), never a life figure.

No bearing maker's worked example of a_ISO with every input printed was found (searched again: ISO 281 a_ISO
worked example, e_C C_u/P examples; docs/bearings.md lists the earlier searches), so a_ISO is checked against the
equations of ISO 281:2007 written out below, and one value against an independent reading of the standard's
Figure 3 style chart is not possible without it.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.engineer_duties import (
    D1,
    K_GAMMA,
    M_P,
    NP,
    P_STEPS,
    PAR,
    PAR_BASE,
    PLANET,
    STEPS,
    YNT_CASE,
    YNT_THROUGH,
    ZNT_CASE,
    ZNT_THROUGH,
    ZR,
    ZS,
    U,
    a_1,
    a_iso,
    cycles_to_failure,
    duty_text,
    life_factor,
    load_multiplier_by_bisection,
    nu_1,
    nu_at,
    par_reactions,
    planet_speeds,
    rating_at,
    run_life,
)


def test_par_cycles_miner_and_safety_by_hand(tmp_path):
    life = run_life(tmp_path, PAR, "--static")["life"]
    stage = life["stages"][0]
    for member, speed, nodes_h, nodes_f in (("pinion", 1.0, ZNT_CASE, YNT_CASE),
                                            ("gear", 1.0 / U, ZNT_CASE, YNT_CASE)):
        for mode, nodes in (("pitting", nodes_h), ("bending", nodes_f)):
            ml = stage[member][mode]
            bins = ml["bins"]
            assert [b["point"] for b in bins] == [s[0] for s in STEPS]
            raw = []
            for b, (_, hours, torque, n_in) in zip(bins, STEPS, strict=True):
                # one load cycle per revolution of the member: hours x 60 x n_member
                assert_allclose(b["cycles"], hours * 60.0 * n_in * speed, rtol=1e-12)
                # the tooth force: F_t = 2 T_1 / d_1 with T_1 = T_out / u
                assert_allclose(b["force_N"], 2.0 * torque / U * 1e3 / D1, rtol=1e-12, atol=1e-9)
                if torque == 0.0:  # the idle step: no stress, no damage, its cycles still counted
                    assert b["stress_MPa"] == 0.0 and b["damage"] == 0.0 and b["cycles_to_failure"] is None
                    continue
                r = getattr(rating_at(PAR, torque, n_in), member)
                stress = r.sigma_H_MPa if mode == "pitting" else r.sigma_F_MPa
                assert_allclose(b["stress_MPa"], stress, rtol=1e-12)
                # sigma_inf: the rating's limit stress over its own life factor at the rating's N_L, where N_L is
                # the required 20 000 h at the member's speed (Z_NT / Y_NT by hand at it)
                n_l = 20000.0 * 60.0 * n_in * speed
                factor = r.Z_NT if mode == "pitting" else r.Y_NT
                assert_allclose(factor, life_factor(n_l, nodes), rtol=1e-12)
                limit = r.sigma_HG_MPa if mode == "pitting" else r.sigma_FG_MPa
                sigma_inf = limit / life_factor(n_l, nodes)
                assert_allclose(b["endurance_MPa"], sigma_inf, rtol=1e-12)
                n_f = cycles_to_failure(stress / sigma_inf, nodes)
                assert_allclose(b["cycles_to_failure"], n_f, rtol=1e-9)
                assert_allclose(b["damage"], b["cycles"] / n_f, rtol=1e-9)
                raw.append((stress, b["cycles"], sigma_inf))
            damage = sum(n / cycles_to_failure(s / si, nodes) for s, n, si in raw)
            assert_allclose(ml["damage"], damage, rtol=1e-9)
            # every stress below 0.85 sigma_inf (the last node): an infinite life, the damage still summed
            below = all(s < 0.85 * si for s, _, si in raw)
            assert ml["below_endurance"] is below and (ml["life_h"] is None) is below
            exponent = 0.5 if mode == "pitting" else 1.0  # sigma_H ~ sqrt(F_t), sigma_F ~ F_t
            s = load_multiplier_by_bisection(lambda k, raw=raw, nodes=nodes, exponent=exponent:
                            sum(n / cycles_to_failure(st * k ** exponent / si, nodes) for st, n, si in raw))
            assert_allclose(ml["load_multiplier"], s, rtol=1e-9)
            assert_allclose(ml["stress_safety"], s ** exponent, rtol=1e-9)


def test_par_peak_above_rated_torque_dominates_the_pinion_flank(tmp_path):
    """The 200 h peak step (1400 N·m, 56 % over the file's 900) on 1 % of the hours does most of the pinion's
    pitting damage: N ∝ sigma^-32.6 beyond the knee (k = ln 200 / ln(1/0.85), written out)."""
    ml = run_life(tmp_path, PAR, "--static")["life"]["stages"][0]["pinion"]["pitting"]
    by = {b["point"]: b for b in ml["bins"]}
    k = math.log(1e10 / 5e7) / math.log(1.0 / 0.85)
    assert_allclose(k, 32.6, rtol=1e-3)
    # full and peak at the same speed (same sigma_inf): N_full / N_peak = (sigma_peak / sigma_full)^k
    assert_allclose(by["full"]["cycles_to_failure"] / by["peak"]["cycles_to_failure"],
                    (by["peak"]["stress_MPa"] / by["full"]["stress_MPa"]) ** k, rtol=1e-9)
    assert by["peak"]["damage"] > 0.85 * ml["damage"]


def test_par_bearings_iso281_by_hand(tmp_path):
    life = run_life(tmp_path, PAR, "--static")["life"]
    bearings = life["bearings"]
    hours = sum(s[1] for s in STEPS)
    nu = nu_at(70.0, 150.0, 15.0)
    assert 35.0 < nu < 45.0  # an ISO VG 150 oil at 70 °C (sanity of the D341 fit)
    # (shaft, near?, kind, C N, C_u N, d_m, reliability) per bearing, in file order
    spec = ((1, True, "ball", 30e3, 800.0, 45.0, 95.0), (1, False, "ball", 30e3, 800.0, 45.0, 99.5),
            (2, False, "roller", 90e3, 9000.0, 110.0, 90.0), (2, True, "roller", 90e3, None, None, None))
    for b, (shaft, near, kind, c_N, cu_N, d_m, rel) in zip(bearings, spec, strict=True):
        p_exp = 3.0 if kind == "ball" else 10.0 / 3.0
        loads = [(par_reactions(t)[0 if near else 1]) for _, _, t, _ in STEPS]
        assert_allclose(b["loads_N"], loads, rtol=1e-9, atol=1e-9)
        speeds = [n if shaft == 1 else n / U for _, _, _, n in STEPS]
        revs = [h * 60.0 * n for (_, h, _, _), n in zip(STEPS, speeds, strict=True)]
        assert_allclose(b["revolutions"], sum(revs), rtol=1e-12)
        # the spectrum's equivalent load: (sum P_i^p N_i / sum N_i)^(1/p), p = 3 ball, 10/3 roller
        p_eq = (sum(p ** p_exp * r for p, r in zip(loads, revs, strict=True)) / sum(revs)) ** (1.0 / p_exp)
        assert_allclose(b["equivalent_load_N"], p_eq, rtol=1e-9)
        l10 = (c_N / p_eq) ** p_exp
        assert_allclose(b["L10_Mrev"], l10, rtol=1e-9)
        mean_rpm = sum(revs) / (60.0 * hours)
        assert_allclose(b["L10_h"], l10 * 1e6 / (60.0 * mean_rpm), rtol=1e-9)
        if cu_N is None:
            assert "a_ISO" not in b and "L_nm_h" not in b
            continue
        # ISO 281 Table 13, normal cleanliness: 0.6-0.5 (d_m < 100 mm), 0.8-0.6 (d_m >= 100 mm), as the MESYS manual
        # transcribes it (mesys.ag/manual-DE/contamination_factor.html); gearcli takes the lower end
        e_c = 0.5 if d_m < 100.0 else 0.6
        kappas = [nu / nu_1(n, d_m) for n in speeds]
        assert_allclose(b["kappa_points"], kappas, rtol=1e-9)
        assert_allclose(b["kappa"], min(kappas), rtol=1e-9)
        # the idle step carries no load: ISO 281's e_C C_u / P is not defined at P = 0, no a_ISO (null, as design)
        a_isos = [a_iso(k, e_c * cu_N / p, kind) if p > 0 else None for k, p in zip(kappas, loads, strict=True)]
        assert loads[3] == 0.0 and b["a_ISO_points"][3] is None
        assert_allclose([a for a in b["a_ISO_points"] if a is not None], [a for a in a_isos if a is not None],
                        rtol=1e-9)
        a1 = a_1(rel)
        assert_allclose(b["a_1"], a1, rtol=1e-12)
        # Palmgren–Miner over the steps: L_nm = sum N_i / sum (N_i / L_nm,i), L_nm,i = a_1 a_ISO,i (C/P_i)^p
        inverse = sum(r / (a1 * a * (c_N / p) ** p_exp * 1e6) for r, a, p in zip(revs, a_isos, loads, strict=True)
                      if p > 0)
        l_nm = sum(revs) / inverse / 1e6
        assert_allclose(b["L_nm_Mrev"], l_nm, rtol=1e-9)
        assert_allclose(b["L_nm_h"], l_nm * 1e6 / (60.0 * mean_rpm), rtol=1e-9)
        assert_allclose(b["a_ISO"], l_nm / (a1 * l10), rtol=1e-9)
    # a_1 between Table 12's printed 99.4 % (0.19) and 99.6 % (0.16): 0.1747 by the Weibull law
    assert 0.16 < bearings[1]["a_1"] < 0.19
    # ISO 76: s_0 = C_0 / P_0 at the largest P_0 of the duty, the peak step's F_r (no static factors: P_0 = F_r)
    assert_allclose(bearings[0]["static_safety"], 20e3 / par_reactions(1400.0)[0], rtol=1e-9)


def test_a_iso_branches_written_out():
    """Hand values of the equations above at chosen points (the code's a_ISO against them)."""
    from gearcli.design.iso281 import life_modification_factor, reference_viscosity_mm2_s

    for kind in ("ball", "roller"):
        for kappa in (0.05, 0.1, 0.25, 0.399, 0.4, 0.7, 0.999, 1.0, 2.5, 4.0, 6.0):
            for x in (0.0, 0.01, 0.05, 0.2, 0.5, 1.0, 3.0):
                assert_allclose(life_modification_factor(kappa, x, kind), a_iso(kappa, x, kind), rtol=1e-12)
    for n in (10.0, 999.0, 1000.0, 5000.0):
        assert_allclose(reference_viscosity_mm2_s(n, 60.0), nu_1(n, 60.0), rtol=1e-12)
    # one value worked to the last digit: roller, kappa 0.5, e_C C_u / P = 0.1:
    # 1.2348 / 0.5^0.19087 = 1.2348 x 2^0.19087 = 1.2348 x 1.141452 = 1.409465; 1.5859 - that = 0.176435;
    # 0.1^0.4 = 0.398107; bracket = 1 - 0.070240 = 0.929760; a_ISO = 0.1 x 0.929760^-9.185 = 0.19522
    inner = 1.5859 - 1.2348 * 2.0 ** 0.19087
    assert_allclose(inner, 0.176435, atol=2e-6)
    assert_allclose(a_iso(0.5, 0.1, "roller"), 0.1 * (1.0 - inner * 0.1 ** 0.4) ** -9.185, rtol=1e-12)
    assert_allclose(a_iso(0.5, 0.1, "roller"), 0.19522, rtol=1e-4)  # the digits above


def test_planetary_cycles_per_member_and_the_pin_bearings_by_hand(tmp_path):
    life = run_life(tmp_path, PLANET + duty_text(P_STEPS), "--static")["life"]
    stage = life["stages"][0]
    expected = {}
    for name, hours, _, n_s in P_STEPS:
        sun_rel, n_c, planet_rel = planet_speeds(n_s)
        expected[name] = {"pinion": hours * 60.0 * sun_rel * NP,  # a sun tooth meets every planet per relative turn
                          "ring": hours * 60.0 * n_c * NP,  # a ring tooth likewise, the ring |0 - n_c|
                          "gear": hours * 60.0 * planet_rel,  # one sun-side contact per planet turn
                          "planet_ring_side": hours * 60.0 * planet_rel}
    for member in ("pinion", "gear", "ring", "planet_ring_side"):
        for mode in ("pitting", "bending"):
            for b in stage[member][mode]["bins"]:
                assert_allclose(b["cycles"], expected[b["point"]][member], rtol=1e-12)
    # the DESIGN §10 names: sun = pinion, planet.bending = the root over both meshes
    assert stage["sun"] == stage["pinion"]
    assert_allclose(stage["planet"]["bending"]["damage"],
                    stage["gear"]["bending"]["damage"] + stage["planet_ring_side"]["bending"]["damage"], rtol=1e-12)
    # the ring's flank on the through-hardened curve (ISO 6336-2 Table 2), its sigma_inf from its rating
    path = tmp_path / "planet_design.toml"
    path.write_text(PLANET)
    res = CliRunner().invoke(cli, ["-q", "design", str(path), "--format", "json", "--set", "load.application_factor=1"])
    assert res.exit_code == 0, res.output
    ring = json.loads(res.stdout)["stages"][0]["meshes"][1]["rating"]["gear"]
    n_l = 10000.0 * 60.0 * planet_speeds(1500.0)[1] * NP
    assert_allclose(ring["load_cycles"], n_l, rtol=1e-12)
    assert_allclose(ring["Z_NT"], life_factor(n_l, ZNT_THROUGH), rtol=1e-12)
    sigma_inf = ring["sigma_HG_MPa"] / life_factor(n_l, ZNT_THROUGH)
    full = next(b for b in stage["ring"]["pitting"]["bins"] if b["point"] == "full")
    assert_allclose(full["stress_MPa"], ring["sigma_H_MPa"], rtol=1e-12)
    assert_allclose(full["cycles_to_failure"], cycles_to_failure(full["stress_MPa"] / sigma_inf, ZNT_THROUGH),
                    rtol=1e-9)
    # and its root on Y_NT of through-hardened steel (static node 1e4 at 2.5, ISO 6336-3 Table 3)
    assert_allclose(ring["Y_NT"], life_factor(n_l, YNT_THROUGH), rtol=1e-12)
    sigma_f_inf = ring["sigma_FG_MPa"] / life_factor(n_l, YNT_THROUGH)
    root = next(b for b in stage["ring"]["bending"]["bins"] if b["point"] == "full")
    assert_allclose(root["stress_MPa"], ring["sigma_F_MPa"], rtol=1e-12)
    assert_allclose(root["cycles_to_failure"], cycles_to_failure(root["stress_MPa"] / sigma_f_inf, YNT_THROUGH),
                    rtol=1e-9)
    # the planet pins: per planet F_t = T_sun / (N r_sun), T_sun = T_out / (1 + z_r / z_s); the sun and the ring push
    # the planet the same way: 2 F_t K_gamma on the pin, half on each bearing (symmetric at 85 / 115 mm)
    for b in life["bearings"]:
        loads = []
        for _, _, t_out, _ in P_STEPS:
            ft = t_out * 1e3 / (1.0 + ZR / ZS) / (NP * ZS * M_P / 2.0)
            loads.append(2.0 * ft * K_GAMMA / 2.0)
        assert_allclose(b["loads_N"], loads, rtol=1e-9)
        revs = [h * 60.0 * planet_speeds(n)[2] for _, h, _, n in P_STEPS]  # the pin turns at n_p relative
        assert_allclose(b["revolutions"], sum(revs), rtol=1e-12)
        p_exp = 10.0 / 3.0
        p_eq = (sum(p ** p_exp * r for p, r in zip(loads, revs, strict=True)) / sum(revs)) ** (1.0 / p_exp)
        assert_allclose(b["equivalent_load_N"], p_eq, rtol=1e-9)
        assert_allclose(b["L10_Mrev"], (40e3 / p_eq) ** p_exp, rtol=1e-9)
        nu = nu_at(70.0, 220.0, 19.0)
        kappas = [nu / nu_1(planet_speeds(n)[2], 40.0) for _, _, _, n in P_STEPS]
        assert_allclose(b["kappa_points"], kappas, rtol=1e-9)
        a_isos = [a_iso(k, 0.4 * 4000.0 / p, "roller") for k, p in zip(kappas, loads, strict=True)]
        assert_allclose(b["a_ISO_points"], a_isos, rtol=1e-9)
        assert b["a_1"] == 0.25  # ISO 281 Table 12 at 99 %
        l_nm = sum(revs) / sum(r / (0.25 * a * (40e3 / p) ** p_exp * 1e6)
                               for r, a, p in zip(revs, a_isos, loads, strict=True)) / 1e6
        assert_allclose(b["L_nm_Mrev"], l_nm, rtol=1e-9)


def test_hours_that_do_not_add_up_to_the_required_life(tmp_path):
    """The same spectrum as time shares (0.2 / 0.6 / 0.01 / 0.19 = 100 % of 1 h) instead of hours over the 20 000 h:
    a `duty` warning names the sum; D scales with the hours (every class's cycles do), the life in hours does
    not, and the load multiplier is that of D over 1 h."""
    shares = tuple((n, h / 20000.0, t, s) for n, h, t, s in STEPS)
    full = run_life(tmp_path, PAR, "--static")
    frac = run_life(tmp_path, PAR_BASE + duty_text(shares), "--static")
    assert not [w for w in full["warnings"] if w["code"] == "duty"]
    said = [w for w in frac["warnings"] if w["code"] == "duty"]
    assert len(said) == 1 and said[0]["hours"] == pytest.approx(1.0) and said[0]["required_life_h"] == 20000.0
    a, b = full["life"]["stages"][0]["pinion"]["pitting"], frac["life"]["stages"][0]["pinion"]["pitting"]
    assert_allclose(b["damage"], a["damage"] / 20000.0, rtol=1e-9)
    assert b["load_multiplier"] > a["load_multiplier"]
    # the bearings: the same equivalent load and lives (revolutions scale, the p-mean does not)
    for x, y in zip(full["life"]["bearings"], frac["life"]["bearings"], strict=True):
        assert_allclose(y["equivalent_load_N"], x["equivalent_load_N"], rtol=1e-9)
        assert_allclose(y["L10_h"], x["L10_h"], rtol=1e-9)


@pytest.mark.parametrize("variant", ["elementary", "modified"])
def test_miner_variants_below_the_knee_by_hand(tmp_path, variant):
    """ISO 6336-6's Miner variants on the same bins: elementary continues the finite-life slope k (static node 1e5
    at 1.6, knee 5e7 at 1.0: k = ln 500 / ln 1.6 = 13.22) below the knee; modified (Haibach) uses 2k - 1 there."""
    life = run_life(tmp_path, PAR, "--static", "--miner", variant)["life"]
    assert variant in life["miner"].lower() or "haibach" in life["miner"].lower()
    k = math.log(5e7 / 1e5) / math.log(1.6)
    assert_allclose(k, 13.22, rtol=1e-3)
    for b in life["stages"][0]["pinion"]["pitting"]["bins"]:
        if b["stress_MPa"] == 0.0:
            continue
        ratio = b["stress_MPa"] / b["endurance_MPa"]
        assert ratio < 1.0  # every loaded step of this duty lies below the knee
        n_f = 1e5 * (1.6 / ratio) ** k if variant == "elementary" else 5e7 * (1.0 / ratio) ** (2.0 * k - 1.0)
        assert_allclose(b["cycles_to_failure"], n_f, rtol=1e-9)


CENTRAL_BEARINGS = """
[[bearing]]
shaft = 1
position_mm = 20
dynamic_load_rating_kN = 20
kind = "ball"
locating = true
fatigue_load_limit_kN = 1
pitch_diameter_mm = 40
static_load_rating_kN = 10

[[bearing]]
shaft = 1
position_mm = 180
dynamic_load_rating_kN = 20
kind = "ball"

[[bearing]]
shaft = 2
position_mm = 150
dynamic_load_rating_kN = 50
kind = "roller"
locating = true
"""


def test_central_members_of_equally_spaced_planets_carry_no_bearing_load(tmp_path):
    """Three identical planets 120° apart: their radial forces on the sun (and through the pins on the carrier) sum
    to zero, spur teeth add no axial force: P = 0, L10 = (C/P)^p unbounded (JSON null), and the tables print ∞ as
    they do for a gear's infinite life (they printed "—", the sign of a figure not computed)."""
    text = PLANET + CENTRAL_BEARINGS + "\n[[bearing]]\nshaft = 2\nposition_mm = 250\ndynamic_load_rating_kN = 50\n" \
        'kind = "roller"\n' + duty_text(P_STEPS)
    life = run_life(tmp_path, text, "--static")["life"]
    central = [b for b in life["bearings"] if b["shaft"] in (1, 2)]
    assert len(central) == 4
    for b in central:
        assert b["equivalent_load_N"] == 0.0 and b["L10_Mrev"] is None and b["L10_h"] is None
    assert central[0]["L_nm_Mrev"] is None and central[0]["static_safety"] is None
    path = tmp_path / "table.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["-q", "life", str(path), "--static", "--format", "table"], terminal_width=250)
    assert res.exit_code == 0, res.output
    rows = {line.split("│")[1].strip(): [c.strip() for c in line.split("│")[2:-1]]
            for line in res.output.splitlines() if line.count("│") > 3}
    # bearings 1, 2: the planet pins (finite); 3-6: the sun's and the carrier's (unloaded)
    assert rows["L10 [10^6 rev]"][2:] == ["∞"] * 4 and rows["L10h [h]"][2:] == ["∞"] * 4
    assert rows["L10 [10^6 rev]"][0] not in ("∞", "—")
    assert rows["L_nm [10^6 rev]"][2] == "∞" and rows["L_nm [10^6 rev]"][3] == "—"  # no C_u: not computed
    assert next(v for k, v in rows.items() if k.startswith("static safety s_0"))[2] == "∞"
