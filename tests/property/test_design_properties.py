"""Invariants of the design calculation over random feasible trains (hypothesis).

The strategy draws 1–4 stages with 14–120 teeth and modest profile shifts (x_pinion ∈ [0, 0.5],
x_gear ∈ [−0.3, 0.5]), which always mesh; warnings may occur and are irrelevant here.
"""

from __future__ import annotations

import copy
import math

from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

PROPERTY_SETTINGS = settings(max_examples=60, deadline=None)


def shifts(lo: float, hi: float):
    """Profile shifts in [lo, hi]: 0, or a magnitude of at least 1e-6 (the design file refuses a nonzero shift
    below that, a subnormal included: docs/design-file.md)."""
    return st.floats(lo, hi).map(lambda x: x if abs(x) >= 1e-6 else 0.0)


@st.composite
def stages(draw, with_shift=True):
    beta = draw(st.one_of(st.just(0.0), st.floats(5.0, 30.0)))
    m_n = draw(st.sampled_from([1.0, 2.0, 3.0, 5.0, 8.0, 12.0]))
    hands = ("left", "right") if draw(st.booleans()) else ("right", "left")

    def gear(teeth, shift, hand):
        g = {"teeth": teeth, "face_width_mm": m_n * draw(st.floats(6.0, 20.0)), "profile_shift": shift}
        return {**g, "hand": hand} if beta > 0 else g
    return {
        "normal_module_mm": m_n,
        "normal_pressure_angle_deg": draw(st.floats(15.0, 25.0)),
        "helix_angle_deg": beta,
        "efficiency": draw(st.one_of(st.just(1.0), st.floats(0.9, 1.0))),
        "pinion": gear(draw(st.integers(14, 40)), draw(shifts(0.0, 0.5)) if with_shift else 0.0, hands[0]),
        "gear": gear(draw(st.integers(14, 120)), draw(shifts(-0.3, 0.5)) if with_shift else 0.0, hands[1]),
    }


@st.composite
def designs(draw):
    return {
        "stage": draw(st.lists(stages(), min_size=1, max_size=4)),
        "input": {"speed_rpm": draw(st.floats(10.0, 3000.0))},
        "load": {"torque_Nm": draw(st.floats(-5000.0, 5000.0).filter(lambda t: abs(t) > 1e-3))},
    }


def run(doc):
    return compute_design(DesignFile.model_validate(doc))


@PROPERTY_SETTINGS
@given(designs())
def test_total_ratio_is_the_product_and_the_speed_ratio(doc):
    r = run(doc)
    product = math.prod(s["gear"]["teeth"] / s["pinion"]["teeth"] for s in doc["stage"])
    assert_allclose(r.total_ratio, product, rtol=1e-12)  # rounding of a product of ≤ 4 quotients
    assert_allclose(r.input_speed_deg_s / r.output_speed_deg_s, r.total_ratio, rtol=1e-12)
    assert_allclose(math.prod(s.ratio for s in r.stages), r.total_ratio, rtol=1e-12)


@PROPERTY_SETTINGS
@given(designs())
def test_power_is_conserved_without_losses_and_never_created_with_them(doc):
    r = run(doc)
    power = [sh.torque_Nmm * sh.speed_deg_s for sh in r.shafts]  # ∝ T ω, same factor on every shaft
    etas = math.prod(s.efficiency for s in r.stages)
    p_in, p_out = power[0], power[-1]
    if r.output_torque_Nmm >= 0:  # power flows in at the input: P_out = P_in Π η
        assert_allclose(p_out, p_in * etas, rtol=1e-11)
    else:  # load reversal, power flows back: P_in = P_out Π η
        assert_allclose(p_in, p_out * etas, rtol=1e-11)
    assert p_in - p_out >= -1e-9 * abs(p_in)  # the losses are never negative
    if etas == 1.0:
        assert_allclose(power, p_in, rtol=1e-11)  # the same power on every shaft


@PROPERTY_SETTINGS
@given(designs(), st.floats(1e-3, 4.0))
def test_static_forces_scale_linearly_with_the_load(doc, scale):
    # a positive factor only: with η < 1 a reversed load takes its loss on the other side of each mesh
    # (T_p = T_g η / i instead of T_g / (i η)), so a sign change is not a pure scaling
    scaled = copy.deepcopy(doc)
    scaled["load"]["torque_Nm"] *= scale
    for a, b in zip(run(doc).stages, run(scaled).stages, strict=True):
        fa, fb = a.static_force_N, b.static_force_N
        assert_allclose([fb.tangential, fb.radial, fb.axial, fb.normal],
                        [scale * fa.tangential, scale * fa.radial, scale * fa.axial, scale * fa.normal], rtol=1e-11)
        assert_allclose(b.pinion.torque_Nmm, scale * a.pinion.torque_Nmm, rtol=1e-11)
        # and the force triangle: F_r = F_t tan α_t, F_a = F_t tan β
        assert_allclose(fa.radial, fa.tangential * math.tan(math.radians(a.transverse_pressure_angle_deg)),
                        rtol=1e-12)
        assert_allclose(fa.axial, fa.tangential * math.tan(math.radians(a.helix_angle_deg)), rtol=1e-12, atol=0)


@PROPERTY_SETTINGS
@given(designs(), st.floats(0.25, 4.0))
def test_overlap_ratio_is_proportional_to_face_width_and_epsilon_alpha_is_not(doc, scale):
    wider = copy.deepcopy(doc)
    for stage in wider["stage"]:
        for part in ("pinion", "gear"):
            stage[part]["face_width_mm"] *= scale
    for a, b in zip(run(doc).stages, run(wider).stages, strict=True):
        assert_allclose(b.overlap_ratio, scale * a.overlap_ratio, rtol=1e-12)
        assert_allclose(b.face_width_mm, scale * a.face_width_mm, rtol=1e-15)
        assert_allclose(b.contact_ratio_transverse, a.contact_ratio_transverse, rtol=1e-15)


@PROPERTY_SETTINGS
@given(stages(with_shift=False), st.sampled_from(["pinion", "gear"]), st.integers(1, 30))
def test_transverse_contact_ratio_grows_with_the_tooth_count(stage, part, extra):
    # zero profile shift: a longer path of contact per base pitch with more teeth on either member
    def eps(s):
        return run({"stage": [s], "input": {"speed_rpm": 100.0}, "load": {"torque_Nm": 10.0}}).stages[0]
    more = copy.deepcopy(stage)
    more[part]["teeth"] += extra
    a, b = eps(stage), eps(more)
    assert b.contact_ratio_transverse > a.contact_ratio_transverse
    # the base pitch is common to both members: π d_b1 / z1 = π d_b2 / z2 = p_bt
    assert_allclose([math.pi * a.pinion.base_diameter_mm / a.pinion.teeth,
                     math.pi * a.gear.base_diameter_mm / a.gear.teeth], a.transverse_base_pitch_mm, rtol=1e-13)
