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
from tests.life.scenes import design_of

MATERIAL = """
[materials.st]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 500
"""

PAR_BASE = MATERIAL + """
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 0
accuracy_grade = 6
pinion = { teeth = 20, face_width_mm = 40, material = "st", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10, axial_position_mm = 100 }
gear   = { teeth = 60, face_width_mm = 40, material = "st", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10, axial_position_mm = 100 }

[input]
speed_rpm = 1500
ramp_s = 0.05

[load]
torque_Nm = 900
ramp_s = 0.05

[lubricant]
viscosity_40C_mm2_s = 150
viscosity_100C_mm2_s = 15
temperature_C = 70
contamination = "normal"

[rating]
required_life_h = 20000
min_safety_pitting = 1.0
min_safety_bending = 1.4

[simulation]
duration_s = 0.3
steps = 2000

[[bearing]]
shaft = 1
position_mm = 50
dynamic_load_rating_kN = 30
kind = "ball"
locating = true
fatigue_load_limit_kN = 0.8
pitch_diameter_mm = 45
reliability_percent = 95
static_load_rating_kN = 20

[[bearing]]
shaft = 1
position_mm = 200
dynamic_load_rating_kN = 30
kind = "ball"
fatigue_load_limit_kN = 0.8
pitch_diameter_mm = 45
reliability_percent = 99.5

[[bearing]]
shaft = 2
position_mm = 0
dynamic_load_rating_kN = 90
kind = "roller"
locating = true
fatigue_load_limit_kN = 9
pitch_diameter_mm = 110

[[bearing]]
shaft = 2
position_mm = 150
dynamic_load_rating_kN = 90
kind = "roller"
"""

# (name, hours, output torque N·m, input speed rpm); the hours sum to the required 20 000 h
STEPS = (("full", 4000.0, 900.0, 1500.0), ("part", 12000.0, 500.0, 1000.0), ("peak", 200.0, 1400.0, 1500.0),
         ("idle", 3800.0, 0.0, 1500.0))


def _duty(steps) -> str:
    return "".join(f'\n[[duty]]\nname = "{n}"\nhours = {h!r}\ntorque_Nm = {t!r}\nspeed_rpm = {s!r}\n'
                   for n, h, t, s in steps)


PAR = PAR_BASE + _duty(STEPS)
Z1, Z2, M_MM, ALPHA = 20, 60, 4.0, math.radians(20.0)
U = Z2 / Z1
D1 = Z1 * M_MM  # spur: the reference diameter 80 mm

# ISO 6336-2:2006 Table 2 / ISO 6336-3:2006 Table 3, normal quality (static node, knee, 1e10)
ZNT_CASE = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))
YNT_CASE = ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85))
ZNT_THROUGH = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))  # St, V, GGG (perl., bai.), GTS (perl.): no pitting permitted
YNT_THROUGH = ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85))  # V, GGG (perl., bai.), GTS (perl.)


def _run(tmp_path, text: str, *args: str) -> dict:
    path = tmp_path / "scene.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["-q", "life", str(path), "--format", "json", *args])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _factor(n: float, nodes) -> float:
    """The life factor Z_NT / Y_NT at N cycles: log-log between the nodes, flat at the static value below it,
    the last slope continued beyond 1e10."""
    (n0, y0), (n1, y1), (n2, y2) = nodes
    if n <= n0:
        return y0
    a, b = ((n0, y0), (n1, y1)) if n <= n1 else ((n1, y1), (n2, y2))
    return a[1] * (b[1] / a[1]) ** (math.log(n / a[0]) / math.log(b[0] / a[0]))


def _cycles_to_failure(ratio: float, nodes) -> float:
    """Invert sigma / sigma_inf = factor(N): N = N_a (y_a / ratio)^k on the branch, k = ln(N_b/N_a) / ln(y_a/y_b)."""
    (n0, y0), (n1, y1), (n2, y2) = nodes
    if ratio <= 0.0:
        return math.inf
    if ratio >= y1:
        return n0 * (y0 / ratio) ** (math.log(n1 / n0) / math.log(y0 / y1))
    return n1 * (y1 / ratio) ** (math.log(n2 / n1) / math.log(y1 / y2))


def _multiplier(damage_at) -> float:
    """The load multiplier s with D(s) = 1, by bisection on ln s (independent of the code's brentq)."""
    lo, hi = math.log(1e-3), math.log(1e3)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if damage_at(math.exp(mid)) < 1.0 else (lo, mid)
    return math.exp(0.5 * (lo + hi))


def _rating(text: str, torque_Nm: float, speed_rpm: float):
    """The ISO 6336 rating of `gearcli design` at one step (K_A = 1): its stresses and limit stresses."""
    _, d = design_of(text, (f"input.speed_rpm={speed_rpm!r}", f"load.torque_Nm={torque_Nm!r}",
                            "load.application_factor=1.0"))
    return d.stages[0].rating


# --- ISO 281:2007, written out ------------------------------------------------------------------------------

def nu_at(t_C: float, nu40: float, nu100: float) -> float:
    """ASTM D341: log10 log10(nu + 0.7) = A - B log10(T), T in K, through the 40 and 100 °C values."""
    w = lambda nu: math.log10(math.log10(nu + 0.7))  # noqa: E731
    x = lambda t: math.log10(t + 273.15)  # noqa: E731
    b = (w(nu40) - w(nu100)) / (x(100.0) - x(40.0))
    return 10.0 ** (10.0 ** (w(nu40) - b * (x(t_C) - x(40.0)))) - 0.7


def nu_1(n_rpm: float, d_m: float) -> float:
    """ISO 281 eq. (A.?) / 6.5.2.4: the rated viscosity nu_1."""
    return 45000.0 * n_rpm ** -0.83 * d_m ** -0.5 if n_rpm < 1000.0 else 4500.0 * n_rpm ** -0.5 * d_m ** -0.5


def a_iso(kappa: float, x: float, kind: str) -> float:
    """ISO 281:2007 eq. (8)-(10) radial ball, (11)-(13) radial roller; x = e_C C_u / P; kappa in [0.1, 4];
    a_ISO <= 50."""
    k = min(max(kappa, 0.1), 4.0)
    if kind == "ball":
        if k < 0.4:
            inner = 2.5671 - 2.2649 / k ** 0.054381
        elif k < 1.0:
            inner = 2.5671 - 1.9987 / k ** 0.19087
        else:
            inner = 2.5671 - 1.9987 / k ** 0.071739
        bracket = 1.0 - inner ** 0.83 * x ** (1.0 / 3.0)
        return 50.0 if bracket <= 0 else min(50.0, 0.1 * bracket ** -9.3)
    if k < 0.4:
        inner = 1.5859 - 1.3993 / k ** 0.054381
    elif k < 1.0:
        inner = 1.5859 - 1.2348 / k ** 0.19087
    else:
        inner = 1.5859 - 1.2348 / k ** 0.071739
    bracket = 1.0 - inner * x ** 0.4
    return 50.0 if bracket <= 0 else min(50.0, 0.1 * bracket ** -9.185)


def a_1(r_percent: float) -> float:
    """ISO 281 Table 12 where printed, else the Weibull law it rounds (ISO/TR 1281-2, shape 1.5, t_0 0.05)."""
    table = {90.0: 1.0, 95.0: 0.64, 99.0: 0.25}
    if r_percent in table:
        return table[r_percent]
    return 0.95 * (math.log(r_percent / 100.0) / math.log(0.9)) ** (2.0 / 3.0) + 0.05


# --- scene PAR ------------------------------------------------------------------------------------------------

def _par_reactions(torque_out_Nm: float) -> tuple[float, float]:
    """|F_r| of the near (2/3) and far (1/3) bearings of either shaft: the gear mid-way... at 100 mm between
    bearings at 50/200 (shaft 1) and 0/150 (shaft 2): the lever rule gives 100/150 and 50/150 of the tooth
    normal force F_t / cos(alpha) (spur, no axial force, loss-free)."""
    ft = 2.0 * torque_out_Nm / U * 1e3 / D1
    fn = ft / math.cos(ALPHA)
    return fn * 2.0 / 3.0, fn / 3.0


def test_par_cycles_miner_and_safety_by_hand(tmp_path):
    life = _run(tmp_path, PAR, "--static")["life"]
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
                r = getattr(_rating(PAR, torque, n_in), member)
                stress = r.sigma_H_MPa if mode == "pitting" else r.sigma_F_MPa
                assert_allclose(b["stress_MPa"], stress, rtol=1e-12)
                # sigma_inf: the rating's limit stress over its own life factor at the rating's N_L, where N_L is
                # the required 20 000 h at the member's speed (Z_NT / Y_NT by hand at it)
                n_l = 20000.0 * 60.0 * n_in * speed
                factor = r.Z_NT if mode == "pitting" else r.Y_NT
                assert_allclose(factor, _factor(n_l, nodes), rtol=1e-12)
                limit = r.sigma_HG_MPa if mode == "pitting" else r.sigma_FG_MPa
                sigma_inf = limit / _factor(n_l, nodes)
                assert_allclose(b["endurance_MPa"], sigma_inf, rtol=1e-12)
                n_f = _cycles_to_failure(stress / sigma_inf, nodes)
                assert_allclose(b["cycles_to_failure"], n_f, rtol=1e-9)
                assert_allclose(b["damage"], b["cycles"] / n_f, rtol=1e-9)
                raw.append((stress, b["cycles"], sigma_inf))
            damage = sum(n / _cycles_to_failure(s / si, nodes) for s, n, si in raw)
            assert_allclose(ml["damage"], damage, rtol=1e-9)
            # every stress below 0.85 sigma_inf (the last node): an infinite life, the damage still summed
            below = all(s < 0.85 * si for s, _, si in raw)
            assert ml["below_endurance"] is below and (ml["life_h"] is None) is below
            exponent = 0.5 if mode == "pitting" else 1.0  # sigma_H ~ sqrt(F_t), sigma_F ~ F_t
            s = _multiplier(lambda k, raw=raw, nodes=nodes, exponent=exponent:
                            sum(n / _cycles_to_failure(st * k ** exponent / si, nodes) for st, n, si in raw))
            assert_allclose(ml["load_multiplier"], s, rtol=1e-9)
            assert_allclose(ml["stress_safety"], s ** exponent, rtol=1e-9)


def test_par_peak_above_rated_torque_dominates_the_pinion_flank(tmp_path):
    """The 200 h peak step (1400 N·m, 56 % over the file's 900) on 1 % of the hours does most of the pinion's
    pitting damage: N ∝ sigma^-32.6 beyond the knee (k = ln 200 / ln(1/0.85), written out)."""
    ml = _run(tmp_path, PAR, "--static")["life"]["stages"][0]["pinion"]["pitting"]
    by = {b["point"]: b for b in ml["bins"]}
    k = math.log(1e10 / 5e7) / math.log(1.0 / 0.85)
    assert_allclose(k, 32.6, rtol=1e-3)
    # full and peak at the same speed (same sigma_inf): N_full / N_peak = (sigma_peak / sigma_full)^k
    assert_allclose(by["full"]["cycles_to_failure"] / by["peak"]["cycles_to_failure"],
                    (by["peak"]["stress_MPa"] / by["full"]["stress_MPa"]) ** k, rtol=1e-9)
    assert by["peak"]["damage"] > 0.85 * ml["damage"]


def test_par_bearings_iso281_by_hand(tmp_path):
    life = _run(tmp_path, PAR, "--static")["life"]
    bearings = life["bearings"]
    hours = sum(s[1] for s in STEPS)
    nu = nu_at(70.0, 150.0, 15.0)
    assert 35.0 < nu < 45.0  # an ISO VG 150 oil at 70 °C (sanity of the D341 fit)
    # (shaft, near?, kind, C N, C_u N, d_m, reliability) per bearing, in file order
    spec = ((1, True, "ball", 30e3, 800.0, 45.0, 95.0), (1, False, "ball", 30e3, 800.0, 45.0, 99.5),
            (2, False, "roller", 90e3, 9000.0, 110.0, 90.0), (2, True, "roller", 90e3, None, None, None))
    for b, (shaft, near, kind, c_N, cu_N, d_m, rel) in zip(bearings, spec, strict=True):
        p_exp = 3.0 if kind == "ball" else 10.0 / 3.0
        loads = [(_par_reactions(t)[0 if near else 1]) for _, _, t, _ in STEPS]
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
        a_isos = [a_iso(k, e_c * cu_N / p if p > 0 else math.inf, kind) for k, p in zip(kappas, loads, strict=True)]
        assert_allclose(b["a_ISO_points"], a_isos, rtol=1e-9)
        assert a_isos[3] == 50.0  # the idle step: no load, a_ISO at its cap
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
    assert_allclose(bearings[0]["static_safety"], 20e3 / _par_reactions(1400.0)[0], rtol=1e-9)


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


# --- the duty's own keys in a step's set ---------------------------------------------------------------------

STEP = '\n[[duty]]\nname = "x"\nhours = 20000\ntorque_Nm = 900\nspeed_rpm = 1000\n'


@pytest.mark.parametrize(("set_line", "named"), [
    # a nested table wrote the step's own speed and torque past the check: the table and JSON reported 1000 rpm
    # and 900 N·m while the damage was computed at 3 rpm / 3 N·m
    ('set = { input = { speed_rpm = 3 } }', "input.speed_rpm"),
    ('set = { load = { torque_Nm = 3, ramp_s = 0.05 } }', "load.torque_Nm"),
    ("set = { 'input.\"speed_rpm\"' = 3 }", 'input."speed_rpm"'),  # a quoted segment, as --set reads it
    ('set = { "stage[0].gear.teeth" = 61, "load.application_factor" = 2 }', "load.application_factor"),
    # the duty's verdicts read the first step's file: its set moved the duty's required life and minimum safety
    ('set = { "rating.required_life_h" = 5 }', "rating.required_life_h"),
    ('set = { rating = { min_safety_pitting = 3 } }', "rating.min_safety_pitting"),
    ('set = { "stage[0].gear.teeth" = 61, "bearing[0].reliability_percent" = 95 }', "bearing[0].reliability_percent"),
    ('set = { "duty.0.hours" = 5 }', "duty.0.hours"),
    ('set = { bearing = [] }', "bearing"),
])
def test_a_step_may_not_set_the_points_or_the_dutys_own_keys(tmp_path, set_line, named):
    path = tmp_path / "scene.toml"
    path.write_text(PAR_BASE + STEP + set_line + "\n")
    res = CliRunner().invoke(cli, ["life", str(path), "--static"])
    assert res.exit_code == 2, res.output
    assert str(path) in res.output and "duty[0]" in res.output and named in res.output
    assert "Traceback" not in res.output


def test_a_steps_other_keys_still_apply(tmp_path):
    """The oil's temperature may differ per step (docs/life.md): kappa of that step follows it by hand."""
    text = PAR_BASE + STEP + 'set = { "lubricant.temperature_C" = 90 }\n'
    b = _run(tmp_path, text, "--static")["life"]["bearings"][0]
    assert_allclose(b["kappa_points"], [nu_at(90.0, 150.0, 15.0) / nu_1(1000.0, 45.0)], rtol=1e-9)


# --- scene PLANET ----------------------------------------------------------------------------------------------

PLANET = MATERIAL + """
[materials.qt]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "through_hardened"
contact_fatigue_limit_MPa = 750
bending_fatigue_limit_MPa = 320

[[stage]]
type = "planetary"
normal_module_mm = 3
normal_pressure_angle_deg = 20
accuracy_grade = 6
sun    = { teeth = 21, face_width_mm = 40, material = "st", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10, axial_position_mm = 100 }
planet = { teeth = 24, face_width_mm = 40, count = 3, material = "st", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10, axial_position_mm = 100 }
ring   = { teeth = 69, face_width_mm = 40, material = "qt", flank_roughness_Rz_um = 6, root_roughness_Rz_um = 10, axial_position_mm = 100 }
fixed = "ring"
input = "sun"

[input]
speed_rpm = 1500

[load]
torque_Nm = 1500

[lubricant]
viscosity_40C_mm2_s = 220
viscosity_100C_mm2_s = 19
temperature_C = 70
e_C = 0.4

[rating]
required_life_h = 10000
load_sharing_factor = 1.15
min_safety_pitting = 1.0
min_safety_bending = 1.4

[[bearing]]
planet_stage = 1
position_mm = 85
dynamic_load_rating_kN = 40
kind = "roller"
locating = true
fatigue_load_limit_kN = 4
pitch_diameter_mm = 40
reliability_percent = 99

[[bearing]]
planet_stage = 1
position_mm = 115
dynamic_load_rating_kN = 40
kind = "roller"
fatigue_load_limit_kN = 4
pitch_diameter_mm = 40
reliability_percent = 99
"""
P_STEPS = (("full", 3000.0, 1500.0, 1500.0), ("half", 7000.0, 750.0, 1200.0))
ZS, ZP, ZR, NP, M_P, K_GAMMA = 21, 24, 69, 3, 3.0, 1.15


def _planet_speeds(n_sun: float) -> tuple[float, float, float]:
    """Willis, ring held: n_c = n_s z_s / (z_s + z_r); relative to the carrier the sun turns n_s - n_c, the ring
    -n_c, the planet -(n_s - n_c) z_s / z_p."""
    n_c = n_sun * ZS / (ZS + ZR)
    return n_sun - n_c, n_c, (n_sun - n_c) * ZS / ZP


def test_planetary_cycles_per_member_and_the_pin_bearings_by_hand(tmp_path):
    life = _run(tmp_path, PLANET + _duty(P_STEPS), "--static")["life"]
    stage = life["stages"][0]
    expected = {}
    for name, hours, _, n_s in P_STEPS:
        sun_rel, n_c, planet_rel = _planet_speeds(n_s)
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
    n_l = 10000.0 * 60.0 * _planet_speeds(1500.0)[1] * NP
    assert_allclose(ring["load_cycles"], n_l, rtol=1e-12)
    assert_allclose(ring["Z_NT"], _factor(n_l, ZNT_THROUGH), rtol=1e-12)
    sigma_inf = ring["sigma_HG_MPa"] / _factor(n_l, ZNT_THROUGH)
    full = next(b for b in stage["ring"]["pitting"]["bins"] if b["point"] == "full")
    assert_allclose(full["stress_MPa"], ring["sigma_H_MPa"], rtol=1e-12)
    assert_allclose(full["cycles_to_failure"], _cycles_to_failure(full["stress_MPa"] / sigma_inf, ZNT_THROUGH),
                    rtol=1e-9)
    # and its root on Y_NT of through-hardened steel (static node 1e4 at 2.5, ISO 6336-3 Table 3)
    assert_allclose(ring["Y_NT"], _factor(n_l, YNT_THROUGH), rtol=1e-12)
    sigma_f_inf = ring["sigma_FG_MPa"] / _factor(n_l, YNT_THROUGH)
    root = next(b for b in stage["ring"]["bending"]["bins"] if b["point"] == "full")
    assert_allclose(root["stress_MPa"], ring["sigma_F_MPa"], rtol=1e-12)
    assert_allclose(root["cycles_to_failure"], _cycles_to_failure(root["stress_MPa"] / sigma_f_inf, YNT_THROUGH),
                    rtol=1e-9)
    # the planet pins: per planet F_t = T_sun / (N r_sun), T_sun = T_out / (1 + z_r / z_s); the sun and the ring push
    # the planet the same way: 2 F_t K_gamma on the pin, half on each bearing (symmetric at 85 / 115 mm)
    for b in life["bearings"]:
        loads = []
        for _, _, t_out, _ in P_STEPS:
            ft = t_out * 1e3 / (1.0 + ZR / ZS) / (NP * ZS * M_P / 2.0)
            loads.append(2.0 * ft * K_GAMMA / 2.0)
        assert_allclose(b["loads_N"], loads, rtol=1e-9)
        revs = [h * 60.0 * _planet_speeds(n)[2] for _, h, _, n in P_STEPS]  # the pin turns at n_p relative
        assert_allclose(b["revolutions"], sum(revs), rtol=1e-12)
        p_exp = 10.0 / 3.0
        p_eq = (sum(p ** p_exp * r for p, r in zip(loads, revs, strict=True)) / sum(revs)) ** (1.0 / p_exp)
        assert_allclose(b["equivalent_load_N"], p_eq, rtol=1e-9)
        assert_allclose(b["L10_Mrev"], (40e3 / p_eq) ** p_exp, rtol=1e-9)
        nu = nu_at(70.0, 220.0, 19.0)
        kappas = [nu / nu_1(_planet_speeds(n)[2], 40.0) for _, _, _, n in P_STEPS]
        assert_allclose(b["kappa_points"], kappas, rtol=1e-9)
        a_isos = [a_iso(k, 0.4 * 4000.0 / p, "roller") for k, p in zip(kappas, loads, strict=True)]
        assert_allclose(b["a_ISO_points"], a_isos, rtol=1e-9)
        assert b["a_1"] == 0.25  # ISO 281 Table 12 at 99 %
        l_nm = sum(revs) / sum(r / (0.25 * a * (40e3 / p) ** p_exp * 1e6)
                               for r, a, p in zip(revs, a_isos, loads, strict=True)) / 1e6
        assert_allclose(b["L_nm_Mrev"], l_nm, rtol=1e-9)


# --- a zero-load step on the dynamic route ----------------------------------------------------------------------

NOISE_CODES = {"statistics_unresolved", "statistics_undersampled", "window_not_settled", "window_ringing"}


def test_a_zero_load_step_is_at_rest_not_an_unresolved_or_unsettled_window(tmp_path):
    """An idle step (0 N·m) carries F_t of 1e-11 N, round-off: its statistics were judged against that rms and
    warned unresolved (0.54 of 4e-11 N), unsampled, and not settled ("a start-up transient decays through it"),
    and the point was run three times longer looking for a settled window. The unloaded stage's targets now refer to
    at least 1/TARGET times the force the run resolves (e K h^e rtol, h = 1 um: written out below), so the idle
    step is quiet and settled in the file's own window, and its damage is nil as on the static route."""
    steps = (("full", 16200.0, 900.0, 1500.0), ("idle", 3800.0, 0.0, 1500.0))
    doc = _run(tmp_path, PAR_BASE + _duty(steps))
    idle = doc["life"]["points"][1]
    assert idle["settled"] is True
    assert idle["solver"]["window_s"] == [0.1, 0.3]  # the file's window: no longer runs
    said = [w for w in doc["warnings"] if "idle" in w["message"] and w["code"] in NOISE_CODES]
    assert said == []
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            b = next(b for b in doc["life"]["stages"][0][member][mode]["bins"] if b["point"] == "idle")
            assert b["damage"] == 0.0 and b["force_N"] < 1e-6


def test_the_unloaded_reference_floor_by_hand():
    """estimate.force_floors_N: the line force e K h^e rtol / TARGET at h = 1 um (an unloaded mesh without backlash:
    the atol's deflection floor), as F_t = F_bt cos(alpha_wt) ... here through the model's own K and e."""
    from gearcli.model import TorsionalModel
    from gearcli.scene import spec_from_design
    from gearcli.simulate.estimate import TARGET, force_floors_N

    cfg, design = design_of(PAR_BASE, ("load.torque_Nm=0",))
    model = TorsionalModel(spec_from_design(cfg, design))
    (m,) = model.spec.meshes
    line = m.exponent * m.stiffness_N_m_e * 1e-6 ** m.exponent * 1e-6 / TARGET
    # spur, no profile shift: the working pressure angle is 20°, F_t = F_bt cos(20°)
    assert_allclose(force_floors_N(model, 1e-6), [line * math.cos(ALPHA)], rtol=1e-9)
    # far below a loaded mesh's reference (7500 N at 900 N·m) and far above round-off (1e-11 N)
    assert 1e-3 < force_floors_N(model, 1e-6)[0] < 100.0


# --- starts, and hours that are not the required life -------------------------------------------------------------

def test_starts_add_their_own_cycles_and_damage_by_hand(tmp_path):
    """50 starts on the full-load step: each start is the run from rest to the window (the file's 0.05 s speed ramp,
    then full speed), 1500/60 x (t_w - 0.05/2) input revolutions; the pinion turns with the input, the gear 1/3 as
    fast, one tooth contact per turn each. The start's classes are rated on the same S–N curve (written out above)
    and add exactly their own damage."""
    n_starts, hours = 50, 20000.0
    text = PAR_BASE + _duty((("full", hours, 900.0, 1500.0),)).replace('name = "full"', f'name = "full"\nstarts = {n_starts}')
    life = _run(tmp_path, text)["life"]
    start = life["points"][0]["start"]
    assert start["count"] == n_starts
    t_w = start["span_s"][1]
    revs = 1500.0 / 60.0 * (t_w - 0.05 / 2.0)  # the ramp's half plus the rest at speed
    assert_allclose(start["input_revolutions"], revs, rtol=1e-9)
    # the ramp's inertia torque on top of the load: the start's peak is above the static 7500 N, by a few per cent
    assert 7500.0 < start["peak_tangential_N"][0] < 1.1 * 7500.0
    for member, speed, nodes in (("pinion", 1.0, ZNT_CASE), ("gear", 1.0 / U, ZNT_CASE)):
        ml = life["stages"][0][member]["pitting"]
        own = [b for b in ml["bins"] if b["point"] == "full (start)"]
        steady = [b for b in ml["bins"] if b["point"] == "full"]
        assert_allclose(sum(b["cycles"] for b in own), n_starts * revs * speed, rtol=1e-9)
        assert_allclose(sum(b["cycles"] for b in steady), hours * 60.0 * 1500.0 * speed, rtol=1e-9)
        d_start = sum(b["cycles"] / _cycles_to_failure(b["stress_MPa"] / b["endurance_MPa"], nodes) for b in own)
        assert_allclose(start["damage"][0][member]["pitting"], d_start, rtol=1e-9)
        assert_allclose(ml["damage"], d_start + sum(b["damage"] for b in steady), rtol=1e-9)
    nu = nu_at(70.0, 150.0, 15.0)
    for j, b in enumerate(life["bearings"]):
        speed = 1500.0 if b["shaft"] == 1 else 500.0
        start_revs = n_starts * revs * speed / 1500.0
        assert_allclose(b["revolutions"], hours * 60.0 * speed + start_revs, rtol=1e-12)
        if "kappa" not in b:
            continue
        # the starts are a load level of their own at the bearing's mean speed during a start (revolutions over the
        # start's span): a thinner film than at full speed, so the duty's lowest kappa is the start's
        d_m, cu, kind, c_N = (45.0, 800.0, "ball", 30e3) if b["shaft"] == 1 else (110.0, 9000.0, "roller", 90e3)
        n_start = revs * speed / 1500.0 / (t_w / 60.0)
        assert_allclose(b["kappa"], nu / nu_1(n_start, d_m), rtol=1e-9)
        p_exp = 3.0 if kind == "ball" else 10.0 / 3.0
        e_c = 0.5 if d_m < 100.0 else 0.6
        levels = ((hours * 60.0 * speed, b["loads_N"][0], speed),
                  (start_revs, start["bearings"][j]["equivalent_load_N"], n_start))
        a1 = b["a_1"]
        inverse = sum(r / (a1 * a_iso(nu / nu_1(n, d_m), e_c * cu / p, kind) * (c_N / p) ** p_exp * 1e6)
                      for r, p, n in levels)
        assert_allclose(b["L_nm_Mrev"], sum(r for r, _, _ in levels) / inverse / 1e6, rtol=1e-9)


def test_hours_that_do_not_add_up_to_the_required_life(tmp_path):
    """The same spectrum as time shares (0.2 / 0.6 / 0.01 / 0.19 = 100 % of 1 h) instead of hours over the 20 000 h:
    a `duty` warning names the sum; D scales with the hours (every class's cycles do), the life in hours does
    not, and the load multiplier is that of D over 1 h."""
    shares = tuple((n, h / 20000.0, t, s) for n, h, t, s in STEPS)
    full = _run(tmp_path, PAR, "--static")
    frac = _run(tmp_path, PAR_BASE + _duty(shares), "--static")
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
    life = _run(tmp_path, PAR, "--static", "--miner", variant)["life"]
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
        'kind = "roller"\n' + _duty(P_STEPS)
    life = _run(tmp_path, text, "--static")["life"]
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


@pytest.mark.parametrize("second", ["full", "full (start)"])
def test_each_duty_point_has_a_name_of_its_own(tmp_path, second):
    """Two points named "full", each with 100 starts, reported each a start damage of 5.435e-12 (their start
    classes merged by name), the damage of 200 starts: exit 2 naming the second point's name now; so is a point
    named as the first one's start classes. Without starts "full (start)" names no start classes and is a name."""
    def point(name: str, starts: int) -> str:
        return f'\n[[duty]]\nname = "{name}"\nhours = 10000\nstarts = {starts}\ntorque_Nm = 900\nspeed_rpm = 1500\n'

    path = tmp_path / "scene.toml"
    path.write_text(PAR_BASE + point("full", 100) + point(second, 100))
    res = CliRunner().invoke(cli, ["life", str(path), "--static"])
    assert res.exit_code == 2 and str(path) in res.output and "duty[1].name" in res.output, res.output
    assert repr(second) in res.output and "Traceback" not in res.output
    path.write_text(PAR_BASE + point("full", 0) + point(second, 0))
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "-q"])
    assert (res.exit_code == 0) is (second == "full (start)"), res.output
