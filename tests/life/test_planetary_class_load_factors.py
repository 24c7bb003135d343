"""A planetary stage's load class is rated at the class's own load (ISO 6336-6: the load factors of each load
level), both meshes, as a parallel stage's is (tests/life/test_class_load_factors.py).

The defect: life re-rated a parallel stage's classes at their own load but scaled a planetary stage's from the
duty point's rating with the point's K_Hβ, K_Hα, K_Fβ, K_Fα held (σ_H ∝ √F_t, σ_F ∝ F_t). A 5.5 kW mixer's light
batch (60 N m of 470 at the output: 210 N per planet on the sun, 6.4 N/mm) starts star-delta with a sun-mesh peak
of 3870 N, 18.4 times its static force: the light point's start classes were rated at 2460 MPa there, where
`gearcli design` at that load gives 1335 MPa and the rated batch's start class of 4280 N was 1690 MPa (1380 MPa
at its own load); the light starts gave 0.93 of the sun's pitting damage, and the sun's life was 1.4e6 h for
2.5e7 h rated at each class's load."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.design.iso6336 import ISO6336
from tests.life.test_class_load_factors import _design  # as life designs a point: K_A = 1, K_v = 1

MIXER = """
title = "Mixer planetary stage: sun 18, three planets 21, ring 60 held"
materials.steel = { density_kg_m3 = 7850, youngs_modulus_MPa = 206000, poisson_ratio = 0.3, treatment = "case_carburized", contact_fatigue_limit_MPa = 1500, bending_fatigue_limit_MPa = 500 }
input = { speed_rpm = 471.7 }
load = { torque_Nm = 470 }
lubricant = { viscosity_40C_mm2_s = 220 }
rating = { required_life_h = 30000, load_sharing_factor = 1.15 }
[[stage]]
type = "planetary"
sun = { teeth = 18, face_width_mm = 35, material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }
normal_module_mm = 2.5
planet = { teeth = 21, face_width_mm = 33, count = 3, material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }
accuracy_grade = 7
ring = { teeth = 60, face_width_mm = 33, material = "steel", rim_thickness_mm = 12, flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }
efficiency = 0.975
fixed = "ring"
input = "sun"
"""

IDLE_NM, CLASS_RATIO = 60.0, 18.4  # the light batch and its start's peak over its static sun-mesh force
MEMBERS = ("pinion", "gear")  # the sun–planet mesh's rating: sun, planet
RING_MEMBERS = ("pinion", "gear")  # the planet–ring mesh's rating: planet, ring


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    path = tmp_path_factory.mktemp("mixer") / "mixer.toml"
    path.write_text(MIXER, encoding="utf-8")
    return tuple(_design(path, torque) for torque in (IDLE_NM, IDLE_NM * CLASS_RATIO))  # light, the class


def _ring(stage):
    return stage.planetary.planet_ring.rating


def test_both_meshes_follow_isos_stress_formulas_at_the_class_load(pair):
    """By hand, ISO 6336-2 and -3 on each mesh: σ_H = σ_H0 √(K_A K_γ K_v K_Hβ K_Hα) with σ_H0 ∝ √F_t, σ_F = σ_F0 K_A
    K_γ K_v K_Fβ K_Fα with σ_F0 ∝ F_t: the class's stress is the idle point's scaled by √ratio (ratio) and by the
    factors' change; the light point's factors held overstate it (the defect's size)."""
    (_, idle), (_, full) = pair
    for get in (lambda s: s.rating, _ring):
        ri, rf = get(idle.stages[0]), get(full.stages[0])
        hand_h = ri.pinion.sigma_H_MPa * math.sqrt(CLASS_RATIO * (rf.K_Hbeta * rf.K_Halpha) / (ri.K_Hbeta * ri.K_Halpha))
        hand_f = ri.pinion.sigma_F_MPa * CLASS_RATIO * (rf.K_Fbeta * rf.K_Falpha) / (ri.K_Fbeta * ri.K_Falpha)
        assert_allclose(rf.pinion.sigma_H_MPa, hand_h, rtol=1e-12)
        assert_allclose(rf.pinion.sigma_F_MPa, hand_f, rtol=1e-12)
        assert ri.K_Hbeta > 1.3 * rf.K_Hbeta  # ISO's K_Hβ falls as the line load rises
        assert ri.pinion.sigma_H_MPa * math.sqrt(CLASS_RATIO) > 1.15 * rf.pinion.sigma_H_MPa


def test_a_planetary_class_is_rated_as_the_design_at_its_own_load(pair):
    """The whole stage re-rated at 18.4x the light point's forces is `gearcli design` at 18.4x its torque: the
    sun–planet and the planet–ring meshes, every member and mode, and their load factors (K_γ on top, as the
    design rates the most loaded planet)."""
    (idle_loaded, idle), (_, full) = pair
    stage = ISO6336.rate_stage_at_force(idle_loaded.design, idle.stages[0], CLASS_RATIO)
    ref = full.stages[0]
    for get in (lambda s: s.rating, _ring):
        rated, want = get(stage), get(ref)
        for member in MEMBERS:
            for mode in ("pitting", "bending"):
                assert_allclose(getattr(rated, member).stress_MPa(mode), getattr(want, member).stress_MPa(mode),
                                rtol=1e-12, err_msg=f"{member} {mode}")
        for factor in ("K_Hbeta", "K_Halpha", "K_Fbeta", "K_Falpha", "K_gamma", "sigma_H0_MPa"):
            assert_allclose(getattr(rated, factor), getattr(want, factor), rtol=1e-12, err_msg=factor)


def test_life_rates_a_planetary_class_at_its_own_load(pair):
    """The life's class stress (gearcli.life.run._stress) of the light point at 18.4x its load is the full-load
    design's for the sun, the planet, the ring and the planet's ring side; at the point's own load (ratio 1) it is
    the point's rating, unchanged."""
    from gearcli.life import run

    (idle_loaded, idle), (_, full) = pair
    pd = _point(run, idle_loaded.design, idle)
    st, ref = idle.stages[0], full.stages[0]
    sun_f0 = st.static_force_N.tangential
    ring_f0 = st.planetary.planet_ring.static_force_N.tangential
    cases = [("pinion", ref.rating.pinion, st.rating.pinion, sun_f0), ("gear", ref.rating.gear, st.rating.gear, sun_f0),
             ("planet_ring_side", _ring(ref).pinion, _ring(st).pinion, ring_f0),
             ("ring", _ring(ref).gear, _ring(st).gear, ring_f0)]
    for member, want, own, f0 in cases:
        for mode in ("pitting", "bending"):
            assert_allclose(run._stress(pd, 0, member, mode, CLASS_RATIO * f0, f0), want.stress_MPa(mode),
                            rtol=1e-12, err_msg=f"{member} {mode}")
            assert run._stress(pd, 0, member, mode, f0, f0) == own.stress_MPa(mode)


def _point(run, cfg, design):
    """A life point's data with the fields _stress reads (its design and file)."""
    from gearcli.life.duty import DutyPoint
    from gearcli.life.result import PointRun

    point = DutyPoint("light", 1.0, IDLE_NM, 471.7)
    return run._PointData(point, design, cfg, [], None, PointRun("light", 1.0, IDLE_NM, 471.7, (1.0,)))


def test_a_plug_in_standards_stage_re_rating_is_held_to_the_protocol(pair):
    """A registered standard's optional ``rate_stage_at_force`` is checked as its ``rate_design`` is: a stage of
    another type or a rating without the standard's title is a PluginError naming the call, not a traceback in
    life; ISO's own stage passes through the check unchanged."""
    from gearcli.errors import PluginError
    from gearcli.rating.guard import Guarded

    (idle_loaded, idle), _ = pair
    stage = idle.stages[0]

    class _Std:
        name, title = "test_stage_at_force", ISO6336.title

        def __init__(self, out):
            self.out = out

        def rate_stage_at_force(self, cfg, st, ratio):
            return self.out

    good = ISO6336.rate_stage_at_force(idle_loaded.design, stage, CLASS_RATIO)
    assert Guarded(_Std(good)).rate_stage_at_force(idle_loaded.design, stage, CLASS_RATIO) is good
    assert Guarded(_Std(None)).rate_stage_at_force(idle_loaded.design, stage, CLASS_RATIO) is None
    with pytest.raises(PluginError, match="rate_stage_at_force"):
        Guarded(_Std(good.rating)).rate_stage_at_force(idle_loaded.design, stage, CLASS_RATIO)
