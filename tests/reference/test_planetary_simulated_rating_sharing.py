"""A rating at the simulated K_v of a planetary stage whose planets' position errors share the load: K_gamma is 1.

Trial tr22b: a ring-held stage with planet errors [3, 0, -1] µm and `[rating] load_sharing_factor = 1.2`, `dynamic_factor
= "simulated"`, was rated at K_v 1.213 (the most loaded planet's window max over the mean planet's static force: the
simulated sharing itself on a quiet run) times K_gamma 1.2: the unequal sharing counted twice (σ_H 1035 MPa for 968).
The dynamic life already sets K_gamma = 1 when the planets' errors are simulated (docs/life.md, "Load sharing").

Reference, independent of the code: the hand model of load sharing (tests/reference/test_planetary_worst_planet.py):
each planet's sun and ring meshes in series, k_eq = k_sp k_rp / (k_sp + k_rp), F_j = F_mean + k_eq (e_j - mean(e)),
so the most loaded planet's share, the settled window's K_v, is 1 + k_eq (max(e) - mean(e)) / F_mean; and ISO 6336-2's
σ_H = σ_H0 √(K_A K_γ K_v K_Hβ K_Hα) with K_γ = 1.
"""

from __future__ import annotations

import math

import pytest

from gearcli import api
from tests.reference import test_planetary_worst_planet as worst  # its scene; errors and rating added

N = worst.N
ERRORS_UM = (3.0, 0.0, -1.0)
K_GAMMA = 1.2
MEMBER = 'face_width_mm = 40, material = "case", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10'
SCENE = (
    "materials.case = { density_kg_m3 = 7850, youngs_modulus_MPa = 206000, poisson_ratio = 0.3, treatment = "
    '"case_carburized", contact_fatigue_limit_MPa = 1500, bending_fatigue_limit_MPa = 460 }\n'
    "lubricant = { viscosity_40C_mm2_s = 220, viscosity_100C_mm2_s = 19, temperature_C = 70 }\n"
    f'rating = {{ required_life_h = 20000, load_sharing_factor = {K_GAMMA}, dynamic_factor = "simulated" }}\n'
    + worst.SCENE.replace("face_width_mm = 40", MEMBER)
    .replace(f"position_error_um = [0.0, {worst.E_UM}, 0.0]", f"position_error_um = {list(ERRORS_UM)}")
    .replace('type = "planetary"', 'type = "planetary"\naccuracy_grade = 6'))


def test_simulated_sharing_is_not_multiplied_by_k_gamma(tmp_path):
    (tmp_path / "rated.toml").write_text(SCENE)
    loaded, design = api.load_and_design(str(tmp_path / "rated.toml"))
    result = api.simulate(loaded.design, design)
    st, ds = result.stages[0], design.stages[0]
    k_eq, f_mean = worst.series_stiffness(ds)  # the hand model's series stiffness and mean planet's line force
    share = 1 + k_eq * (max(ERRORS_UM) - sum(ERRORS_UM) / N) * 1e-6 / f_mean  # the hand model's most loaded planet
    assert share > 1.05  # the errors matter
    r = st.rating
    assert r.K_v_source == "simulated"
    assert r.K_v == pytest.approx(share, rel=1e-3)
    assert r.K_gamma == 1.0
    assert r.sigma_H_MPa == pytest.approx(r.sigma_H0_MPa * math.sqrt(r.K_A * share * r.K_Hbeta * r.K_Halpha), rel=1e-3)
    ring = st.planet_ring_rating
    assert ring.K_gamma == 1.0 and ring.K_v == pytest.approx(share, rel=1e-3)
    assert any(w.code == "load_sharing" and w.data["load_sharing_factor"] == K_GAMMA for w in result.diagnostics)
    # the design itself (ISO's K_v, identical planets) keeps the file's K_gamma
    assert ds.rating.K_gamma == K_GAMMA
