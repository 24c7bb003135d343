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


def test_spectrum_safety_beyond_the_first_bracket():
    """The load multiplier that makes D = 1 lies outside [1e-3, 1e3] for a gross overload or a very light spectrum:
    the root find widens its bracket and finds it (by hand, the curve inverted), never stops at the bracket's end.
    Before the fix a spectrum past D = 1 at s = 1e-3 was reported as s = 1e-3 (the 100 x overload of a 60 mm spur
    pair, `gearcli life` at 5e7 N m: 0.001 for 6.0e-5, its stress safety 0.032 for 0.0078), and one below D = 1 at
    s = 1e3 as unbounded (None)."""
    el = SNCurve(ZNT_EH, 1000.0, "elementary")
    # overload, pitting (stress ∝ sqrt(s)): one class 60 x the knee stress, 1e8 cycles on the finite-life slope
    # extrapolated past the static node: sigma sqrt(s) = 1600 (1e5 / n)^(1/k)
    sigma, n = 60_000.0, 1e8
    exact = (1600.0 * (1e5 / n) ** (1 / K_FIN) / sigma) ** 2
    assert exact < 1e-3  # 4.2e-4 (outside the first bracket)
    s = spectrum_safety(lambda x: miner_damage([sigma * x**0.5], [n], [el]))
    assert_allclose(s, exact, rtol=1e-10)
    # overload, bending (stress ∝ s): the multiplier 1.9e-6, 500 x below the first bracket
    sigma_f = 5e8
    exact_f = 1600.0 * (1e5 / n) ** (1 / K_FIN) / sigma_f
    assert exact_f < 1e-5
    assert_allclose(spectrum_safety(lambda x: miner_damage([sigma_f * x], [n], [el])), exact_f, rtol=1e-10)
    # a light spectrum on the optimum curve (flat at the knee): D = 1 once the stress reaches the knee's 1000
    # with n above the knee's 5e7 cycles, so s = (1000 / sigma)^2 for pitting: 4e4 at 5 N/mm^2
    opt = SNCurve(ZNT_EH, 1000.0, optimum=True)
    s_opt = spectrum_safety(lambda x: miner_damage([5.0 * x**0.5], [1e9], [opt]))
    assert s_opt is not None
    assert_allclose(s_opt, (1000.0 / 5.0) ** 2, rtol=1e-9)
    # and the normal curve's slope beyond 1e10 (k 32.6): sigma sqrt(s) = 850 (1e10 / n)^(1/K_LONG), n = 1e12
    normal = SNCurve(ZNT_EH, 1000.0)
    exact_n = (850.0 * (1e10 / 1e12) ** (1 / K_LONG) / 10.0) ** 2
    assert exact_n > 1e3
    assert_allclose(spectrum_safety(lambda x: miner_damage([10.0 * x**0.5], [1e12], [normal])), exact_n, rtol=1e-9)
    # nothing to load: every class at zero stress stays unbounded
    assert spectrum_safety(lambda x: miner_damage([0.0 * x], [1e9], [normal])) is None

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
