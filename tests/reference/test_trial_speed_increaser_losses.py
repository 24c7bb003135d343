"""A wind-turbine-like two-stage speed increaser (97/23 then 89/22, 98 % per stage) driven from its low-speed side
by a torque (the rotor, 4000 kg m^2 on a stiff coupling) against a generator-like load on the high-speed side: the
losses in the dynamics checked by hand, with power flowing forward and overrunning (the load drives the rotor).

Hand model (DESIGN sections 9 and 13, docs/physics.md "Stage efficiency in the dynamics"):
- speeds: n_out = n_in (97/23)(89/22); the torque the load needs at the input, forward T_L i / eta^2 with i the
  speed-up ratio, overrunning T_L i eta^2;
- forward: each gear receives eta of the law's force f, so in the steady state the law's F_t = T_pinion / r_pinion
  (the design's static force, losses included: T_pinion = T_gear i_stage / eta);
- overrunning (power from gear to pinion): the pinion receives eta f, so the law's F_t = T_gear / r_gear, the design's
  F_t / eta, and the calibrated law's tangent is k_n at that force: K = k_n^e / (e^e F_n0^(e-1)) with F_n0 the
  normal force it carries (docs/physics.md, the calibrated default law);
- efficiency: the window's output power over its input power is eta^2; the energy the meshes dissipate over the
  run is (1 - eta) of the power each one passes: (1 - eta^2) of the input work, less the little the couplings'
  dampers and the meshes' own damping take;
- k_n of each mesh by ISO 6336-1 method B (index 1 the smaller wheel, the driven one here), F_t/b > 100 N/mm.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

SCENE = """
title = "two-stage speed increaser, rotor-driven, generator load"
[materials.st]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.06e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 10
normal_pressure_angle_deg = 20
helix_angle_deg = 10
efficiency = 0.98
pinion = { teeth = 97, face_width_mm = 160, hand = "left", material = "st" }
gear   = { teeth = 23, face_width_mm = 150, hand = "right", material = "st" }
[[stage]]
normal_module_mm = 6
normal_pressure_angle_deg = 20
helix_angle_deg = 14
efficiency = 0.98
pinion = { teeth = 89, face_width_mm = 90, hand = "right", material = "st" }
gear   = { teeth = 22, face_width_mm = 85, hand = "left", material = "st" }
[input]
speed_rpm = 90
drive = "torque"
torque_Nm = 53294.24663307285
ramp_s = 0.5
inertia_kg_m2 = 4000
coupling_stiffness_Nm_rad = 5e7
coupling_damping_Nms_rad = 2e4
[load]
torque_Nm = 3000
ramp_s = 0.5
inertia_kg_m2 = 5
coupling_stiffness_Nm_rad = 2e5
coupling_damping_Nms_rad = 100
[simulation]
duration_s = 3
steps = 6000
"""

ETA, E = 0.98, 1.5
STAGES = [dict(mn=10.0, beta=10.0, zp=97, zg=23, bp=160.0, bg=150.0),
          dict(mn=6.0, beta=14.0, zp=89, zg=22, bp=90.0, bg=85.0)]
UP = (97 / 23) * (89 / 22)  # speed-up ratio


def _geometry(s: dict) -> dict:
    an, be = math.radians(20.0), math.radians(s["beta"])
    at = math.atan(math.tan(an) / math.cos(be))
    mt = s["mn"] / math.cos(be)
    dp, dg = s["zp"] * mt, s["zg"] * mt
    rbp, rbg = dp / 2 * math.cos(at), dg / 2 * math.cos(at)
    eps_a = (math.sqrt((dp / 2 + s["mn"]) ** 2 - rbp**2) + math.sqrt((dg / 2 + s["mn"]) ** 2 - rbg**2)
             - (dp + dg) / 2 * math.sin(at)) / (math.pi * mt * math.cos(at))
    bb = math.atan(math.tan(be) * math.cos(at))
    zn_small, zn_big = (z / (math.cos(bb) ** 2 * math.cos(be)) for z in (min(s["zp"], s["zg"]), max(s["zp"], s["zg"])))
    q = 0.04723 + 0.15551 / zn_small + 0.25791 / zn_big
    c_prime = (1 / q) * 0.8 * 0.975 * math.cos(be)
    k_n = c_prime * (0.75 * eps_a + 0.25) * min(s["bp"], s["bg"]) / math.cos(bb) ** 2 * 1e3  # N/mm
    return dict(rp=dp / 2e3, rg=dg / 2e3, k_n=k_n, normal=1 / (math.cos(an) * math.cos(be)))


G = [_geometry(s) for s in STAGES]


def _run(tmp_path: Path, *sets: str) -> dict:
    path = tmp_path / "increaser.toml"
    path.write_text(SCENE, encoding="utf-8")
    args = ["simulate", str(path), "--format", "json", "-q"]
    for s in sets:
        args += ["--set", s]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _check_law(stage: dict, g: dict, f_t: float) -> None:
    ms = stage["mesh_stiffness"]
    assert_allclose(ms["iso_N_mm"], g["k_n"], rtol=1e-9)
    f_n0 = abs(f_t) * g["normal"]  # the normal force the law carries
    assert_allclose(ms["K"], g["k_n"] ** E / (E**E * f_n0 ** (E - 1)), rtol=1e-6)
    assert_allclose(ms["linearised_N_mm"], g["k_n"], rtol=1e-6)


@pytest.mark.parametrize("flow", ["forward", "overrunning"])
def test_losses_statics_efficiency_energy(tmp_path: Path, flow: str) -> None:
    if flow == "forward":
        t_load, t_in = 3000.0, 3000.0 * UP / ETA**2
        tp2 = t_load * (89 / 22) / ETA  # the gear of stage 2 gets eta of the law's force
        # forward: the law carries the pinion's force, T_pinion / r_pinion (T_pinion 1 is the input torque)
        f_law = [t_in / G[0]["rp"], tp2 / G[1]["rp"]]
        sets = ()
    else:
        t_load, t_in = -3000.0, -3000.0 * UP * ETA**2
        tg2 = t_load
        tg1 = tg2 * (89 / 22) * ETA  # = T_pinion2: the gear of stage 1 passes eta of what it receives on
        # overrunning: the law carries the gear's force, T_gear / r_gear (the design's F_t / eta)
        f_law = [tg1 / G[0]["rg"], tg2 / G[1]["rg"]]
        sets = ("load.torque_Nm=-3000", f"input.torque_Nm={t_in!r}")
    out = _run(tmp_path, *sets)
    s = out["summary"]
    assert s["steady"]["settled"] is True
    assert_allclose(s["ratio"], 1 / UP, rtol=1e-6)
    assert_allclose(s["input_speed_rpm"], 90.0, rtol=1e-4)  # the torques balance at the nominal speed
    for st, f, g in zip(s["stages"], f_law, G, strict=True):
        # the window mean is the static law force (run's rtol 1e-6; the slow rotor mode's leftover ~1e-5)
        assert_allclose(st["tangential_N"]["mean"], f, rtol=3e-5)
        assert st["back_flank_fraction"] == 0.0 and st["contact_loss_fraction"] == 0.0
        _check_law(st, g, f)
    # efficiency from the window: output over input power, eta^2 either way round
    p_in = t_in * s["input_speed_rpm"]
    p_out = t_load * s["output_speed_rpm"]
    assert_allclose(p_out / p_in if flow == "forward" else p_in / p_out, ETA**2, rtol=1e-4)
    e = out["energy"]
    source = e["input_work_J"] if flow == "forward" else -e["load_work_J"]
    # the meshes dissipate (1 - eta^2) of the work passed through them: the source's work less what the rotor's
    # coupling stores (T^2 / 2k = 28 J, 2e-5 of it) and the dampers' share (the run is nearly steady throughout)
    assert_allclose(e["damping_loss_J"], (1 - ETA**2) * source, rtol=1e-4)
    balance = e["input_work_J"] - e["load_work_J"] - e["damping_loss_J"] - e["kinetic_change_J"] - e["potential_change_J"]
    assert abs(balance) < 1e-8 * abs(source)
