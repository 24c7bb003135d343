"""``gearcli life --static`` on the S–N curve of every ISO 6336-5 material group, by hand (round-4 trial tr29e).

Scene: one helical stage 21/67, m_n 6 (so Y_X < 1), β 14°, x 0.3/0.1, grade 6, rated over four duty points: a long
light one (past the knee), a nominal one, a short heavy one, and an overload for minutes (beyond the static node). Five pairs put
each of the ten `treatment` groups on one member: a surface-hardened pinion (case-carburized, nitrided,
nitrocarburized, induction or flame hardened) on a through-hardened, structural, cast steel, nodular or grey iron
wheel (the first with `surface_hardness_HV`, so Z_W acts on it).

Independent of the code: every bin's stress and endurance strength from the hand rating of ISO 6336-1/-2/-3
(``tests/reference/rating_hand.py``: every formula typed again) at the point's torque and speed with K_A = 1
(σ_∞ = σ_HG / Z_NT, σ_FG / Y_NT: Z_L, Z_V, Z_R, Z_W, Y_δrelT, Y_RrelT, Y_X of the point), the load cycles, and the
curves' nodes typed here from ISO 6336-2:2006 Table 2 (no pitting permitted) and ISO 6336-3:2006 Table 3 per group:
cycles to failure by inverting the power law of the segment that holds the stress (the first segment continued above
the static node, the last below 0.85 at 1e10, the `iso` variant with normal quality), Miner's sum, the life, and the
load multiplier that makes D = 1 (σ_H ∝ √F, σ_F ∝ F).
"""

from __future__ import annotations

import json
import math

import pytest
import tomli_w
from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gearcli.cli import cli
from tests.reference.rating_hand import Member, Pair, rate, toml_doc

# (treatment, σ_Hlim, σ_Flim, E, ν)
GROUPS = {
    "case_carburized": (1500.0, 500.0, 206000.0, 0.3), "nitrided": (1250.0, 420.0, 206000.0, 0.3),
    "nitrocarburized": (650.0, 290.0, 206000.0, 0.3), "induction_hardened": (1150.0, 360.0, 206000.0, 0.3),
    "flame_hardened": (1100.0, 340.0, 206000.0, 0.3), "through_hardened": (760.0, 310.0, 206000.0, 0.3),
    "structural_steel": (430.0, 200.0, 206000.0, 0.3), "cast_steel": (440.0, 170.0, 202000.0, 0.3),
    "nodular_iron": (600.0, 245.0, 173000.0, 0.275), "grey_iron": (350.0, 80.0, 118000.0, 0.3),
}
PAIRS = [("case_carburized", "through_hardened"), ("nitrided", "nodular_iron"), ("nitrocarburized", "grey_iron"),
         ("induction_hardened", "structural_steel"), ("flame_hardened", "cast_steel")]
# (N_L, life factor) nodes: ISO 6336-2:2006 Table 2 (Z_NT) and ISO 6336-3:2006 Table 3 (Y_NT)
PITTING = {**dict.fromkeys(("case_carburized", "induction_hardened", "flame_hardened", "through_hardened",
                            "structural_steel", "cast_steel", "nodular_iron"), ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))),
           **dict.fromkeys(("nitrided", "grey_iron"), ((1e5, 1.3), (2e6, 1.0), (1e10, 0.85))),
           "nitrocarburized": ((1e5, 1.1), (2e6, 1.0), (1e10, 0.85))}
BENDING = {**dict.fromkeys(("through_hardened", "structural_steel", "cast_steel", "nodular_iron"),
                           ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85))),
           **dict.fromkeys(("case_carburized", "induction_hardened", "flame_hardened"), ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85))),
           **dict.fromkeys(("nitrided", "grey_iron"), ((1e3, 1.6), (3e6, 1.0), (1e10, 0.85))),
           "nitrocarburized": ((1e3, 1.1), (3e6, 1.0), (1e10, 0.85))}
Z1, Z2 = 21, 67


def cycles_to_failure(ratio: float, nodes) -> float:
    """N where the curve's factor equals σ/σ_∞: the segment that holds it, the first continued above the static node
    and the last below its end node."""
    (n0, y0), (n1, y1), (n2, y2) = nodes
    (na, ya), (nb, yb) = ((n0, y0), (n1, y1)) if ratio >= y1 else ((n1, y1), (n2, y2))
    return na * (ratio / ya) ** (math.log(nb / na) / math.log(yb / ya))


def pair(tp: str, tg: str, torque_out_Nm: float, speed_rpm: float, hours: float) -> Pair:
    def member(t: str, z: int, b: float, x: float, rz: tuple[float, float], hv: float | None) -> Member:
        h, f, e, nu = GROUPS[t]
        return Member(z, b, t, h, f, rz[0], rz[1], x=x, hv=hv, e_mod=e, nu=nu, rho=7.83e-6)
    return Pair(p=member(tp, Z1, 65.0, 0.3, (3.0, 10.0), None), g=member(tg, Z2, 60.0, 0.1, (4.0, 12.0), 300.0),
                mn=6.0, alpha_n_deg=20.0, beta_deg=14.0, grade=6, torque_pinion_Nm=torque_out_Nm * Z1 / Z2,
                n1_rpm=speed_rpm, k_a=1.0, nu40=220.0, life_h=hours)


@pytest.mark.parametrize(("tp", "tg"), PAIRS)
def test_static_life_follows_each_groups_sn_curve(tmp_path, tp, tg):
    nominal = 4000.0 * (min(GROUPS[tp][0], GROUPS[tg][0]) / 1500.0) ** 2  # comparable stress levels for each pair
    points = [(15000.0, 0.6 * nominal, 1000.0), (4000.0, nominal, 600.0), (20.0, 3.0 * nominal, 300.0),
              (0.05, 20.0 * nominal, 100.0)]
    doc = toml_doc(pair(tp, tg, nominal, 1000.0, sum(h for h, _, _ in points)))
    doc["duty"] = [{"name": f"p{i}", "hours": h, "torque_Nm": t, "speed_rpm": n} for i, (h, t, n) in enumerate(points)]
    path = tmp_path / "scene.toml"
    path.write_text(tomli_w.dumps(doc))
    res = CliRunner().invoke(cli, ["-q", "life", str(path), "--static", "--format", "json"])
    assert res.exit_code == 0, res.output
    stage = json.loads(res.stdout)["life"]["stages"][0]
    hands = [rate(pair(tp, tg, t, n, h)) for h, t, n in points]
    hours = sum(h for h, _, _ in points)
    for member, treatment in (("pinion", tp), ("gear", tg)):
        for mode, stress, strength, factor, nodes, exponent in (
                ("pitting", "sigma_H", "sigma_HG", "Z_NT", PITTING[treatment], 0.5),
                ("bending", "sigma_F", "sigma_FG", "Y_NT", BENDING[treatment], 1.0)):
            got = stage[member][mode]
            bins = [(h[member]["load_cycles"], h[member][stress], h[member][strength] / h[member][factor]) for h in hands]
            assert_allclose([b["cycles"] for b in got["bins"]], [n for n, _, _ in bins], rtol=1e-12)
            assert_allclose([b["stress_MPa"] for b in got["bins"]], [s for _, s, _ in bins], rtol=1e-9)
            assert_allclose([b["endurance_MPa"] for b in got["bins"]], [e for _, _, e in bins], rtol=1e-9)
            assert_allclose([b["cycles_to_failure"] for b in got["bins"]],
                            [cycles_to_failure(s / e, nodes) for _, s, e in bins], rtol=1e-6)

            def damage(scale: float, bins=bins, nodes=nodes, exponent=exponent) -> float:
                return sum(n / cycles_to_failure(s * scale ** exponent / e, nodes) for n, s, e in bins)

            assert_allclose(got["damage"], damage(1.0), rtol=1e-6)
            assert got["below_endurance"] is (max(s / e for _, s, e in bins) < 0.85)
            if not got["below_endurance"]:
                assert_allclose(got["life_h"], hours / damage(1.0), rtol=1e-6)
            multiplier = brentq(lambda s: math.log(damage(s)), 1e-3, 1e3, xtol=1e-14)
            assert_allclose(got["load_multiplier"], multiplier, rtol=1e-7)
            assert_allclose(got["stress_safety"], multiplier ** exponent, rtol=1e-7)
