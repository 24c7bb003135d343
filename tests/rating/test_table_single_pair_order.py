"""The rating table's single-pair row on a speed increaser (round-4 trial tr29e).

ISO 6336-2's Z_B belongs to the wheel with fewer teeth and Z_D to the other, whichever drives; the table's cells, like
every per-member row, read "pinion / gear" (gearcli's driving / driven member). On a speed increaser (a 67-tooth
pinion driving a 21-tooth gear) the row was labelled "single pair Z_B / Z_D" above the cells Z_D / Z_B, so a reader
took the 67-tooth wheel's 1 for Z_B. Now it reads "Z_B,D p / g".

Independent of the code: Z_B and Z_D from M_1 and M_2 of ISO 6336-2:2006, 6.2, on the geometry of ISO 21771 as
``tests/reference/rating_hand.py`` types it (tip alteration for x1 + x2 = 0.4), Z = M − ε_β (M − 1) ≥ 1 for ε_β < 1.
"""

from __future__ import annotations

import json
import math

import tomli_w
from click.testing import CliRunner

from gearcli.cli import cli
from tests.reference.rating_hand import Member, Pair, geometry, toml_doc

SMALL = Member(21, 60.0, "case_carburized", 1500.0, 500.0, 3.0, 10.0, x=0.3)
LARGE = Member(67, 65.0, "case_carburized", 1500.0, 500.0, 3.0, 10.0, x=0.1)


def pair(driving: Member, driven: Member) -> Pair:
    return Pair(p=driving, g=driven, mn=6.0, alpha_n_deg=20.0, beta_deg=14.0, grade=6, torque_pinion_Nm=3000.0,
                n1_rpm=1000.0, k_a=1.0, nu40=220.0, life_h=20000.0)


def hand_z_b_z_d() -> tuple[float, float]:
    """(Z_B of the 21-tooth wheel, Z_D of the 67-tooth wheel) by ISO 6336-2:2006, 6.2."""
    g = geometry(pair(SMALL, LARGE))  # ISO's order: the wheel with fewer teeth first
    z = (SMALL.z, LARGE.z)
    roll = [math.sqrt((g["da"][i] / g["db"][i]) ** 2 - 1) for i in (0, 1)]
    out = []
    for i, j in ((0, 1), (1, 0)):
        m = math.tan(g["awt"]) / math.sqrt((roll[i] - 2 * math.pi / z[i])
                                           * (roll[j] - (g["ea"] - 1) * 2 * math.pi / z[j]))
        out.append(max(1.0, m - g["eb"] * (m - 1)))
    return out[0], out[1]


def test_single_pair_row_reads_pinion_then_gear(tmp_path):
    path = tmp_path / "increaser.toml"
    path.write_text(tomli_w.dumps(toml_doc(pair(LARGE, SMALL))))  # the 67-tooth wheel drives
    res = CliRunner().invoke(cli, ["-q", "design", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    stage = json.loads(res.stdout)["stages"][0]
    assert (stage["pinion"]["teeth"], stage["gear"]["teeth"]) == (67, 21)
    z_b, z_d = hand_z_b_z_d()
    assert z_b > 1.005 and z_d == 1.0  # the smaller wheel's single-pair point lies inside its flank here
    assert math.isclose(stage["rating"]["gear"]["Z_BD"], z_b, rel_tol=1e-6)  # the 21-tooth driven gear carries Z_B
    assert math.isclose(stage["rating"]["pinion"]["Z_BD"], z_d, rel_tol=1e-6)
    table = CliRunner().invoke(cli, ["-q", "design", str(path), "--format", "table"], terminal_width=200)
    assert table.exit_code == 0, table.output
    rows = [line for line in table.output.splitlines() if "single pair" in line]
    assert len(rows) == 1 and "Z_B / Z_D" not in rows[0] and "p / g" in rows[0]
    assert f"{z_d:.4g} / {z_b:.4g}" in rows[0]  # pinion (Z_D) / gear (Z_B), as the label says
    contact = [line for line in table.output.splitlines() if "contact σ_HB" in line]
    assert len(contact) == 1 and "σ_HB / σ_HD" not in contact[0] and "p / g" in contact[0]
