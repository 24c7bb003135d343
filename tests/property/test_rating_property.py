"""The strength rating over random stages and materials: a finite rating within ISO's bounds, or a DesignError
naming a key; never another exception (a traceback) and never a NaN."""

from __future__ import annotations

import dataclasses
import math

from hypothesis import given, settings
from hypothesis import strategies as st

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.design.rating_factors import TREATMENTS
from gearcli.errors import DesignError

ROUGH = {"flank_roughness_Rz_um": 4.0, "root_roughness_Rz_um": 12.0}


# a profile shift is 0 or at least 1e-6 in magnitude (the design file refuses a nonzero subnormal-like shift)
SHIFTS = st.floats(-0.3, 1.0).map(lambda x: x if abs(x) >= 1e-6 else 0.0)


@st.composite
def rated_designs(draw):
    beta = draw(st.one_of(st.just(0.0), st.floats(1.0, 40.0)))
    hands = ({"hand": "left"}, {"hand": "right"}) if beta else ({}, {})
    widths = draw(st.floats(2.0, 400.0)), draw(st.floats(2.0, 400.0))
    materials = {name: {"density_kg_m3": 7800.0, "youngs_modulus_MPa": draw(st.floats(1e5, 2.2e5)),
                        "poisson_ratio": 0.3, "treatment": draw(st.sampled_from(TREATMENTS)),
                        "contact_fatigue_limit_MPa": draw(st.floats(300.0, 1700.0)),
                        "bending_fatigue_limit_MPa": draw(st.floats(100.0, 600.0)),
                        "surface_hardness_HV": draw(st.floats(150.0, 750.0))} for name in ("a", "b")}
    stage = {"normal_module_mm": draw(st.floats(0.5, 40.0)), "helix_angle_deg": beta,
             "normal_pressure_angle_deg": draw(st.floats(15.0, 25.0)), "accuracy_grade": draw(st.integers(1, 12)),
             "tip_relief_um": draw(st.floats(0.0, 100.0, allow_subnormal=False)),  # a subnormal is refused
             "pinion": {"teeth": draw(st.integers(8, 120)), "face_width_mm": widths[0], "material": "a",
                        "profile_shift": draw(SHIFTS), **hands[0], **ROUGH},
             "gear": {"teeth": draw(st.integers(8, 300)), "face_width_mm": widths[1], "material": "b",
                      "profile_shift": draw(SHIFTS), **hands[1], **ROUGH}}
    rating = {"required_life_h": draw(st.floats(1.0, 2e5)),
              "material_quality": draw(st.sampled_from(["normal", "optimum"])),
              "dynamic_factor": draw(st.one_of(st.just("iso"), st.floats(1.0, 3.0)))}
    if draw(st.booleans()):
        rating["face_load_factor"] = draw(st.floats(1.0, 2.5))
    return {"materials": materials, "stage": [stage], "input": {"speed_rpm": draw(st.floats(1.0, 2e4))},
            "load": {"torque_Nm": draw(st.one_of(st.just(0.0), st.floats(1.0, 1e5), st.floats(-1e5, -1.0))), "application_factor": draw(st.floats(1.0, 2.0))},
            "lubricant": {"viscosity_40C_mm2_s": draw(st.floats(20.0, 1000.0))}, "rating": rating}


def _floats(obj):
    for f in dataclasses.fields(obj):
        v = getattr(obj, f.name)
        if dataclasses.is_dataclass(v):
            yield from _floats(v)
        elif isinstance(v, float):
            yield f.name, v


@settings(max_examples=150, deadline=None, derandomize=True, database=None)
@given(rated_designs())
def test_rating_is_finite_and_within_the_standards_bounds(doc):
    try:
        result = compute_design(DesignFile.model_validate(doc))
    except DesignError as exc:
        assert exc.key  # names the key to change
        return
    st_, r = result.stages[0], result.stages[0].rating
    assert all(math.isfinite(v) for _, v in _floats(r))
    assert r.K_Hbeta >= 1.0 and 1.0 <= r.K_Fbeta <= r.K_Hbeta
    assert r.K_Halpha >= 1.0 and r.K_Falpha >= 1.0 and r.Z_eps > 0.0 and r.Z_beta >= 1.0 and 0.0 < r.Y_beta <= 1.0
    if st_.contact_ratio_transverse >= 1.0:  # below, the stage is outside the method (a rating_out_of_range warning)
        assert r.K_Halpha <= st_.contact_ratio_total / (st_.contact_ratio_transverse * r.Z_eps ** 2) + 1e-12
        assert r.K_Falpha <= st_.contact_ratio_total / (0.25 * st_.contact_ratio_transverse + 0.75) + 1e-12
        assert r.Z_eps <= 1.0 + 1e-12
    else:
        assert any(d.code == "rating_out_of_range" for d in result.diagnostics)
    for m in (r.pinion, r.gear):
        assert m.Z_BD >= 1.0 and m.S_H > 0.0 and m.S_F > 0.0
        assert 0.85 - 1e-12 <= m.Z_NT <= 1.6 and 0.85 - 1e-12 <= m.Y_NT <= 2.5
        assert m.sigma_H_MPa >= r.sigma_H_MPa and m.sigma_F_MPa >= m.sigma_F0_MPa * 0.75  # K_v ≥ 0.75 (supercritical)
