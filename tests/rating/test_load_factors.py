"""The one K_v / K_Hβ resolution of ISO 6336-1 (``gearcli.design.rating_load``) that the gear pair and the planet–ring
mesh share: the source of each (simulated, given, ISO / estimated) and the factors that follow, by hand."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import Rating
from gearcli.design.rating_load import MeshLoad, resolve_load_factors

MESH = MeshLoad(grade=6, normal_module_mm=4.0, transverse_pressure_angle_rad=math.radians(20.6),
                pitch_diameters_mm=(84.0, 210.0), treatments=("case_carburized", "case_carburized"),
                hlim_MPa=(1500.0, 1500.0), small=0, speed_m_s=8.0, line_load_N_mm=300.0, face_width_mm=90.0,
                resonance_ratio=0.4, resonance_lower_limit=0.85, contact_ratios=(1.6, 1.2, 2.8),
                single_pair_stiffness=14.0, mesh_stiffness=20.0, mesh_stiffness_beta=17.0, tip_relief_um=0.0,
                tooth_depth_mm=9.0)


def _n_f(b_over_h: float) -> float:
    """ISO 6336-1:2006 (7.7): N_F = (b/h)² / (1 + b/h + (b/h)²)."""
    return b_over_h**2 / (1.0 + b_over_h + b_over_h**2)


def test_given_factors_are_taken_and_the_root_and_contact_ratio_factors_follow():
    lf = resolve_load_factors(Rating(required_life_h=1000.0, dynamic_factor=1.25, face_load_factor=1.4), MESH)
    assert (lf.k_v, lf.k_v_source, lf.k_hb, lf.k_hb_source) == (1.25, "given", 1.4, "given")
    # b/h = 90/9 = 10; ε_β = 1.2 ≥ 1: Z_ε = √(1/ε_α)
    assert_allclose([lf.k_fb, lf.z_eps], [1.4 ** _n_f(10.0), math.sqrt(1.0 / 1.6)], rtol=1e-14)
    assert lf.k_ha >= 1.0 and lf.k_fa >= 1.0  # ISO's floor of K_Hα, K_Fα


@pytest.mark.parametrize(("run", "expected"), [(0.8, 1.0), (1.3, 1.3)])
def test_a_simulated_dynamic_factor_wins_over_the_file_s_and_is_at_least_one(run, expected):
    lf = resolve_load_factors(Rating(required_life_h=1000.0, dynamic_factor=1.25, face_load_factor=1.4), MESH,
                              simulated_k_v=run)
    assert (lf.k_v, lf.k_v_source) == (expected, "simulated")


def test_without_given_factors_iso_and_the_estimate_answer():
    lf = resolve_load_factors(Rating(required_life_h=1000.0), MESH)
    assert (lf.k_v_source, lf.k_hb_source) == ("iso", "estimated")
    assert lf.k_v >= 1.0 and lf.k_hb >= 1.0
    assert_allclose(lf.k_fb, lf.k_hb ** _n_f(10.0), rtol=1e-14)


def test_the_gear_pair_and_the_planet_ring_mesh_resolve_alike(tmp_path):
    """A planetary stage's two meshes take the file's K_v and K_Hβ the same way, and each its own K_Fβ from its
    b/h, h the deeper tooth of its pair ((d_a − d_f)/2; the ring's (d_f − d_a)/2)."""
    from pathlib import Path

    from gearcli import api

    cfg = Path(__file__).resolve().parents[2] / "configs" / "planetary_stage.toml"
    loaded = api.load(str(cfg), ("rating.dynamic_factor=1.3", "rating.face_load_factor=1.5"))
    st = api.design(loaded).stages[0]
    assert st.planetary is not None and st.planetary.planet_ring.rating is not None
    p = st.planetary
    depth = {"sun": max(0.5 * (g.tip_diameter_mm - g.root_diameter_mm) for g in (p.sun, p.planet)),
             "ring": max(0.5 * (p.planet.tip_diameter_mm - p.planet.root_diameter_mm),
                         0.5 * (p.ring.root_diameter_mm - p.ring.tip_diameter_mm))}
    for r, b, h in ((st.rating, st.face_width_mm, depth["sun"]),
                    (p.planet_ring.rating, p.planet_ring.face_width_mm, depth["ring"])):
        assert r is not None
        f = r.factor_table()
        assert (f["K_v"], f["K_v_source"], f["K_Hbeta"], f["K_Hbeta_source"]) == (1.3, "given", 1.5, "given")
        assert_allclose(f["K_Fbeta"], 1.5 ** _n_f(max(b / h, 3.0)), rtol=1e-14)
