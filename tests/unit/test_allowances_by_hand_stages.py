"""Allowances of spur and helical stages with profile shift checked against ISO 21771's tooth-thickness route
written out here (not gearcli's closed form): the backlash is the working pitch less both tooth thicknesses on the
working circles at the limit centre distance, s_w = d_w (s_t/d + inv α_t − inv α'), s_t = m_t (π/2 + 2 x_E tan α_n),
and the contact ratio is the path of contact over the base pitch at the limit tips and centre distance (tr19a).

The first stage has no allowances and the later two have them: the design CSV names each of their columns once
(it repeated a column once per stage that had it and the first did not)."""

from __future__ import annotations

import csv
import io
import json
import math
import os
import tempfile
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gearcli.cli import cli

SCENE = """
title = "three stages, allowances on the second (spur, h_fP* = 1.4) and third (helical)"
[materials]
steel = { density_kg_m3 = 7830, youngs_modulus_MPa = 206000, poisson_ratio = 0.3 }

[[stage]]
normal_module_mm = 3
pinion = { teeth = 23, face_width_mm = 30, hand = "spur" }
gear   = { teeth = 47, face_width_mm = 30, hand = "spur" }

[[stage]]
normal_module_mm = 4
basic_rack = { addendum = 1.0, dedendum = 1.4, root_radius = 0.3 }
center_distance_allowance_mm = [0.035, -0.020]
pinion = { teeth = 19, face_width_mm = 40, hand = "spur", profile_shift = 0.3, tooth_thickness_allowance_mm = [-0.060, -0.110] }
gear   = { teeth = 61, face_width_mm = 38, hand = "spur", profile_shift = -0.1, tooth_thickness_allowance_mm = [-0.090, -0.150], tip_diameter_allowance_mm = [0.0, -0.2] }

[[stage]]
normal_module_mm = 6
helix_angle_deg = 15
center_distance_allowance_mm = [0.030, 0.010]
pinion = { teeth = 17, face_width_mm = 60, hand = "right", profile_shift = 0.45, tooth_thickness_allowance_mm = [-0.080, -0.140], tip_diameter_allowance_mm = [-0.05, -0.15] }
gear   = { teeth = 53, face_width_mm = 58, hand = "left", profile_shift = 0.2, tooth_thickness_allowance_mm = [-0.120, -0.200] }

[input]
speed_rpm = 1480
[load]
torque_Nm = 6000
"""

CASES = {  # stage index (0-based) -> the allowance data of SCENE
    1: dict(m=4.0, beta=0.0, z=(19, 61), x=(0.3, -0.1), hf=1.4, asn=((-0.06, -0.11), (-0.09, -0.15)),
            ada=((0.0, 0.0), (0.0, -0.2)), aa=(0.035, -0.020)),
    2: dict(m=6.0, beta=15.0, z=(17, 53), x=(0.45, 0.2), hf=1.25, asn=((-0.08, -0.14), (-0.12, -0.20)),
            ada=((-0.05, -0.15), (0.0, 0.0)), aa=(0.030, 0.010)),
}


def inv(a: float) -> float:
    return math.tan(a) - a


def by_hand(m, beta, z, x, hf, asn, ada, aa):
    an, b = math.radians(20.0), math.radians(beta)
    at, mt = math.atan(math.tan(an) / math.cos(b)), m / math.cos(b)
    d = [zi * mt for zi in z]
    db = [di * math.cos(at) for di in d]
    bb = math.atan(math.tan(b) * math.cos(at))
    target = inv(at) + 2 * math.tan(an) * sum(x) / sum(z)  # the nominal (backlash-free) working angle
    awt = brentq(lambda a: inv(a) - target, 1e-6, 1.4)
    a0 = sum(d) / 2
    aw = a0 * math.cos(at) / math.cos(awt)
    k = (aw - a0) / m - sum(x)  # tip alteration
    da = [d[i] + 2 * m * (1.0 + x[i] + k) for i in (0, 1)]
    xe = [[x[i] + a / (2 * m * math.tan(an)) for a in asn[i]] for i in (0, 1)]
    df = [[d[i] + 2 * m * (v - hf) for v in xe[i]] for i in (0, 1)]

    def backlash(xs, a):  # p_w − s_w1 − s_w2 on the working circles at centre distance a
        al = math.acos(a0 * math.cos(at) / a)
        dw = [d[i] * math.cos(at) / math.cos(al) for i in (0, 1)]
        st = [mt * (math.pi / 2 + 2 * xs[i] * math.tan(an)) for i in (0, 1)]
        sw = [dw[i] * (st[i] / d[i] + inv(at) - inv(al)) for i in (0, 1)]
        jt = math.pi * dw[0] / z[0] - sw[0] - sw[1]
        return jt, jt * math.cos(al) * math.cos(bb)

    def eps(tips, a):
        al = math.acos(a0 * math.cos(at) / a)
        path = sum(math.sqrt(tips[i] ** 2 / 4 - db[i] ** 2 / 4) for i in (0, 1)) - a * math.sin(al)
        return path / (math.pi * mt * math.cos(at))

    jmax, jnmax = backlash((xe[0][1], xe[1][1]), aw + aa[0])  # thinnest teeth, largest centre distance
    jmin, jnmin = backlash((xe[0][0], xe[1][0]), aw + aa[1])  # thickest teeth, smallest centre distance
    mean_tip = [da[i] + 0.5 * (ada[i][0] + ada[i][1]) for i in (0, 1)]
    e = (eps([da[i] + ada[i][0] for i in (0, 1)], aw + aa[1]), eps(mean_tip, aw + 0.5 * (aa[0] + aa[1])),
         eps([da[i] + ada[i][1] for i in (0, 1)], aw + aa[0]))
    return dict(xe=xe, df=df, jt=(jmax, jmin), jn=(jnmax, jnmin), eps=e)


def _design(*args):
    fd, name = tempfile.mkstemp(prefix="allowances_stages_", suffix=".toml")
    os.close(fd)
    path = Path(name)
    try:
        path.write_text(SCENE)
        res = CliRunner().invoke(cli, ["design", str(path), *args])
    finally:
        path.unlink(missing_ok=True)
    assert res.exit_code == 0, res.output
    return res.stdout


def test_spur_and_helical_allowances_by_the_tooth_thickness_route():
    doc = json.loads(_design("--format", "json"))
    assert "backlash_circumferential_mm" not in doc["stages"][0]
    for k, case in CASES.items():
        st, ref = doc["stages"][k], by_hand(**case)
        for i, part in enumerate(("pinion", "gear")):
            assert_allclose(st[part]["generating_profile_shift"], ref["xe"][i], rtol=0, atol=1e-12)
            assert_allclose(st[part]["manufactured_root_diameter_mm"], ref["df"][i], rtol=0, atol=1e-9)
        assert_allclose(st["backlash_circumferential_mm"], ref["jt"], rtol=1e-9)
        assert_allclose(st["backlash_normal_mm"], ref["jn"], rtol=1e-9)
        assert_allclose(st["contact_ratio_transverse_with_allowances"], ref["eps"], rtol=1e-12)


def test_csv_names_each_column_once_when_later_stages_add_columns():
    text = _design("--format", "csv")
    header = next(csv.reader(io.StringIO(text)))
    assert len(header) == len(set(header)), sorted({h for h in header if header.count(h) > 1})
    rows = list(csv.DictReader(io.StringIO(text)))
    assert len(rows) == 3 and all(len(r) == len(header) for r in rows)
    assert rows[0]["backlash_circumferential_mm_min"] == ""
    for k, case in CASES.items():
        ref = by_hand(**case)
        assert_allclose(float(rows[k]["backlash_circumferential_mm_max"]), ref["jt"][0], rtol=1e-9)
        assert_allclose(float(rows[k]["gear_manufactured_root_diameter_mm_i"]), ref["df"][1][1], rtol=0, atol=1e-9)
        assert_allclose(float(rows[k]["contact_ratio_transverse_with_allowances_i"]), ref["eps"][2], rtol=1e-12)
