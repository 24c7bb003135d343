"""Bearing reactions of a three-stage helical train where the features meet, against shaft statics written out
here (docs/life.md "Bearings", DESIGN §10), no gearcli figure used as a reference:

- profile-shifted stages: the forces act at the operating pitch point, r_w = r_b / cos α_wt with
  inv α_wt = inv α_t + 2 tan α_n (x_1 + x_2) / (z_1 + z_2) (ISO 21771), F_t = F_bt cos α_wt,
  F_r = |F_bt| sin α_wt (always separating), F_a = F_bt tan β_b, F_bt = T_1 / r_b1;
- stage efficiencies: T_1 = T_2 / (i η) with the power flowing forward, T_1 = T_2 η / i under a reversed load;
- the frame: x along the shafts, u = (0, cos φ, sin φ) the line of centres (φ clockwise seen from the input end),
  t = x × u; a pinion turning with sense s about +x (cw: +1) is held back by -s F_t t, pushed off by -F_r u and,
  with hand h (right +1), pushed along +s h F_a x (its tooth line r t + h c x; the normal force is perpendicular
  to it); every gear turns against its pinion, the next pinion with its gear;
- each shaft on two bearings: forces and bending moments (about bearing A, arms from the point of application,
  the axial force's arm r_w included) balance; the locating bearing takes -Σ F_x;
- ISO 281 P = F_r for F_a/F_r ≤ e, else X F_r + Y F_a; L10 = (C/P)^p; ISO 76 s_0 = C_0 / max(F_r, X_0 F_r + Y_0 F_a);
- `simulate`'s bearing channels: the same statics applied to every sample of the simulated tooth-force channels
  (F_bt = F_t / cos α_t, the channel's convention), through force reversals.
Trial tr25c (session 21): every figure agreed to round-off; this keeps that.
"""

from __future__ import annotations

import csv
import io
import json
import math

import numpy as np
from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gearcli.cli import cli

# (m_n, α_n, β, z_1, z_2, x_1, x_2, η, φ, pinion hand, pinion x, gear x)
STAGES = [(4, 20, 15, 19, 73, 0.4, 0.1, 0.98, 30, +1, 20, 250),
          (6, 20, 10, 17, 61, 0.3, 0.0, 0.97, 200, +1, 80, 80),
          (8, 22, 8, 18, 55, 0.0, 0.0, 1.0, -60, -1, 330, 330)]
# (shaft, x, C kN, kind, locating, e, X, Y, C_0 kN, X_0, Y_0)
BEARINGS = [(1, 100, 60, "ball", True, 0.3, 0.56, 1.5, 40, 0.6, 0.5),
            (1, 300, 60, "ball", False, 0, 1, 0, 40, 1, 0),
            (2, 20, 250, "roller", False, 0, 1, 0, 300, 1, 0),
            (2, 320, 250, "roller", True, 0.35, 0.4, 1.7, 300, 0.5, 0.9),
            (3, 30, 500, "roller", True, 0.4, 0.4, 1.5, 600, 0.5, 0.8),
            (3, 400, 500, "roller", False, 0, 1, 0, 600, 1, 0),
            (4, 250, 700, "roller", False, 0, 1, 0, 700, 1, 0),
            (4, 500, 700, "roller", True, 0.4, 0.4, 1.5, 700, 1, 0)]
HAND = {1: "right", -1: "left"}


def scene(rotation: str, torque_Nm: float) -> str:
    out = ['[materials.steel]\ndensity_kg_m3 = 7850\nyoungs_modulus_MPa = 2.1e5\npoisson_ratio = 0.3\n']
    for mn, an, b, z1, z2, x1, x2, eta, phi, h, xp, xg in STAGES:
        out.append(f"[[stage]]\nnormal_module_mm = {mn}\nnormal_pressure_angle_deg = {an}\nhelix_angle_deg = {b}\n"
                   f"efficiency = {eta}\ncenter_angle_deg = {phi}\n"
                   f'pinion = {{ teeth = {z1}, face_width_mm = 60, hand = "{HAND[h]}", material = "steel", '
                   f"profile_shift = {x1}, axial_position_mm = {xp} }}\n"
                   f'gear = {{ teeth = {z2}, face_width_mm = 55, hand = "{HAND[-h]}", material = "steel", '
                   f"profile_shift = {x2}, axial_position_mm = {xg} }}\n")
    out.append(f'[input]\nspeed_rpm = 1480\nramp_s = 0.02\nrotation = "{rotation}"\n\n'
               f"[load]\ntorque_Nm = {torque_Nm}\nramp_s = 0.02\n"
               "fluctuation = [{ amplitude_percent = 100, frequency_Hz = 40 }]\n\n"
               "[simulation]\nduration_s = 0.1\nsteps = 400\n")
    for sh, x, c, kind, loc, e, bx, by, c0, x0, y0 in BEARINGS:
        out.append(f'[[bearing]]\nshaft = {sh}\nposition_mm = {x}\ndynamic_load_rating_kN = {c}\nkind = "{kind}"\n'
                   f"locating = {'true' if loc else 'false'}\nstatic_load_rating_kN = {c0}\n"
                   + (f"factors = {{ e = {e}, X = {bx}, Y = {by} }}\nstatic_factors = {{ X0 = {x0}, Y0 = {y0} }}\n"
                      if loc else ""))
    return "\n".join(out)


def inv(a: float) -> float:
    return math.tan(a) - a


def geometry() -> list[dict]:
    out = []
    for mn, an, b, z1, z2, x1, x2, _eta, phi, h, xp, xg in STAGES:
        an, b = math.radians(an), math.radians(b)
        at = math.atan(math.tan(an) / math.cos(b))
        rb1, rb2 = z1 * mn / math.cos(b) / 2 * math.cos(at), z2 * mn / math.cos(b) / 2 * math.cos(at)
        target = inv(at) + 2 * math.tan(an) * (x1 + x2) / (z1 + z2)
        awt = brentq(lambda a, target=target: inv(a) - target, 1e-3, 1.5)
        out.append({"at": at, "awt": awt, "bb": math.atan(math.tan(b) * math.cos(at)), "rb1": rb1,
                    "rw1": rb1 / math.cos(awt), "rw2": rb2 / math.cos(awt), "phi": math.radians(phi), "h": h,
                    "xp": xp, "xg": xg})
    return out


def pinion_torques_Nmm(torque_Nm: float) -> list[float]:
    t, out = torque_Nm * 1e3, []
    for _mn, _an, _b, z1, z2, *_x, eta, _phi, _h, _xp, _xg in reversed(STAGES):
        t = t / (z2 / z1 * eta) if t >= 0 else t * eta / (z2 / z1)
        out.insert(0, t)
    return out


def reactions(line_forces_N: list[float], sense: int) -> list[tuple[float, float, float]]:
    """(y, z, axial) of every bearing on its shaft for the stages' transverse line forces F_bt."""
    loads: dict[int, list] = {k: [] for k in range(1, len(STAGES) + 2)}
    x_axis = np.array([1.0, 0.0, 0.0])
    for k, (g, fbt) in enumerate(zip(geometry(), line_forces_N, strict=True)):
        u = np.array([0.0, math.cos(g["phi"]), math.sin(g["phi"])])
        t = np.cross(x_axis, u)
        ft, fr, fa = fbt * math.cos(g["awt"]), abs(fbt) * math.sin(g["awt"]), fbt * math.tan(g["bb"])
        on_pinion = -sense * ft * t - fr * u + sense * g["h"] * fa * x_axis
        loads[k + 1].append((np.array([g["xp"], 0.0, 0.0]) + g["rw1"] * u, on_pinion))
        loads[k + 2].append((np.array([g["xg"], 0.0, 0.0]) - g["rw2"] * u, -on_pinion))
        sense = -sense
    out = []
    for sh, x, *_rest in BEARINGS:
        loc = _rest[2]
        other = next(b[1] for b in BEARINGS if b[0] == sh and b[1] != x)
        xa, xb = min(x, other), max(x, other)
        force = sum(f for _, f in loads[sh])
        moment = sum(np.cross(p - np.array([xa, 0.0, 0.0]), f) for p, f in loads[sh])
        rb = (-moment[2] / (xb - xa), moment[1] / (xb - xa))
        ra = (-force[1] - rb[0], -force[2] - rb[1])
        out.append((*(ra if x == xa else rb), -force[0] if loc else 0.0))
    return out


def run(args: list[str], text: str, tmp_path) -> str:
    path = tmp_path / "train.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, [args[0], str(path), *args[1:]])
    assert res.exit_code == 0, res.output
    return res.stdout


def design(rotation: str, torque_Nm: float, tmp_path) -> dict:
    out = run(["design", "--format", "json"], scene(rotation, torque_Nm), tmp_path)
    return json.loads(out[out.index("{"):])


def check_design(d: dict, rotation: str, torque_Nm: float) -> None:
    geo = geometry()
    forces = [t / g["rb1"] for t, g in zip(pinion_torques_Nmm(torque_Nm), geo, strict=True)]
    hand = reactions(forces, 1 if rotation == "cw" else -1)
    scale = max(abs(c) for r in hand for c in r)
    for (y, z, a), spec, got in zip(hand, BEARINGS, d["bearings"], strict=True):
        assert_allclose([got["radial_y_N"], got["radial_z_N"], got["axial_N"]], [y, z, a], rtol=0, atol=1e-9 * scale)
        _sh, _x, c, kind, _loc, e, bx, by, c0, x0, y0 = spec
        fr, fa = math.hypot(y, z), abs(a)
        p = fr if fa <= e * fr else bx * fr + by * fa
        assert_allclose(got["equivalent_load_N"], p, rtol=1e-9)
        assert_allclose(got["L10_Mrev"], (c * 1e3 / p) ** (3 if kind == "ball" else 10 / 3), rtol=1e-9)
        assert_allclose(got["static_safety"], c0 * 1e3 / max(fr, x0 * fr + y0 * fa), rtol=1e-9)


def test_three_stage_ccw_profile_shifted_lossy_reactions_by_hand(tmp_path):
    check_design(design("ccw", 12000, tmp_path), "ccw", 12000)


def test_reversed_load_turns_the_tangential_and_axial_forces_not_the_separating_ones(tmp_path):
    # the power flows back: T_1 = T_2 eta / i per stage; F_r still pushes the wheels apart
    d = design("cw", -12000, tmp_path)
    check_design(d, "cw", -12000)
    forward = design("cw", 12000, tmp_path)
    assert d["bearings"][0]["axial_N"] * forward["bearings"][0]["axial_N"] < 0


def test_simulated_bearing_channels_are_the_statics_of_every_sample(tmp_path):
    # a 100 % load fluctuation takes the tooth forces through zero: the reaction is not linear in F_bt there
    text = scene("ccw", 3000)
    rows = list(csv.reader(io.StringIO(run(["simulate", "--format", "csv"], text, tmp_path))))
    head, data = rows[0], np.array(rows[1:], dtype=float)
    col = {name: i for i, name in enumerate(head)}
    geo = geometry()
    reversed_samples = 0
    for row in data[::4]:
        forces = [row[col[f"stage{k + 1}_tangential_N"]] / math.cos(g["at"]) for k, g in enumerate(geo)]
        reversed_samples += sum(f < 0 for f in forces)
        hand = reactions(forces, -1)
        scale = max(1.0, max(abs(c) for r in hand for c in r))
        for j, (y, z, a) in enumerate(hand):
            got = (row[col[f"bearing{j + 1}_radial_N"]], row[col[f"bearing{j + 1}_axial_N"]])
            assert_allclose(got, (math.hypot(y, z), a), rtol=0, atol=1e-6 * scale)  # CSV digits
    assert reversed_samples > 0
