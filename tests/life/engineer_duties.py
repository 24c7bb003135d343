"""Scenes and hand formulas of tests/life/test_life_engineer_duties.py and test_life_engineer_steps.py (the round-4
trial's own duties, branch t9d): ISO 6336-2/-3 life-factor curves, ISO 281:2007 written out, the shaft statics
and planetary kinematics by hand."""

from __future__ import annotations

import json
import math

from click.testing import CliRunner

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


def duty_text(steps) -> str:
    return "".join(f'\n[[duty]]\nname = "{n}"\nhours = {h!r}\ntorque_Nm = {t!r}\nspeed_rpm = {s!r}\n'
                   for n, h, t, s in steps)


PAR = PAR_BASE + duty_text(STEPS)
Z1, Z2, M_MM, ALPHA = 20, 60, 4.0, math.radians(20.0)
U = Z2 / Z1
D1 = Z1 * M_MM  # spur: the reference diameter 80 mm

# ISO 6336-2:2006 Table 2 / ISO 6336-3:2006 Table 3, normal quality (static node, knee, 1e10)
ZNT_CASE = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))
YNT_CASE = ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85))
ZNT_THROUGH = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))  # St, V, GGG (perl., bai.), GTS (perl.): no pitting permitted
YNT_THROUGH = ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85))  # V, GGG (perl., bai.), GTS (perl.)


def run_life(tmp_path, text: str, *args: str) -> dict:
    path = tmp_path / "scene.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["-q", "life", str(path), "--format", "json", *args])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def life_factor(n: float, nodes) -> float:
    """The life factor Z_NT / Y_NT at N cycles: log-log between the nodes, flat at the static value below it,
    the last slope continued beyond 1e10."""
    (n0, y0), (n1, y1), (n2, y2) = nodes
    if n <= n0:
        return y0
    a, b = ((n0, y0), (n1, y1)) if n <= n1 else ((n1, y1), (n2, y2))
    return a[1] * (b[1] / a[1]) ** (math.log(n / a[0]) / math.log(b[0] / a[0]))


def cycles_to_failure(ratio: float, nodes) -> float:
    """Invert sigma / sigma_inf = factor(N): N = N_a (y_a / ratio)^k on the branch, k = ln(N_b/N_a) / ln(y_a/y_b)."""
    (n0, y0), (n1, y1), (n2, y2) = nodes
    if ratio <= 0.0:
        return math.inf
    if ratio >= y1:
        return n0 * (y0 / ratio) ** (math.log(n1 / n0) / math.log(y0 / y1))
    return n1 * (y1 / ratio) ** (math.log(n2 / n1) / math.log(y1 / y2))


def load_multiplier_by_bisection(damage_at) -> float:
    """The load multiplier s with D(s) = 1, by bisection on ln s (independent of the code's brentq)."""
    lo, hi = math.log(1e-3), math.log(1e3)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if damage_at(math.exp(mid)) < 1.0 else (lo, mid)
    return math.exp(0.5 * (lo + hi))


def rating_at(text: str, torque_Nm: float, speed_rpm: float):
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

def par_reactions(torque_out_Nm: float) -> tuple[float, float]:
    """|F_r| of the near (2/3) and far (1/3) bearings of either shaft: the gear mid-way... at 100 mm between
    bearings at 50/200 (shaft 1) and 0/150 (shaft 2): the lever rule gives 100/150 and 50/150 of the tooth
    normal force F_t / cos(alpha) (spur, no axial force, loss-free)."""
    ft = 2.0 * torque_out_Nm / U * 1e3 / D1
    fn = ft / math.cos(ALPHA)
    return fn * 2.0 / 3.0, fn / 3.0


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


def planet_speeds(n_sun: float) -> tuple[float, float, float]:
    """Willis, ring held: n_c = n_s z_s / (z_s + z_r); relative to the carrier the sun turns n_s - n_c, the ring
    -n_c, the planet -(n_s - n_c) z_s / z_p."""
    n_c = n_sun * ZS / (ZS + ZR)
    return n_sun - n_c, n_c, (n_sun - n_c) * ZS / ZP
