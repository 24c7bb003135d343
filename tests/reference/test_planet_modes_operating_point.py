"""`modes` linearises planets with position errors at the shares those errors give, not at equal shares.

The field test (session 16): a star 20/25/70 x3 with position errors [15, 0, -5] µm settles at 7622, 1508 and 314 N
on the planets (simulate, matching a hand static model to 2e-6), yet `modes` and simulate's natural frequencies took
every planet mesh's tangent at the equal 3148 N: the N - 1 fold planet modes stayed a pair at 7098 Hz and the
lowest mesh mode at 807 Hz, where the operating point's Hertzian tangents (k = e K h^(e-1), F^(1/3)) split them to
4851, 6300 and 8254 Hz and move it to 751 Hz. Reference: an independent hand model of the stage (ring held, sun
driven, lossless): the settled state solved from the planets' balances (each planet's sun and ring forces equal)
and the carrier's moment balance with the design's K, then the torsional eigenproblem on the rotational degrees of
freedom with each mesh's tangent along its line of action (transverse base tangent: k_n cos² β_b).
"""

from __future__ import annotations

import json

import numpy as np
import scipy.linalg as sl
from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.optimize import fsolve

from gearcli.cli import cli

ERRORS_UM = [15.0, 0.0, -5.0]
SCENE = f"""
[[stage]]
type = "planetary"
normal_module_mm = 3
sun    = {{ teeth = 20, face_width_mm = 45 }}
planet = {{ teeth = 25, face_width_mm = 42, count = 3, position_error_um = {ERRORS_UM} }}
ring   = {{ teeth = 70, face_width_mm = 42 }}
carrier = {{ inertia_kg_m2 = 0.3 }}
fixed = "ring"
input = "sun"

[input]
speed_rpm = 1000

[load]
torque_Nm = 2500
"""


def _json(tmp_path, command: str) -> dict:
    path = tmp_path / "planetary.toml"
    path.write_text(SCENE)
    out = CliRunner().invoke(cli, [command, str(path), "--format", "json"])
    assert out.exit_code == 0, out.output
    return json.loads(out.stdout)


def test_planet_modes_are_those_of_the_settled_shares(tmp_path):
    s = _json(tmp_path, "design")["stages"][0]
    modes = _json(tmp_path, "modes")
    k_sp_law, k_rp_law = (m["mesh_stiffness"]["K"] for m in s["meshes"])  # N/mm^1.5 along the normal, spur
    rbs, rbp, rbr = (0.5 * s[m]["base_diameter_mm"] for m in ("sun", "planet", "ring"))
    e = np.array(ERRORS_UM) * 1e-3  # mm, along the sun mesh
    t_carrier = abs(s["moment_balance_Nm"]["carrier"]) * 1e3  # N mm

    def deflections(x):  # ring held, carrier at 0: x = (sun angle, planet angles relative to the carrier)
        return rbs * x[0] + rbp * x[1:] + e, -rbp * x[1:]

    def residual(x):
        h_sp, h_rp = deflections(x)
        f_sp, f_rp = k_sp_law * np.sign(h_sp) * np.abs(h_sp) ** 1.5, k_rp_law * np.sign(h_rp) * np.abs(h_rp) ** 1.5
        return np.r_[f_sp - f_rp, np.sum(f_sp) * rbs * (1 + rbr / rbs) - t_carrier]

    h_sp, h_rp = deflections(fsolve(residual, np.r_[1e-4, -1e-4, -1e-4, -1e-4], xtol=1e-13))
    assert np.all(h_sp > 0) and np.all(h_rp > 0)  # every planet on its drive flank
    f_sp = k_sp_law * h_sp ** 1.5
    assert f_sp.max() / f_sp.mean() > 1.5  # the check has teeth: planet 1 carries 1.8 times the mean
    k_sp, k_rp = 1.5 * k_sp_law * np.sqrt(h_sp) * 1e3, 1.5 * k_rp_law * np.sqrt(h_rp) * 1e3  # N/m
    # clamped input (the sun's speed is prescribed): planets 1..3 (absolute angles), carrier
    jp, jc = s["planet"]["inertia_kg_m2"], s["carrier"]["inertia_kg_m2"]
    r_s, r_p, r_r = rbs * 1e-3, rbp * 1e-3, rbr * 1e-3
    stiffness = np.zeros((4, 4))
    for j in range(3):
        for k, lever in ((k_sp[j], {j: r_p, 3: -(r_s + r_p)}), (k_rp[j], {j: -r_p, 3: -(r_r - r_p)})):
            v = np.zeros(4)
            for i, value in lever.items():
                v[i] = value
            stiffness += k * np.outer(v, v)
    w2 = sl.eigh(stiffness, np.diag([jp, jp, jp, jc]), eigvals_only=True)
    hand = np.sqrt(w2) / (2 * np.pi)
    assert hand[2] / hand[1] > 1.05  # the check has teeth: equal shares would give the planet modes as a pair
    found = [m["frequency_Hz"] for m in modes["boundaries"]["clamped_input"]]
    assert_allclose(found, hand, rtol=1e-6)
