"""S–N curves from the ISO 6336-2/-3 life factors and the ISO 6336-6 Miner variants, by hand."""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from gearcli.life.miner import SNCurve, miner_damage, spectrum_safety

ZNT_EH = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))  # ISO 6336-2:2006 Table 2, case-carburized
K_FIN = math.log(5e7 / 1e5) / math.log(1.6)  # N ∝ sigma^-k on the finite-life branch: 13.22
K_LONG = math.log(1e10 / 5e7) / math.log(1 / 0.85)  # beyond the knee, normal quality: 32.6


def test_iso_curve_passes_through_the_table_nodes():
    c = SNCurve(ZNT_EH, 1000.0)
    assert_allclose([c.cycles_to_failure(1600.0), c.cycles_to_failure(1000.0), c.cycles_to_failure(850.0)],
                    [1e5, 5e7, 1e10], rtol=1e-12)
    assert_allclose(c.cycles_to_failure(800.0), 1e10 * (850 / 800) ** K_LONG, rtol=1e-12)  # slope continued
    assert_allclose(K_FIN, 13.22, atol=5e-3)  # ISO: Z_NT = (5e7/N_L)^0.0756 -> k = 1/0.0756
    assert_allclose(1 / K_LONG, 0.0307, atol=5e-5)  # the rating's (5e7/N_L)^0.0307
    for n in (2e5, 1e7, 3e9):  # stress_at inverts cycles_to_failure
        assert_allclose(c.cycles_to_failure(c.stress_at(n)), n, rtol=1e-10)


def test_optimum_quality_has_no_damage_below_the_endurance_limit():
    c = SNCurve(ZNT_EH, 1000.0, optimum=True)
    assert math.isinf(c.cycles_to_failure(999.0))
    assert_allclose(c.cycles_to_failure(1001.0), 5e7 * (1000 / 1001) ** K_FIN, rtol=1e-12)


def test_miner_elementary_and_modified_below_the_knee():
    el = SNCurve(ZNT_EH, 1000.0, "elementary")
    mod = SNCurve(ZNT_EH, 1000.0, "modified")
    assert_allclose(el.cycles_to_failure(900.0), 5e7 * (1000 / 900) ** K_FIN, rtol=1e-12)
    assert_allclose(mod.cycles_to_failure(900.0), 5e7 * (1000 / 900) ** (2 * K_FIN - 1), rtol=1e-12)
    # above the knee all variants are the same curve
    for c in (el, mod):
        assert_allclose(c.cycles_to_failure(1200.0), 5e7 * (1000 / 1200) ** K_FIN, rtol=1e-12)


def test_endurance_limit_of_each_variant():
    """The stress under which a spectrum has an infinite life: the iso curve's last node (normal quality, 0.85 σ_∞ at
    1e10) or its knee (optimum, flat); Miner elementary and modified have none: every stress damages on their slope."""
    assert_allclose(SNCurve(ZNT_EH, 1000.0).endurance_limit_MPa, 850.0, rtol=1e-12)
    assert_allclose(SNCurve(ZNT_EH, 1000.0, optimum=True).endurance_limit_MPa, 1000.0, rtol=1e-12)
    for variant in ("elementary", "modified"):
        c = SNCurve(ZNT_EH, 1000.0, variant)
        assert c.endurance_limit_MPa == 0.0 and math.isfinite(c.cycles_to_failure(100.0))


def test_spectrum_safety_closed_form():
    """One class on the finite-life branch: D(s) = n (sigma s^e / sigma_0)^k / N_0 = 1 solved by hand."""
    c = SNCurve(ZNT_EH, 1000.0, "elementary")
    sigma, n, e = 1300.0, 2e6, 0.5  # pitting: the stress goes with sqrt(load)
    exact = ((1600.0 / sigma) * (1e5 / n) ** (1 / K_FIN)) ** (1 / e)
    s = spectrum_safety(lambda x: miner_damage([sigma * x**e], [n], [c]))
    assert_allclose(s, exact, rtol=1e-10)


def test_miner_sum_of_a_published_example():
    """Palmgren–Miner example (Modarres, Amiri, Jackson, Probabilistic Physics of Failure Approach to
    Reliability, 2017, pp. 33-37, as reproduced in the `reliability` package docs): lives 50000, 6500 and
    1000 h at three stresses; each duty cycle spends 40, 15 and 5 min at them; the parts last 7400.38 cycles,
    and the stresses take 9.867 %, 28.463 % and 61.670 % of the damage. Each level gets a curve whose knee
    sits at its published life (the stress 1 is the knee), so the curve gives exactly that life."""
    lives = [50000.0, 6500.0, 1000.0]
    curves = [SNCurve(((life / 2, 2.0), (life, 1.0), (life * 2, 0.5)), 1.0) for life in lives]
    hours = [40 / 60, 15 / 60, 5 / 60]
    d = miner_damage([1.0, 1.0, 1.0], hours, curves)  # each at its curve's knee: N = the life in hours
    assert_allclose(1 / d, 7400.38, atol=0.005)
    shares = [h / life / d for h, life in zip(hours, lives, strict=True)]
    assert_allclose(shares, [0.0986717, 0.28463, 0.6166983], atol=5e-6)
