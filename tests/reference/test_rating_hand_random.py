"""Seeded random gear pairs rated by gearcli and by ``rating_hand`` (ISO 6336:2006 method B typed again by hand).

``test_rating_hand_pairs`` checks named scenes, each chosen for one branch of the standard; here the branches are
crossed at random, as a user's files cross them: any two of the ten ISO 6336-5 material groups (with or without a
surface hardness, so Z_W on either member or none), spur or helical (ε_β below and above 1), α_n 17.5 … 25°, four
basic racks, m_n 1 … 20, profile shifts, grades 3 … 11, tip relief or none, K_Hβ given or estimated, pitch-line
speeds from a few cm/s to some 100 m/s (the running-in caps, every K_v range of method B) and lives from the static
range of Z_NT and Y_NT to past 1e10 cycles, "normal" and "optimum". Every factor, stress, limit and safety of the
design must equal the hand calculation to 1e-9 (the same closed forms in double precision).

The generator keeps to ``rating_hand``'s scope: ε_α ≥ 1 and a nominal F_t at or above gearcli's floor of 1 N per mm
of face width (below it gearcli rates the floor, a separate test); everything else is drawn freely.
"""

from __future__ import annotations

import math
import random

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from tests.reference.rating_hand import Member, Pair, geometry, rate, toml_doc

GROUPS = ("case_carburized", "nitrided", "nitrocarburized", "induction_hardened", "flame_hardened",
          "through_hardened", "structural_steel", "cast_steel", "nodular_iron", "grey_iron")
RACKS = ((1.0, 1.25, 0.38), (1.0, 1.25, 0.25), (1.0, 1.4, 0.39), (1.1, 1.35, 0.3))  # h_aP*, h_fP*, ρ_fP*
STAGE = ("K_v", "K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha", "Z_H", "Z_E", "Z_eps", "Z_beta", "Z_L", "Z_V", "Z_R",
         "Z_W", "Y_beta", ("sigma_H0", "sigma_H0_MPa"), ("sigma_H", "sigma_H_MPa"))
MEMBER = ("load_cycles", "Z_BD", "Z_NT", "Y_F", "Y_S", "Y_DT", "Y_delta_rel_T", "Y_R_rel_T", "Y_X", "Y_NT", "S_H",
          "S_F", ("sigma_H", "sigma_H_MPa"), ("sigma_HG", "sigma_HG_MPa"), ("sigma_F0", "sigma_F0_MPa"),
          ("sigma_F", "sigma_F_MPa"), ("sigma_FG", "sigma_FG_MPa"))
SEEDS = range(120)


def _member(rng: random.Random, teeth: int, width: float, shift: float) -> Member:
    group = rng.choice(GROUPS)
    return Member(teeth, width, group, rng.uniform(300.0, 1600.0), rng.uniform(100.0, 520.0), rng.uniform(0.5, 12.0),
                  rng.uniform(0.5, 45.0), x=shift, hv=rng.choice([None, rng.uniform(150.0, 750.0)]),
                  e_mod=170000.0 if group.endswith("iron") else 206000.0)


def _pair(seed: int) -> Pair:
    """A pair drawn from ``seed``, redrawn until it lies in the hand calculation's scope."""
    rng = random.Random(seed)
    while True:
        z1 = rng.randint(15, 40)
        z2 = rng.randint(z1 + 1, 140)
        mn = rng.choice((1.0, 1.5, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0))
        beta = rng.choice((0.0, rng.uniform(5.0, 30.0)))
        b = rng.uniform(0.2, 1.2) * z1 * mn / math.cos(math.radians(beta))
        q = Pair(_member(rng, z1, b * rng.uniform(1.0, 1.2), rng.uniform(0.0, 0.7)),
                 _member(rng, z2, b, rng.uniform(-0.3, 0.5)),
                 mn=mn, alpha_n_deg=rng.choice((17.5, 20.0, 22.5, 25.0)), beta_deg=beta, grade=rng.randint(3, 11),
                 torque_pinion_Nm=rng.uniform(0.2, 3.0) * (z1 * mn) ** 2 * b * 1e-3 * rng.choice((0.05, 0.5, 1.5)),
                 n1_rpm=10.0 ** rng.uniform(0.5, 4.3), k_a=rng.uniform(1.0, 2.0), nu40=rng.uniform(20.0, 1000.0),
                 life_h=10.0 ** rng.uniform(-2.0, 5.5), c_a=rng.choice((0.0, rng.uniform(0.0, 30.0))),
                 k_hbeta=rng.choice((None, None, rng.uniform(1.0, 2.5))), rack=rng.choice(RACKS),
                 quality=rng.choice(("normal", "optimum")))
        g = geometry(q)
        if g["ea"] >= 1.0 and q.torque_pinion_Nm * 2000.0 / g["d"][0] >= g["b"]:
            return q


def _pairs(names: tuple, tool: object, hand: dict) -> list[tuple[str, float, float]]:
    out = []
    for name in names:
        mine, theirs = name if isinstance(name, tuple) else (name, name)
        out.append((mine, getattr(tool, theirs), hand[mine]))
    return out


@pytest.mark.parametrize("seed", SEEDS)
def test_random_pair_against_the_hand_calculation(seed):
    q = _pair(seed)
    hand = rate(q)
    rating = compute_design(DesignFile.model_validate(toml_doc(q))).stages[0].rating
    rows = _pairs(STAGE, rating, hand)
    for part in ("pinion", "gear"):
        rows += [(f"{part}.{k}", v, h) for k, v, h in _pairs(MEMBER, getattr(rating, part), hand[part])]
    names, got, want = zip(*rows, strict=True)
    bad = [n for n, a, b in rows if not math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)]
    assert_allclose(got, want, rtol=1e-9, atol=1e-12, err_msg=f"seed {seed}: {bad} of {len(names)}")


def test_the_random_pairs_cross_the_branches():
    """The draw reaches what it claims to: every material group on both members, all four K_v ranges, K_Hβ above 2,
    ε_β below and above 1, the static range and the region past 1e10 cycles, Z_W on either member."""
    hands = [(_pair(s), rate(_pair(s))) for s in SEEDS]
    assert {q.p.treatment for q, _ in hands} == set(GROUPS) == {q.g.treatment for q, _ in hands}
    assert {h["range"] for _, h in hands} >= {"subcritical", "main", "intermediate", "supercritical"}
    assert any(h["K_Hbeta"] > 2.0 for _, h in hands)
    assert any(0.0 < h["g"]["eb"] < 1.0 for _, h in hands) and any(h["g"]["eb"] >= 1.0 for _, h in hands)
    assert any(h["pinion"]["load_cycles"] < 1e5 for _, h in hands) and any(h["gear"]["load_cycles"] > 1e10 for _, h in hands)
    assert any(h["pinion"]["Z_W"] > 1.0 for _, h in hands) and any(h["gear"]["Z_W"] > 1.0 for _, h in hands)
