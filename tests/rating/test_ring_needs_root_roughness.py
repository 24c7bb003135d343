"""The planet–ring mesh needs the ring's root roughness (Y_RrelT, ISO 6336-3:2006 13.3): without it the mesh was rated
as if the ring's root were polished (R_z < 1 µm: Y_RrelT = 1.025 for a nitrided ring, against 4.299 − 3.259 · 13^0.0058
= 0.99115 at R_z 12), an unconservative S_F with no word. Now it is not rated, with the ``unrated_mesh`` warning naming
the key, as a missing flank roughness already was."""

from __future__ import annotations

from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design


def _doc(ring_root_rz: float | None) -> dict:
    eh = {"density_kg_m3": 7850, "youngs_modulus_MPa": 206000, "poisson_ratio": 0.3, "treatment": "case_carburized",
          "contact_fatigue_limit_MPa": 1500, "bending_fatigue_limit_MPa": 460}
    nt = {**eh, "treatment": "nitrided", "contact_fatigue_limit_MPa": 1000, "bending_fatigue_limit_MPa": 400}
    rough = {"flank_roughness_Rz_um": 3, "root_roughness_Rz_um": 10}
    ring = {"teeth": 81, "face_width_mm": 25, "material": "nt", "flank_roughness_Rz_um": 4}
    if ring_root_rz is not None:
        ring["root_roughness_Rz_um"] = ring_root_rz
    stage = {"type": "planetary", "normal_module_mm": 2, "normal_pressure_angle_deg": 20, "accuracy_grade": 6,
             "sun": {"teeth": 21, "face_width_mm": 25, "material": "eh", **rough},
             "planet": {"teeth": 30, "face_width_mm": 25, "count": 3, "material": "eh", **rough},
             "ring": ring, "fixed": "ring", "input": "sun"}
    return {"materials": {"eh": eh, "nt": nt}, "stage": [stage], "input": {"speed_rpm": 1500},
            "load": {"torque_Nm": 300}, "lubricant": {"viscosity_40C_mm2_s": 150},
            "rating": {"required_life_h": 10000, "face_load_factor": 1.2}}


def test_ring_root_roughness_sets_y_rrelt():
    design = compute_design(DesignFile.model_validate(_doc(12.0)))
    ring = design.stages[0].planetary.planet_ring.rating.gear
    assert_allclose(ring.Y_R_rel_T, 4.299 - 3.259 * 13.0 ** 0.0058, rtol=1e-12)  # GG, NT, NV line, R_z 12 µm


def test_missing_ring_root_roughness_leaves_the_ring_mesh_unrated_with_a_warning():
    design = compute_design(DesignFile.model_validate(_doc(None)))
    st = design.stages[0]
    assert st.rating is not None  # the sun–planet mesh is rated
    assert st.planetary.planet_ring.rating is None
    found = [d for d in design.diagnostics if d.data.get("mesh") == "planet_ring" and d.data.get("key")]
    assert [d.data["key"] for d in found] == ["stage[0].ring.root_roughness_Rz_um"]
