"""An unloaded spur stage with 0.15 mm backlash and an 8 um first-harmonic transmission error, behind a prescribed
input speed: with the default viscous mesh damping (DESIGN section 6: c q' at all times, also inside the backlash)
the free gear floats inside its backlash, never touching either flank, carried by the damper alone.

Hand model: along the line of action q = delta - e with delta = r_bp theta_p - r_bg theta_g and the pinion at a
constant speed; inside the gap the only force is F_bt = c q' on the gear, so with m_e = J_g / r_bg^2 (a speed-driven
pinion is infinitely heavy) delta'' = -(c/m_e)(delta' - e'), a first-order low pass of e' = -e_1 w_m sin(w_m t).
In the steady state |F_bt| = m_e |delta''| = m_e w_m^2 e_1 a / sqrt(a^2 + w_m^2), a = c / m_e, and the gear's mean
position stays where the run-up left it (no force pushes it to a flank). c = 2 zeta sqrt(k_lin m_e) with zeta 0.05
and k_lin the calibrated law's tangent at its floor load, 1 N/mm of face width: the ISO 6336-1 stiffness with its
low-load factor (1/100)^0.25 (docs/physics.md). F_t = F_bt cos(alpha).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

SCENE = """
title = "unloaded spur stage floating in its backlash"
[materials.st]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.06e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 0
backlash_mm = 0.15
pinion = { teeth = 25, face_width_mm = 30, material = "st" }
gear   = { teeth = 50, face_width_mm = 30, material = "st", inertia_kg_m2 = 0.01 }
mesh = { transmission_error_um = [8] }
[input]
speed_rpm = 1200
ramp_s = 0.1
[load]
torque_Nm = 0
[simulation]
duration_s = 0.6
steps = 20000
"""


def _k_lin_N_m() -> float:
    m, z1, z2, b, al = 3.0, 25, 50, 30.0, math.radians(20.0)
    r1, r2 = m * z1 / 2, m * z2 / 2
    rb1, rb2 = r1 * math.cos(al), r2 * math.cos(al)
    eps_a = (math.sqrt((r1 + m) ** 2 - rb1**2) + math.sqrt((r2 + m) ** 2 - rb2**2) - (r1 + r2) * math.sin(al)) / (
        math.pi * m * math.cos(al))
    c_prime = 1 / (0.04723 + 0.15551 / z1 + 0.25791 / z2) * 0.8 * 0.975 * (1.0 / 100.0) ** 0.25
    return c_prime * (0.75 * eps_a + 0.25) * b * 1e6


def test_the_gear_floats_on_the_damper(tmp_path: Path) -> None:
    path = tmp_path / "float.toml"
    path.write_text(SCENE, encoding="utf-8")
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    st = json.loads(res.stdout)["summary"]["stages"][0]
    k = _k_lin_N_m()
    assert_allclose(st["mesh_stiffness"]["linearised_N_mm"], k / 1e3, rtol=1e-9)
    al = math.radians(20.0)
    m_e = 0.01 / (0.075 * math.cos(al)) ** 2
    c = 2 * 0.05 * math.sqrt(k * m_e)
    a, w_m = c / m_e, 25 * 1200 / 60 * 2 * math.pi
    f_t = math.cos(al) * m_e * w_m**2 * 8e-6 * a / math.sqrt(a * a + w_m * w_m)
    # the window (0.2-0.6 s) is 400 damper time constants past the ramp: steady to the run's accuracy
    assert_allclose(st["tangential_N"]["max"], f_t, rtol=1e-4)
    assert_allclose(-st["tangential_N"]["min"], f_t, rtol=1e-4)
    assert_allclose(st["tangential_N"]["std"], f_t / math.sqrt(2), rtol=1e-3)  # a sine's rms about its mean
    assert abs(st["tangential_N"]["mean"]) < 1e-4 * f_t
    # never in contact: the DTE stays inside the half gap of 75 um (normal = transverse for spur gears)
    assert st["contact_loss_fraction"] == 1.0 and st["back_flank_fraction"] == 0.0
    assert -75.0 < st["dte_um"]["min"] and st["dte_um"]["max"] < 75.0
    # the DTE: q' = delta' - e' = -delta''/a, so |q'| = F_bt/c and |q| = F_bt/(c w_m) = e_1 w_m / sqrt(a^2 + w_m^2)
    assert_allclose((st["dte_um"]["max"] - st["dte_um"]["min"]) / 2, 8.0 * w_m / math.sqrt(a * a + w_m * w_m), rtol=1e-3)
